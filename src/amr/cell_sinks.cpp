#include "amr/cell_sinks.h"

#include <algorithm>
#include <utility>

namespace amrvk::amr {

SinkBase::SinkBase(uint64_t cap, uint64_t expected, const ProgressFn* progress, std::string phase)
    : mCap(cap), mExpected(std::max<uint64_t>(expected, 1)), mProgress(progress), mPhase(std::move(phase)) {}

void SinkBase::reportProgress() const {
    (*mProgress)(mPhase, std::min(0.99, static_cast<double>(mCount) / static_cast<double>(mExpected)));
}

void CellSink::fillStats(SyntheticStats& stats) const {
    stats.cells = count();
    levelRange(mPerLevel, stats.minLevel, stats.maxLevel, stats.cellsPerLevel);
}

MemorySink::MemorySink(uint64_t cap, uint64_t expected, const ProgressFn* progress)
    : CellSink(cap, expected, progress, "generating") {}

FileSink::FileSink(const std::filesystem::path& cellsPath, const std::filesystem::path& scalarsPath,
                   uint64_t cap, uint64_t expected, const ProgressFn* progress)
    : CellSink(cap, expected, progress, "writing"), mWriter(cellsPath, scalarsPath) {}

}  // namespace amrvk::amr
