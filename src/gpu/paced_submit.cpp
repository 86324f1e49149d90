#include "gpu/paced_submit.h"

#include <vector>

namespace amrvk::gpu {

PacedResult submitPaced(Context& ctx, GpuDeadline& deadline, const PacedWork& work) {
    PacedResult result;
    // A fixed --gpu-timeout ignores the deadline: one submission.
    const std::vector<GpuDeadline::Part> parts =
        ctx.adaptiveTimeout() ? deadline.submissions(work.groups, kProbeGroups)
                              : std::vector<GpuDeadline::Part>{{0, work.groups}};
    for (const GpuDeadline::Part& part : parts) {
        const AdaptiveWait wait{.limitSeconds = deadline.limit(part.count),
                                .quietSeconds = deadline.floorSeconds(),
                                .progress = work.progress,
                                .stillText = work.stillText};
        const double wall = ctx.submitAndWait(
            [&](VkCommandBuffer cmd) {
                uint32_t scope = 0;
                if (work.timer) {
                    work.timer->reset(cmd);
                    scope = work.timer->begin(cmd);
                }
                work.record(cmd, uint32_t(part.first), uint32_t(part.count), part.first == 0);
                if (work.timer) work.timer->end(cmd, scope);
            },
            work.what, wait);
        deadline.record(wall, part.count);
        result.wallSeconds += wall;
        if (work.timer) result.gpuSeconds += work.timer->seconds();
        ++result.submissions;
    }
    return result;
}

}  // namespace amrvk::gpu
