#pragma once
// Streaming writer of leaf cells and one field's values as an ExaBrick pair (.cells: 16-byte
// Cell records; .scalars: one float32 per cell, same order), the layout writeExaBrick writes.
// Cells are buffered in chunks of kChunkCells, so memory stays bounded whatever the count.
// Both files are AtomicFileWriters: nothing appears under the final names before commit(), and a
// writer destroyed without commit() leaves no file behind.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "amr/model.h"
#include "core/file_io.h"

namespace amrvk::amr {

class CellsWriter {
public:
    static constexpr size_t kChunkCells = size_t{1} << 20;  // cells buffered before a write

    CellsWriter(const std::filesystem::path& cellsPath, const std::filesystem::path& scalarsPath);

    void write(const Cell& c, float value) {
        mCells.push_back(c);
        mValues.push_back(value);
        if (mCells.size() == kChunkCells) flush();
    }
    // Writes what is buffered and moves both files into place; returns the bytes of both.
    uint64_t commit();

private:
    void flush();

    AtomicFileWriter mCellsOut, mScalarsOut;
    std::vector<Cell> mCells;  // one chunk of 16-byte records
    std::vector<float> mValues;
};

}  // namespace amrvk::amr
