#pragma once
// The GPU renderer: one API for `amrvk render`, `bench`, the viewer and every other front end,
// taking incremental edits. It owns its structures: a VolumeScene over a shared, immutable
// scene::Volume, configured only through setStructure(), so the device copy always matches the
// configuration it renders with. It joins three parts, each in its own file pair:
//   DeviceScene   the device copy of the scene's TF-independent structures (one combination)
//   MajorantPass  the TF, majorants, culled traversal hierarchy and kd-tree (per TF)
//   PathTracePass pipelines, accumulation and counters (per sample)
// and composes the RenderParams buffer from their blocks. Every edit is applied through
// scene::invalidatedBy (scene/invalidation.h), the one rule of what depends on what, and
// redoes exactly what it lists (counted in UpdateCounts).
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/shader_library.h"
#include "render/device_scene.h"
#include "render/majorant_pass.h"
#include "render/path_trace_pass.h"
#include "render/staged_pass.h"
#include "scene/invalidation.h"
#include "scene/render_output.h"
#include "scene/render_settings.h"
#include "scene/transfer_function.h"
#include "scene/volume_scene.h"
#include "shared/render_params.h"

namespace amrvk::render {

// How often each part was redone since construction: the invalidation rule made observable, one
// counter per field of scene::Invalidation.
struct UpdateCounts {
    uint64_t deviceScenes = 0;         // device copies of the TF-independent structures
    uint64_t majorantDispatches = 0;   // majorant passes over every structure (culling, kd-tree with them)
    uint64_t accumulationResets = 0;
    uint64_t accumulationBuffers = 0;  // (re)allocations of the accumulation buffer
    uint64_t viewWrites = 0;           // ViewGpu rewritten
    uint64_t shadingWrites = 0;        // ShadingGpu rewritten
    uint64_t pipelineDrops = 0;        // every pipeline dropped or replaced (structure, shaders)
    uint64_t pipelinesCompiled = 0;    // path-trace pipelines created
};

// Edits gathered to be committed at once (as Open VKL commits an object): every part given is
// taken, and what their union invalidates (scene/invalidation.h) is redone once, so a session's
// structure, TF and settings cost one device copy and one majorant pass.
struct Edit {
    std::optional<scene::StructureConfig> structure;  // back-end resolved
    std::optional<scene::TransferFunction> tf;        // linear colours, as rendered
    std::optional<scene::RenderSettings> settings;
};

class Renderer {
public:
    // Builds the structures of `config` (back-end resolved: Sw or Rq) over `volume` and uploads
    // them (and only those). Shaders come from `shaders` (default: the embedded ones).
    Renderer(gpu::Context& ctx, std::shared_ptr<const scene::Volume> volume, const scene::StructureConfig& config,
             gpu::ShaderLibrary shaders = {});
    // Its passes refer to its own scene and shader library: neither copied nor moved.
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // ---- Edits (each resets the accumulation; what else it redoes is in scene/invalidation.h) ----
    // The parts of `e`, committed at once: checked first (a TF with no nodes, invalid settings:
    // nothing changes); the structure built next (on a failure its error is thrown, the previous
    // combination rebuilt and nothing of `e` taken); then the union of what they invalidate redone
    // once. The setters below are commits of one part.
    void commit(const Edit& e);
    // Another combination (back-end resolved): host structures built or freed, a new device copy
    // (the old one freed first), the majorants of the current TF, new pipelines. Equal configs
    // change nothing. When a build fails (e.g. the dense grid over its limit) the error is thrown
    // and the previous combination is rebuilt and stays in use.
    void setStructure(const scene::StructureConfig& config);
    // New TF: TF nodes, majorants, culling, kd-tree. Nothing TF-independent is touched.
    void setTransferFunction(const scene::TransferFunction& tf);
    // Camera, image size, seed, mode, lighting, medium and dvr options: applies only what differs
    // from the current settings (nothing at all when they are equal). Throws a one-line error for
    // an invalid value, leaving the current settings in place.
    void setSettings(const scene::RenderSettings& settings);
    void setCamera(const scene::Camera& camera);
    // Takes shaders from `shaders` from now on: recompiles the pipeline in use (before setSettings:
    // at the first accumulate); on a compile error throws, and the previous pipelines and library
    // stay. reloadShaders() does it again from the current library (a file in it was edited).
    void setShaders(gpu::ShaderLibrary shaders);
    // Takes the path tracer of `mode` for the current structures, compiled by warmPathTracer while
    // they were built; a pipeline that failed to compile is left for the first accumulate to
    // compile again (and report).
    void adoptPathTracer(TracerVariant variant, std::future<gpu::ComputePipeline>& warm);
    void reloadShaders() { setShaders(mShaders); }
    void resetAccumulation();
    // Numbers (and seeds) the samples of the next accumulation from `first` on: a sample-parallel
    // rank renders a range of the sample indices one process would (resets the accumulation).
    void setFirstSample(uint32_t first);

