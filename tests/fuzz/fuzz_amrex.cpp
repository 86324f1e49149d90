// AMReX plotfile (src/amr/amrex_reader.cpp): a directory with Header and Level_<l>/Cell_H +
// Cell_D_00000 files. Input: the files in this order, joined by fuzz_common.h kSeparator:
//   Header, Level_0/Cell_H, Level_0/Cell_D_00000, Level_1/Cell_H, Level_1/Cell_D_00000
// (missing parts are left out, so "no such file" paths are reached too).
#include "amr/readers.h"
#include "fuzz_common.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const char* const kNames[] = {"Header", "Level_0/Cell_H", "Level_0/Cell_D_00000",
                                         "Level_1/Cell_H", "Level_1/Cell_D_00000"};
    const auto parts = fuzz::splitParts(data, size, std::size(kNames));
    const fuzz::Scratch scratch;
    const auto dir = scratch.path() / "plt";
    for (size_t i = 0; i < parts.size(); ++i)
        if (i == 0 || !parts[i].empty()) fuzz::writeFile(dir / kNames[i], parts[i]);
    fuzz::expectOnlyAmrvkErrors("amrex", [&] {
        amr::ReadOptions options;  // format auto: detectFormat sees the Header
        amr::readModel(dir, options);
    });
    return 0;
}
