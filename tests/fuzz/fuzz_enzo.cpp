// Enzo output (src/amr/enzo_reader.cpp): a text parameter file, its .hierarchy (text) and the
// HDF5 grid file the hierarchy names. Input, joined by fuzz_common.h kSeparator:
//   DD0000 (parameter text), DD0000.hierarchy (text), grid-file description
// The third part is not HDF5 bytes: it chooses the groups Grid<id> and their datasets (name,
// rank, shape, type) of a well-formed file written through the HDF5 API (hdf5_writer.h), so the
// reader's own logic is fuzzed rather than libhdf5's parser (fuzz_chombo_bytes does that).
#include <cstdio>

#include "amr/readers.h"
#include "fuzz_common.h"
#include "hdf5_writer.h"

using namespace amrvk;

namespace {

void writeGrids(const std::filesystem::path& path, std::string_view description) {
    FuzzedDataProvider p(reinterpret_cast<const uint8_t*>(description.data()), description.size());
    hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const int grids = p.ConsumeIntegralInRange<int>(0, 4);
    for (int i = 0; i < grids; ++i) {
        char name[32];
        std::snprintf(name, sizeof(name), "Grid%08d", p.ConsumeBool() ? i + 1 : p.ConsumeIntegralInRange<int>(0, 9));
        if (H5Lexists(f, name, H5P_DEFAULT) > 0) continue;
        hid_t g = H5Gcreate2(f, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
        const int datasets = p.ConsumeIntegralInRange<int>(0, 3);
        for (int k = 0; k < datasets; ++k) {
            static const char* const kNames[] = {"Density", "Temperature", "x-velocity", "particle_mass"};
            const char* dsName = kNames[p.ConsumeIntegralInRange<int>(0, 3)];
            if (H5Lexists(g, dsName, H5P_DEFAULT) > 0) continue;
            const int rank = p.ConsumeIntegralInRange<int>(0, 7) == 0 ? p.ConsumeIntegralInRange<int>(1, 4) : 3;
            std::vector<hsize_t> dims;
            hsize_t count = 1;
            for (int a = 0; a < rank; ++a) {
                dims.push_back(p.ConsumeBool() ? 4 : p.ConsumeIntegralInRange<hsize_t>(0, 40));
                count *= dims.back();
            }
            std::vector<double> values(count);
            for (size_t v = 0; v < values.size(); ++v) values[v] = 1.0 + double(v % 5);
            if (!values.empty() && p.ConsumeBool())
                values[p.ConsumeIntegralInRange<size_t>(0, count - 1)] = p.ConsumeFloatingPoint<double>();
            static const hid_t kTypes[] = {H5T_IEEE_F32LE, H5T_IEEE_F64LE, H5T_STD_I32LE, H5T_STD_U8LE};
            fuzz::doubleDataset(g, dsName, dims, values, kTypes[p.ConsumeIntegralInRange<int>(0, 3)]);
        }
        H5Gclose(g);
    }
    H5Fclose(f);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const bool quiet = (H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr), true);
    (void)quiet;
    const auto parts = fuzz::splitParts(data, size, 3);
    const fuzz::Scratch scratch;
    const auto dir = scratch.path();
    fuzz::writeFile(dir / "DD0000", parts[0]);
    fuzz::writeFile(dir / "DD0000.hierarchy", parts[1]);
    writeGrids(dir / "DD0000.cpu0000", parts[2]);
    fuzz::expectOnlyAmrvkErrors("enzo", [&] {
        amr::ReadOptions options;  // format auto: DD0000.hierarchy beside it
        amr::readModel(dir / "DD0000", options);
    });
    return 0;
}
