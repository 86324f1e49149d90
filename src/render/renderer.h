#pragma once
// The GPU renderer: one API for `amrvk render`, `bench` and the viewer, taking incremental edits.
// It joins three parts, each in its own file pair:
//   DeviceScene   the device copy of the scene's TF-independent structures (one combination)
//   MajorantPass  the TF, majorants, culled traversal hierarchy and kd-tree (per TF)
//   PathTracePass pipelines, accumulation and counters (per sample)
// and composes the RenderParams buffer from their blocks. Each edit invalidates only what depends
// on it (scene/invalidation.h): a camera move resets the accumulation and rewrites 64 bytes; a TF
// edit reruns the majorant pass; a structure change rebuilds the device copy. The scene is only
// read: whoever owns it configures it, then calls setStructure().
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/context.h"
#include "render/device_scene.h"
#include "render/majorant_pass.h"
#include "render/path_trace_pass.h"
#include "scene/invalidation.h"
#include "scene/render_output.h"
#include "scene/render_settings.h"
#include "scene/transfer_function.h"
#include "scene/volume_scene.h"
#include "shared/render_params.h"

namespace amrvk::render {

// How often each part was rebuilt since construction (the invalidation rule made observable).
struct UpdateCounts {
    uint64_t deviceScenes = 0;        // device copies of the TF-independent structures
    uint64_t majorantDispatches = 0;  // majorant passes over every structure
    uint64_t accumulationResets = 0;
    uint64_t pipelinesCompiled = 0;   // path-trace pipelines created
};

class Renderer {
public:
    // Uploads the structures of scene.config (and only those). The scene must outlive the renderer
    // and may change only through configure() followed by setStructure().
    Renderer(gpu::Context& ctx, const scene::VolumeScene& scene);

    // ---- Edits (each resets the accumulation; what else it redoes is in scene/invalidation.h) ----
    // The scene was configured for another combination: a new device copy, the majorants of the
    // current TF, new pipelines. Device memory of the old combination is freed first.
    void setStructure();
    // New TF: TF nodes, majorants, culling, kd-tree. Nothing TF-independent is touched.
    void setTransferFunction(const scene::TransferFunction& tf);
    // Camera, image size, seed, mode, lighting, medium and dvr options: applies only what differs
    // from the current settings (nothing at all when they are equal). Throws a one-line error for
    // an invalid value, leaving the current settings in place.
    void setSettings(const scene::RenderSettings& settings);
    void setCamera(const scene::Camera& camera);
    // Recompiles the pipelines in use from the shader library (e.g. after gpu::setShaderDirectory
    // and an edit); on a compile error throws and the previous pipelines keep running.
    void reloadShaders();
    void resetAccumulation();

    // ---- Accumulation ----
    // Adds `spp` samples per pixel to the current image; progress(done, spp) after each batch.
    void accumulate(uint32_t spp, const std::function<void(uint32_t, uint32_t)>& progress = {},
                    uint32_t maxBatch = 64);
    uint32_t accumulatedSpp() const { return mPathTrace.spp(); }
    // A time-budgeted tile: traces the next `rows` rows of the current sample (the viewer, so one
    // frame never waits for a whole sample). Returns the GPU seconds; rowsDone() tells how far.
    double accumulateRows(uint32_t rows);
    uint32_t rowsDone() const { return mPathTrace.rowsDone(); }
    // The accumulation buffer (vec4 sum with count in w, then sum of squares, per pixel) at the
    // current image size, for the display pass.
    uint64_t accumulationAddress() const { return mPathTrace.accumAddress(); }
    // The image so far: mean, sums of squares, spp and the counters of every path in it.
    scene::RenderOutput output() const { return mPathTrace.read(); }
    // The counters and GPU time of every path in the current image (no download).
    const scene::RenderStats& stats() const { return mPathTrace.stats(); }
    // One image from scratch: setSettings, reset, accumulate `spp`. `snapshot(out)` additionally
    // sees the image at each sample count in `snapshotSpp` (ascending; downloads are not timed).
    scene::RenderOutput render(const scene::RenderSettings& settings, uint32_t spp,
                               const std::function<void(uint32_t, uint32_t)>& progress = {},
                               const std::vector<uint32_t>& snapshotSpp = {},
                               const std::function<void(const scene::RenderOutput&)>& snapshot = {});

    // ---- State and statistics ----
    const scene::StructureConfig& config() const { return mScene.config; }
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
    // Overwrites the macrocell majorants (grid-dda only; tests: deliberate overestimates).
    void overrideMajorants(const std::vector<float>& majorants);
    // Device address of the RenderParams buffer (current after any edit), for test kernels.
    uint64_t paramsAddress();

private:
    void buildStructures();
    const gpu::ComputePipeline& currentPipeline();  // compiled on first use; params uploaded
    void writeView(const scene::RenderSettings& s);
    void writeShading(const scene::RenderSettings& s);
    void uploadParams();
    void changed();

    gpu::Context& mCtx;
    const scene::VolumeScene& mScene;
    std::unique_ptr<DeviceScene> mDevice;
    std::unique_ptr<MajorantPass> mMajorants;
    PathTracePass mPathTrace;
    gpu::Buffer mParamsBuffer;
    shared::RenderParams mParams{};
    bool mParamsDirty = true;
    std::optional<scene::TransferFunction> mTf;
    scene::RenderSettings mSettings;
    bool mHasSettings = false;
    UpdateCounts mCounts;
};

}  // namespace amrvk::render
