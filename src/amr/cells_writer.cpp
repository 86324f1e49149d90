#include "amr/cells_writer.h"

#include <span>

namespace amrvk::amr {

CellsWriter::CellsWriter(const std::filesystem::path& cellsPath, const std::filesystem::path& scalarsPath)
    : mCellsOut(cellsPath), mScalarsOut(scalarsPath) {
    mCells.reserve(kChunkCells);
    mValues.reserve(kChunkCells);
}

uint64_t CellsWriter::commit() {
    flush();
    mCellsOut.finish();  // both written out before either is renamed into place
    mScalarsOut.finish();
    mCellsOut.commit();
    mScalarsOut.commit();
    return mCellsOut.bytesWritten() + mScalarsOut.bytesWritten();
}

void CellsWriter::flush() {
    mCellsOut.writeSpan(std::span<const Cell>(mCells));
    mScalarsOut.writeSpan(std::span<const float>(mValues));
    mCells.clear();
    mValues.clear();
}

}  // namespace amrvk::amr
