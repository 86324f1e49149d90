// Chombo HDF5 plotfile as bytes (src/amr/chombo_reader.cpp through libhdf5). Input: the file's
// bytes. Most mutations are parsed by libhdf5 itself (Debian's build, not instrumented), so this
// target mostly finds libhdf5 bugs; it is not in the default list (docs/fuzzing.md).
#include "amr/readers.h"
#include "fuzz_common.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const fuzz::Scratch scratch;
    const auto dir = scratch.path();
    fuzz::writeFile(dir / "plt.hdf5", std::string_view(reinterpret_cast<const char*>(data), size));
    fuzz::expectOnlyAmrvkErrors("chombo_bytes", [&] {
        amr::ReadOptions options;  // format auto: HDF5 magic
        amr::readModel(dir / "plt.hdf5", options);
    });
    return 0;
}
