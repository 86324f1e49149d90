// Enzo output (src/amr/enzo_reader.cpp): a text parameter file, its .hierarchy (text) and the
// HDF5 grid file the hierarchy names. Input, joined by fuzz_common.h kSeparator:
//   DD0000 (parameters), DD0000.hierarchy, DD0000.cpu0000 (HDF5 bytes)
#include "amr/readers.h"
#include "fuzz_common.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto parts = fuzz::splitParts(data, size, 3);
    const auto dir = fuzz::freshScratch();
    fuzz::writeFile(dir / "DD0000", parts[0]);
    fuzz::writeFile(dir / "DD0000.hierarchy", parts[1]);
    fuzz::writeFile(dir / "DD0000.cpu0000", parts[2]);
    fuzz::expectOnlyAmrvkErrors("enzo", [&] {
        amr::ReadOptions options;  // format auto: DD0000.hierarchy beside it
        amr::readModel(dir / "DD0000", options);
    });
    return 0;
}
