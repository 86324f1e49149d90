// Chombo HDF5 plotfile (src/amr/chombo_reader.cpp). Input: the file's bytes. Most mutations are
// parsed by libhdf5 itself (not instrumented: Debian's build), so a crash there is reported as a
// SEGV without an amrvk frame; see docs/fuzzing.md.
#include "amr/readers.h"
#include "fuzz_common.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto dir = fuzz::freshScratch();
    fuzz::writeFile(dir / "plt.hdf5", std::string_view(reinterpret_cast<const char*>(data), size));
    fuzz::expectOnlyAmrvkErrors("chombo", [&] {
        amr::ReadOptions options;  // format auto: HDF5 magic
        amr::readModel(dir / "plt.hdf5", options);
    });
    return 0;
}
