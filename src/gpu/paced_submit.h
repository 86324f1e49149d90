#pragma once
// A 1-D dispatch of known size under the adaptive --gpu-timeout (core/gpu_deadline.h): where no
// pace is measured yet it runs in parts, a probe of kProbeGroups workgroups first (the floor is its
// only limit), then 4x more per submission, each held to the pace measured before it; once
// measured, in one submission. Used by the staged data-parallel pass (path_trace_dp.comp) and the
// majorants (majorants.comp, domain_aabbs.comp), whose runaways would otherwise wait 600 s. Under
// a fixed --gpu-timeout S it is one submission held to S.
#include <cstdint>
#include <functional>
#include <string>

#include "core/gpu_deadline.h"
#include "gpu/compute_pipeline.h"
#include "gpu/context.h"

namespace amrvk::gpu {

struct PacedWork {
    uint64_t groups = 0;  // workgroups of the whole dispatch
    // Records workgroups [first, first + count) (ComputePipeline::dispatchPart); `opening`: the
    // first submission of this work (e.g. zero its counters there).
    std::function<void(VkCommandBuffer cmd, uint32_t first, uint32_t count, bool opening)> record;
    std::string what;  // names the work in the runaway line (the pipeline's name)
    // Where set: a count that changes while the work is alive (AdaptiveWait::progress); past its
    // limit a submission is then cut only once it stood still for the floor's time.
    std::function<uint64_t()> progress;
    std::string stillText = "with no progress";  // AdaptiveWait::stillText
    GpuTimer* timer = nullptr;  // where set: each submission in one scope of it
};

struct PacedResult {
    double wallSeconds = 0, gpuSeconds = 0;  // gpuSeconds: from `timer`, where one was given
    uint32_t submissions = 0;
};

inline constexpr uint64_t kProbeGroups = 64;  // 4096 invocations of 64

// Runs the work (groups > 0) and records each submission's pace in `deadline`.
PacedResult submitPaced(Context& ctx, GpuDeadline& deadline, const PacedWork& work);

}  // namespace amrvk::gpu
