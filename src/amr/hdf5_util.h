#pragma once
// HDF5 helpers shared by the Chombo and Enzo readers. Include only from amr .cpp files (the HDF5
// headers are private to amrvk_amr).
#include <hdf5.h>

#include <filesystem>
#include <utility>

namespace amrvk::amr {

// Owns one HDF5 id and closes it with the matching H5?close on destruction.
class H5Id {
public:
    using Closer = herr_t (*)(hid_t);
    H5Id(hid_t id, Closer close) : mId(id), mClose(close) {}
    ~H5Id() {
        if (mId >= 0) mClose(mId);
    }
    H5Id(H5Id&& other) noexcept
        : mId(std::exchange(other.mId, H5I_INVALID_HID)), mClose(other.mClose) {}
    H5Id& operator=(H5Id&&) = delete;
    H5Id(const H5Id&) = delete;
    H5Id& operator=(const H5Id&) = delete;

    hid_t get() const { return mId; }
    bool valid() const { return mId >= 0; }

private:
    hid_t mId;
    Closer mClose;
};

// Opens an existing HDF5 file read-only with HDF5's own error printing off. Throws
// "PATH: no such file" (via fileSize) or "PATH: cannot open as HDF5 (...)".
H5Id openHdf5ReadOnly(const std::filesystem::path& path);

}  // namespace amrvk::amr