    // ---- Accumulation ----
    // Adds `spp` samples per pixel to the current image; progress(done, spp) after each batch.
    void accumulate(uint32_t spp, const std::function<void(uint32_t, uint32_t)>& progress = {},
                    uint32_t maxBatch = 64);
    // Adds `spp` samples per pixel in stages (render/staged_pass.h): the same estimators with
    // tracking cut to staged's box of space, each result agreed with the other owners of space
    // through staged.exchange. What data-parallel MPI ranks render with; modes ae, ss and ms.
    StagedReport accumulateStaged(const StagedRender& staged, uint32_t spp,
                                  const std::function<void(uint32_t, uint32_t)>& progress = {});
    uint32_t accumulatedSpp() const { return mPathTrace.spp(); }
    // A time-budgeted tile: traces the next `rows` rows of the current sample (the viewer, so one
    // frame never waits for a whole sample). Returns the GPU seconds; rowsDone() tells how far.
    double accumulateRows(uint32_t rows);
    uint32_t rowsDone() const { return mPathTrace.rowsDone(); }
    // The accumulation buffer (shared::AccumPixelGpu per pixel: double-float sum with the count in
    // w, and sum of squares) at the current image size, for the display pass.
    uint64_t accumulationAddress() const { return mPathTrace.accumAddress(); }
    // The image so far: mean, sums of squares, spp and the counters of every path in it.
    scene::RenderOutput output() const { return mPathTrace.read(); }
    // The double sums behind output() (what ranks add up).
    scene::AccumulatedSums sums() const { return mPathTrace.readSums(); }
    // Adds another renderer's sums of n samples at this size, with their statistics (the MPI
    // viewer's rank 0: the other ranks' samples of each pass; their indices kept apart by the
    // caller, mpi/view_link.h).
    void addSums(const scene::AccumulatedSums& add, uint32_t n, const scene::RenderStats& stats) {
        mPathTrace.addSums(add, n, stats);
    }
    // The counters and GPU time of every path in the current image (no download).
    const scene::RenderStats& stats() const { return mPathTrace.stats(); }
    // One image from scratch: setSettings, reset, accumulate `spp`. `snapshot(out)` additionally
    // sees the image at each sample count in `snapshotSpp` (ascending; downloads are not timed).
    scene::RenderOutput render(const scene::RenderSettings& settings, uint32_t spp,
                               const std::function<void(uint32_t, uint32_t)>& progress = {},
                               const std::vector<uint32_t>& snapshotSpp = {},
                               const std::function<void(const scene::RenderOutput&)>& snapshot = {});

