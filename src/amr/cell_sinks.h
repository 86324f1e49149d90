#pragma once
// Where the leaves of a depth-first pass over a synthetic field go (amr/octree_refine.h): counted
// block by block, kept in memory, or streamed to disk. Every sink counts cells, reports progress
// each time the count passes a multiple of 65536, and stops the pass once the count exceeds its
// cap (stopped(): the count is then a lower bound).
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "amr/cells_writer.h"
#include "amr/model.h"
#include "amr/synthetic.h"

namespace amrvk::amr {

// Called with the phase name and its estimated completed fraction in [0, 0.99].
using ProgressFn = std::function<void(std::string_view, double)>;

class SinkBase {
public:
    static constexpr bool kCountsOnly = false;  // true: takes whole blocks via countBlock()

    // expected: the count that means "done" for progress; progress may be null or empty.
    SinkBase(uint64_t cap, uint64_t expected, const ProgressFn* progress, std::string phase);
    bool stopped() const { return mCount > mCap; }
    uint64_t count() const { return mCount; }  // cells

protected:
    void counted(uint64_t cells = 1) {
        const uint64_t before = mCount;
        mCount += cells;
        if ((before >> 16) != (mCount >> 16) && mProgress && *mProgress) reportProgress();
    }

private:
    void reportProgress() const;

    uint64_t mCount = 0;
    uint64_t mCap, mExpected;
    const ProgressFn* mProgress;
    std::string mPhase;
};

// Counts whole blocks without visiting their cells (threshold search passes).
class CountSink : public SinkBase {
public:
    static constexpr bool kCountsOnly = true;
    using SinkBase::SinkBase;
    void countBlock(uint64_t cells) { counted(cells); }
};

// Takes every cell and keeps the cell count per level for SyntheticStats.
class CellSink : public SinkBase {
public:
    using SinkBase::SinkBase;
    // Sets stats.cells, minLevel, maxLevel and cellsPerLevel from the cells taken.
    void fillStats(SyntheticStats& stats) const;

protected:
    void record(const Cell& c) {
        counted();
        mPerLevel[static_cast<size_t>(c.level)]++;
    }

private:
    std::array<uint64_t, kMaxLevel + 1> mPerLevel{};
};

// Keeps the cells and values in memory.
class MemorySink : public CellSink {
public:
    MemorySink(uint64_t cap, uint64_t expected, const ProgressFn* progress);
    void emit(const Cell& c, float v) {
        record(c);
        mCells.push_back(c);
        mValues.push_back(v);
    }
    CellArray takeCells() { return std::move(mCells); }
    std::vector<float> takeValues() { return std::move(mValues); }

private:
    CellArray mCells;
    std::vector<float> mValues;
};

// Streams the cells and values to a .cells / .scalars pair (CellsWriter); kept only by commit().
class FileSink : public CellSink {
public:
    FileSink(const std::filesystem::path& cellsPath, const std::filesystem::path& scalarsPath, uint64_t cap,
             uint64_t expected, const ProgressFn* progress);
    void emit(const Cell& c, float v) {
        record(c);
        mWriter.write(c, v);
    }
    // Moves both files into place; returns the bytes written.
    uint64_t commit() { return mWriter.commit(); }

private:
    CellsWriter mWriter;
};

}  // namespace amrvk::amr
