#pragma once
// The one entry from a picture description to pixels, below every front end (render, view,
// bench, the Python module, the MPI renderer): the data read (or given), the description fitted
// to it (session::resolvePicture: TF, camera, traversal), the back-end chosen for the device,
// --traversal auto probed, the structures built and a renderer ready with the TF and settings.
// Each fitted choice is reported once, the same way (Report::notes, and Options::note as it
// happens).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "render/auto_select.h"
#include "render/renderer.h"
#include "scene/tf_colors.h"
#include "session/picture_description.h"

namespace amrvk::picture {

struct Options {
    gpu::ShaderLibrary shaders;                                // --shader-dir (default: embedded)
    std::function<void(const std::string&)> note;              // each fitted choice, one line, as it is made
    std::function<void(const std::string&)> probe;             // --traversal auto: each probe as it starts
    // The mode and shadow estimator of the first accumulation, whose path tracer compiles on
    // another thread while the structures are built (render::warmPathTracer); none: compiled at
    // the first accumulate.
    std::optional<render::TracerVariant> warmTracer;
};

struct Report {
    std::vector<std::string> notes;       // fitted traversal, back-end, auto's pick: one line each
    std::string backendReason;            // why --backend auto chose what it chose (empty when given)
    std::optional<render::AutoChoice> autoChoice;  // StructureFit::Probe
    double readSeconds = 0;               // reading and per-cell validation (set by the front end that read)
    double buildSeconds = 0;              // bricks and the structures of the combination (host)
};

// Edits of a picture gathered to be committed at once (Picture::commit; the renderer redoes the
// union of what they invalidate once). Every part given is taken.
struct PictureEdit {
    std::optional<scene::TfChannels> tf;              // the TF's colours as given
    std::optional<scene::TfColors> tfColors;          // what they mean (--tf-colors)
    std::optional<scene::StructureConfig> structure;  // as requested: commit resolves it for the device
    std::optional<scene::RenderSettings> settings;
};

struct Picture {
    std::shared_ptr<const scene::Volume> volume;
    std::unique_ptr<render::Renderer> renderer;  // structures built, TF and settings applied
    Report report;

    // The session as rendered: the description fitted to the data, with the renderer's settings
    // (held once, by the renderer), the TF as its colour and opacity channels (the renderer holds
    // their merged function) and the structure as requested (the back-end unresolved; the renderer
    // holds the resolved combination).
    session::Session session() const;
    // The one way a picture changes: the parts of `e` applied to the renderer at once (a refused
    // edit changes nothing: validated and resolved first; a structure that fails to build is thrown
    // with the previous one kept), then recorded in `described`. The renderer gets the TF as
    // rendered (scene::albedoOf of its channels under the session's tfColors).
    void commit(const PictureEdit& e);
    // Commits of one part.
    void setTransferFunction(const scene::TfChannels& tf);
    // What the TF's colours mean (`--tf-colors`): the renderer's TF redone, the channels kept.
    void setTfColors(scene::TfColors colors);
    // Renders session().spp samples per pixel from scratch (progress(done, spp) after each batch).
    scene::RenderOutput render(const std::function<void(uint32_t, uint32_t)>& progress = {});
    // Renders from scratch until the image's noise (scene::meanRelativeError) is at most
    // `targetError`, or session().spp samples per pixel (the cap) are in; checks at
    // scene::kFirstNoiseCheckSpp and at each doubling (progress(done, cap) after each batch).
    // out.spp says how many it took.
    scene::RenderOutput renderUntil(double targetError, const std::function<void(uint32_t, uint32_t)>& progress = {});

    // The fitted description less its settings (Picture::session adds the renderer's); set by
    // makePicture, changed only by the edits above.
    session::Session described;
};

// The picture `d` describes over `volume`: the one door every front end opens a picture through.
// The volume is the front end's to make, as only it knows when and from what: session::loadVolume
// (render, view, bench, Python files), mpi::loadPart (a data-parallel rank's part) or
// scene::makeVolume over cells a caller made (Python arrays, yt).
Picture makePicture(gpu::Context& ctx, std::shared_ptr<const scene::Volume> volume,
                    const session::PictureDescription& d, Options options = {});

// Wall-clock times only the caller knows (0 when not measured).
struct RenderTimes {
    double wallSeconds = 0;         // the render call
    double firstSampleSeconds = 0;  // command start to the first finished batch
};
// The statistics of a render of `p` that produced `out`: what `amrvk render --json` writes and
// the Python module's Renderer.stats holds (keys in docs/architecture.md's order, every counter,
// timings, host bytes per structure, device bytes per buffer, the mean RGB).
nlohmann::ordered_json renderStats(const Picture& p, const scene::RenderOutput& out, const RenderTimes& times = {});

// `--traversal auto`'s probes and pick (render --json "auto", bench's results.json "auto"):
// pick, probeSize, probeSeconds, lookupNsAboveReference per sampler, and per probe its
// combination, grid, GPU seconds per spp, variance, efficiency, counts per path, whether it was
// predicted, its wall seconds and why it stopped.
nlohmann::ordered_json autoChoiceJson(const render::AutoChoice& c);

// What the back-end choice reads from a device.
scene::DeviceTraits deviceTraits(const gpu::Context& ctx);
// `requested` with its back-end resolved for ctx's device (scene::resolveBackend) and validated:
// what Renderer::setStructure takes. Throws a one-line error before anything is built.
scene::BackendChoice resolveStructure(const gpu::Context& ctx, scene::StructureConfig& requested);

}  // namespace amrvk::picture
