#pragma once
// How long one submission of GPU work may run before amrvk calls it a runaway, under the default
// --gpu-timeout 0 (adaptive). A dispatch cannot be cancelled once it runs, so the limit is set
// before it starts: kMargin x the slowest pace measured since the work last changed (wall seconds
// per unit of work, submit to fence, so the submission's overhead and a loaded machine count) x the
// submission's units, and never under the floor. Units are paths for path tracing, workgroups of a
// 1-D dispatch for the staged data-parallel pass and the majorants (gpu/paced_submit.h). Before any
// measurement only the floor holds: the first submission after a change is a small probe (spread
// over the whole image in render/path_trace_pass.cpp; submissions() otherwise). Past the limit the
// work is cut only once its progress count (where it has one) has stood still for the floor's time
// (gpu::AdaptiveWait), so a shader that loops forever ends after the floor, while an honest
// submission, however slow its paths, ends unless one wave of paths outlasts the floor.
#include <cstdint>
#include <vector>

namespace amrvk {

class GpuDeadline {
public:
    static constexpr double kMargin = 32;        // x the slowest measured seconds per path
    static constexpr double kFloorSeconds = 10;  // no limit is shorter
    // The floor is kFloorSeconds, or AMRVK_TEST_GPU_TIMEOUT_FLOOR seconds where that is set (tests:
    // a short floor shows that honest submissions longer than it are not cut).
    GpuDeadline();
    explicit GpuDeadline(double floorSeconds);
    // The work changed (settings, scene, shaders): the paces measured so far no longer hold.
    void reset() { mSecondsPerPath = 0; }
    bool measured() const { return mSecondsPerPath > 0; }
    // The limit in seconds for a submission of `paths` paths (or other units of work; > 0).
    double limit(uint64_t paths) const;
    // A submission of `paths` paths finished after `seconds` of wall time.
    void record(double seconds, uint64_t paths);
    // How to split `work` units into submissions, as {first, count}: all at once where a pace is
    // measured; else a probe of `probe` units (the floor is its only limit), then 4x more per
    // submission, each held to the pace measured before it. Covers [0, work) in order.
    struct Part {
        uint64_t first, count;
    };
    std::vector<Part> submissions(uint64_t work, uint64_t probe) const;
    double floorSeconds() const { return mFloor; }

private:
    double mFloor;
    double mSecondsPerPath = 0;  // the slowest pace measured since reset(); 0 = none
};

}  // namespace amrvk
