#pragma once
// What a front end asks for, before the data is read: a session (every field of the schema,
// docs/sessions.md) plus what is still to be fitted to the data. `amrvk render` and `view` make
// one from their options (a --session file fixes everything), `bench` one per reference render,
// the Python module and the MPI renderer from their arguments. resolvePicture() fits it to the
// data the same way for all of them; picture::makePicture (src/picture) turns the result into a
// ready renderer. Vulkan-free.
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "amr/readers.h"
#include "scene/volume.h"
#include "session/session.h"

namespace amrvk::session {

// A transfer function to load once the field's range is known.
struct TfSource {
    std::string name = "layers";  // a ParaView JSON or .xf file, or a preset (layers, ramp, spiky, ...)
    std::string preset;         // the preset inside a ParaView JSON file (empty: the first)
};

// How the structure combination is chosen.
enum class StructureFit : uint8_t {
    None,   // as session.structure says
    Data,   // the traversal that fits the data (scene::fittingTraversal) and, unless given, its sampler
    Probe,  // --traversal auto: probe every allowed combination (render::autoSelect)
};

struct PictureDescription {
    Session session;                  // data source, read options, field, settings, spp, structure, TF
    std::optional<TfSource> tfSource;  // set: the TF comes from here (session.tf is ignored)
    // Map the TF's node range (tfSource's or the session's) onto [lo, hi]: presets take their
    // range-fixed shape there (scene::makePreset(name, lo, hi)). Without it and dataRange, presets
    // are fitted to the data (scene::makePreset(name, percentiles): spiky and foggy over the
    // field's percentiles, the others over its range) and other TFs keep their positions.
    std::optional<std::pair<float, float>> tfRange;
    // The field range presets are laid over, in their range-fixed shape, instead of the volume's
    // own distribution (tfRange still wins): one TF for every output of a time series of several
    // outputs (render --series-range), whose percentiles differ from output to output.
    std::optional<std::pair<float, float>> dataRange;
    // The distribution presets are fitted to instead of the volume's own (tfRange and dataRange
    // still win): a time series' cells, all of its outputs' pooled (amr::pooledPercentiles,
    // amr::pooledVolumeHistograms) or the first output's, so that every frame gets one TF that
    // follows the series' values. spiky and foggy are laid over these percentiles, layers over the
    // histogram (none: its range-fixed shape over [P0, P100], the series' range, as for the other
    // presets).
    std::optional<amr::Percentiles> dataPercentiles;
    std::optional<amr::VolumeHistogram> dataHistogram;  // with dataPercentiles only
    bool fitCamera = false;           // frame the data with the default view (session fov kept)
    StructureFit fit = StructureFit::None;
    // The structure settings the front end was given, by their session key in settingTable()
    // ("sampler", "backend", "grid", "subMajorants"): what Data and Probe keep (Probe: the
    // constraints; Data: the sampler).
    std::set<std::string, std::less<>> given;
    bool isGiven(std::string_view key) const { return given.count(key) > 0; }
};

// Reads the data a session names (its input, read options and field; only that field is loaded
// when one is named) and makes the volume every picture of it shares. Progress on stderr.
std::shared_ptr<const scene::Volume> loadVolume(const Session& s, const scene::VolumeOptions& options = {});

// `d` fitted to `volume`: the field named, the TF loaded (tfSource; a fitted spiky or foggy notes
// the percentiles it was laid over), the camera framed
// (fitCamera), the traversal fitted (StructureFit::Data); one line per fitted choice in `notes`.
// Probe is left to picture::makePicture (it needs a device). Throws one-line errors (a TF file
// that does not load, --tf-range LO >= HI, an invalid structure combination).
Session resolvePicture(const PictureDescription& d, const scene::Volume& volume, std::vector<std::string>* notes);

// The `amrvk render` command line that renders the picture `d` describes (`renderer` the amrvk
// to call): the read options, the TF as d.tfSource or, without one, as `tfFile` (a ParaView JSON
// file of session.tf the caller writes), the camera unless fitCamera, every setting, spp and the
// structure (its back-end as given). What the viewer's "copy as command" and the bench's
// reference records write; the bench's reference cache key is this text too.
std::string renderCommandLine(const PictureDescription& d, const std::string& tfFile, const std::string& output,
                              const std::string& renderer = "amrvk");
// A session's picture (everything given, the TF in tfFile).
std::string renderCommandLine(const Session& s, const std::string& tfFile, const std::string& output);

}  // namespace amrvk::session
