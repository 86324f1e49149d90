#include "amr/hdf5_util.h"

#include "core/error.h"
#include "core/file_io.h"

namespace amrvk::amr {

H5Id openHdf5ReadOnly(const std::filesystem::path& path) {
    fileSize(path);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    H5Id f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    AMRVK_CHECK(f.valid(), path.string(),
                ": cannot open as HDF5 (not an HDF5 file, or truncated/damaged)");
    noteInputFile(path);
    return f;
}

}  // namespace amrvk::amr