    // ---- State and statistics ----
    const scene::StructureConfig& config() const { return mScene.config(); }
    const scene::VolumeScene& scene() const { return mScene; }
    const scene::Volume& volume() const { return mScene.volume(); }
    const gpu::ShaderLibrary& shaders() const { return mShaders; }
    gpu::Context& context() const { return mCtx; }
    const scene::RenderSettings& settings() const { return mSettings; }
    UpdateCounts updateCounts() const {
        UpdateCounts c = mCounts;
        c.pipelinesCompiled = mPathTrace.pipelinesCompiled();
        return c;
    }
    // GPU seconds of the last majorant pass (+ AABB pass and BLAS build for rq).
    double majorantSeconds() const { return mMajorants->gpuSeconds(); }
    // Host seconds of the last TF update spent on TF-dependent structures (kd-tree, sw culling BVH).
    double structureUpdateSeconds() const { return mMajorants->hostSeconds(); }
    double kdTreeBuildSeconds() const { return mMajorants->kdTreeSeconds(); }
    // Traversal boxes (macrocells for grid-bvh) whose range can reach alpha > 0 under the TF.
    uint64_t activeTraversalBoxes() const { return mMajorants->activeBoxes(); }
    const std::vector<uint8_t>& activeTraversalMask() const { return mMajorants->activeMask(); }
    // Host bytes of the TF-dependent structures (the scene reports the rest).
    std::vector<std::pair<std::string, uint64_t>> hostBytes() const { return mMajorants->hostBytes(); }
    // The traversal boxes (local voxel space) of abr | brick | ext-brick | kdtree (under the last TF).
    const std::vector<shared::AabbGpu>& traversalBoxes() const { return mMajorants->traversalBoxes(); }
    std::vector<float> downloadMajorants() const { return mMajorants->downloadGridMajorants(); }
    std::vector<float> downloadDomainMajorants() const { return mMajorants->downloadDomainMajorants(); }
    // grid-dda's block majorants (empty without blocks), blocks of 2^gridBlockShift macrocells.
    std::vector<float> downloadBlockMajorants() const { return mMajorants->downloadBlockMajorants(); }
    const MajorantPass& majorantPass() const { return *mMajorants; }
    // With settings().controlExtinction minorant: "" when the trackers use the minorants, else why
    // not (MajorantPass::setMinorants; they then track without a control, as with none).
    const std::string& controlExtinctionOff() const { return mMinorantsOff; }
    std::vector<float> downloadMinorants() const { return mMajorants->downloadGridMinorants(); }
    // Whether grid-dda crosses empty blocks (default Auto: where enough are empty under the TF);
    // kept across structure changes. The walk changes no expectation: accumulation goes on.
    void setGridBlockUse(MajorantPass::GridBlockUse use);
    // grid-bvh: culled macrocells in a row stepped before one box query (>= 1; default
    // accel::kGridBvhQueryAfter); kept across structure changes. Changes no expectation.
    void setGridBvhQueryAfter(uint32_t culledSteps);
    // Overwrites the macrocell majorants (grid-dda only; tests: deliberate overestimates).
    void overrideMajorants(const std::vector<float>& majorants);
    // Tests: every collision a sub-majorant decides is looked up too, and an extinction above the
    // sub-majorant counted as a majorant violation (kept across structure changes).
    void setSubMajorantCheck(bool on);
    // Overwrites every sub-box's q (0..255) under the current TF (tests: deliberate underestimates).
    void overrideSubMajorants(uint32_t q);
    // Sub-majorants built on another thread after a TF edit (the viewer: an edit does not wait for
    // them); the accumulation calls take them when ready, without a reset (they change no
    // expectation). Off (the default): built within setTransferFunction. render() waits for them.
    void setSubMajorantsInBackground(bool on);
    // Takes a background build's sub-majorants once it finished (true when they came in).
    bool waitForSubMajorants();
    // Device address of the RenderParams buffer (current after any edit), for test kernels.
    uint64_t paramsAddress();

private:
    // Redoes what `inv` lists (the only place an edit takes effect).
    void redo(const scene::Invalidation& inv, const scene::RenderSettings* settings = nullptr);
    // The scene's host structures for `config`; on a failure the previous ones are built again
    // (or mBroken says why not) and the error is thrown.
    void configure(const scene::StructureConfig& config);
    void buildDeviceScene();
    void takeMajorantParams();  // the majorant pass's params into RenderParams, to upload
    void requireRenderable() const;  // structures, a TF and settings exist
    const gpu::ComputePipeline& currentPipeline();  // compiled on first use; params uploaded
    void writeView(const scene::RenderSettings& s);
    void writeShading(const scene::RenderSettings& s);
    void uploadParams();

    gpu::Context& mCtx;
    gpu::ShaderLibrary mShaders;
    scene::VolumeScene mScene;
    std::unique_ptr<DeviceScene> mDevice;
    std::unique_ptr<MajorantPass> mMajorants;
    PathTracePass mPathTrace;
    gpu::Buffer mParamsBuffer;
    shared::RenderParams mParams{};
    bool mParamsDirty = true;
    MajorantPass::GridBlockUse mGridBlockUse = MajorantPass::GridBlockUse::Auto;
    uint32_t mGridBvhQueryAfter = 0;  // 0: the device scene's default
    bool mSubMajorantCheck = false;
    bool mSubInBackground = false;
    bool mMinorantsWanted = false;  // settings' controlExtinction is minorant (kept across structure changes)
    std::string mMinorantsOff;      // why they are not made though wanted
    void adoptSubMajorants();  // a finished background build into the params
    std::optional<scene::TransferFunction> mTf;
    scene::RenderSettings mSettings;
    bool mHasSettings = false;
    std::string mBroken;  // non-empty: a failed structure change left no usable structures (why)
    UpdateCounts mCounts;
};

// Compiles the path tracer of (mode, config) from `shaders` on another thread, so that it is ready
// when the structures of config are (Renderer::adoptPathTracer): on a JIT driver (lavapipe) the
// compile is about 0.5 s of one core, the first sample's last serial stretch. config's back-end is
// resolved.
std::future<gpu::ComputePipeline> warmPathTracer(gpu::Context& ctx, TracerVariant variant,
                                                 const scene::StructureConfig& config,
                                                 const gpu::ShaderLibrary& shaders);

}  // namespace amrvk::render
