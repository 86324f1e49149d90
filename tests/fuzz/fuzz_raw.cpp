// Raw uniform volumes (src/amr/raw_reader.cpp): headerless voxels, dimensions and type from the
// options or the file name. Input: byte 0 = voxel type (low 2 bits) and flags, bytes 1-3 = dims
// (1..32 each), byte 4 = threshold; the rest are the voxels, padded with zeros or cut to the
// expected size unless flag 0x04 asks for the bytes as given (a size mismatch). Flag 0x08 puts
// dimensions and type in the file name instead of the options; flag 0x10 makes the dimensions
// large (byte << 16 + 1, bytes as given: the size checks must reject them without allocating).
#include <algorithm>
#include <string>

#include "amr/readers.h"
#include "fuzz_common.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 5) return 0;
    static const char* const kTypes[] = {"uint8", "uint16", "float32", "float64"};
    static const size_t kBytes[] = {1, 2, 4, 8};
    const int t = data[0] & 3;
    const bool large = data[0] & 0x10, asGiven = (data[0] & 4) || large, inName = data[0] & 8;
    const glm::ivec3 dims = large ? glm::ivec3(1 + (data[1] << 16), 1 + (data[2] << 16), 1 + (data[3] << 16))
                                  : glm::ivec3(1 + data[1] % 32, 1 + data[2] % 32, 1 + data[3] % 32);
    const double threshold = data[4] / 16.0;
    std::string voxels(reinterpret_cast<const char*>(data + 5), size - 5);
    if (!asGiven) voxels.resize(size_t(dims.x) * size_t(dims.y) * size_t(dims.z) * kBytes[t], '\0');

    const fuzz::Scratch scratch;
    const auto dir = scratch.path();
    amr::ReadOptions options;
    options.format = "raw";
    options.rawThreshold = threshold;
    std::string name = "vol.raw";
    if (inName)
        name = "vol_" + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
               std::to_string(dims.z) + "_" + kTypes[t] + ".raw";
    else {
        options.rawDims = dims;
        options.rawType = kTypes[t];
    }
    fuzz::writeFile(dir / name, voxels);
    fuzz::expectOnlyAmrvkErrors("raw", [&] { amr::readModel(dir / name, options); });
    return 0;
}
