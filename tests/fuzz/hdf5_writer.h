#pragma once
// Small HDF5 files written through the HDF5 API from fuzz bytes (FuzzedDataProvider), so the
// structured targets exercise what amrvk does with a well-formed HDF5 file of any content
// (shapes, attributes, offsets), not libhdf5's own parser (fuzz_chombo_bytes does that).
#include <fuzzer/FuzzedDataProvider.h>
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace amrvk::fuzz {

// Mostly a small value in [lo, hi]; sometimes any int (limits, overflow).
inline int smallOrAny(FuzzedDataProvider& p, int lo, int hi) {
    if (p.ConsumeIntegralInRange<int>(0, 15) == 0) return p.ConsumeIntegral<int>();
    return p.ConsumeIntegralInRange<int>(lo, hi);
}

inline void intAttribute(hid_t loc, const char* name, int value) {
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(loc, name, H5T_NATIVE_INT, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_INT, &value);
    H5Aclose(a);
    H5Sclose(space);
}

inline void doubleAttribute(hid_t loc, const char* name, double value) {
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(loc, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(a, H5T_NATIVE_DOUBLE, &value);
    H5Aclose(a);
    H5Sclose(space);
}

inline void stringAttribute(hid_t loc, const char* name, const std::string& value) {
    hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, value.empty() ? 1 : value.size());
    hid_t space = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    std::string padded = value.empty() ? std::string(1, '\0') : value;
    H5Awrite(a, type, padded.data());
    H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
}

// A compound of int members `names`: one element as an attribute (count < 0) or a 1-D dataset
// of `count` elements; values row by row.
inline void intCompound(hid_t loc, const char* name, const std::vector<std::string>& names,
                        const std::vector<int>& values, long count) {
    hid_t type = H5Tcreate(H5T_COMPOUND, sizeof(int) * names.size());
    for (size_t i = 0; i < names.size(); ++i)
        H5Tinsert(type, names[i].c_str(), i * sizeof(int), H5T_NATIVE_INT);
    if (count < 0) {
        hid_t space = H5Screate(H5S_SCALAR);
        hid_t a = H5Acreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
        H5Awrite(a, type, values.data());
        H5Aclose(a);
        H5Sclose(space);
    } else {
        const hsize_t n = hsize_t(count);
        hid_t space = H5Screate_simple(1, &n, nullptr);
        hid_t d = H5Dcreate2(loc, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        if (n) H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
        H5Dclose(d);
        H5Sclose(space);
    }
    H5Tclose(type);
}

// A dataset of `rank` dims (slowest first) of values stored as `fileType`, written from doubles.
inline void doubleDataset(hid_t loc, const char* name, const std::vector<hsize_t>& dims,
                          const std::vector<double>& values, hid_t fileType) {
    hid_t space = H5Screate_simple(int(dims.size()), dims.data(), nullptr);
    hid_t d = H5Dcreate2(loc, name, fileType, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (!values.empty()) H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(d);
    H5Sclose(space);
}

inline void int64Dataset(hid_t loc, const char* name, const std::vector<int64_t>& values) {
    const hsize_t n = values.size();
    hid_t space = H5Screate_simple(1, &n, nullptr);
    hid_t d = H5Dcreate2(loc, name, H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (n) H5Dwrite(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(d);
    H5Sclose(space);
}

}  // namespace amrvk::fuzz
