// ExaBrick .cells + .scalars (src/amr/exabrick_io.cpp), read as `amrvk info x.cells` does
// (readModel: reader, NaN policy, validation). Input: <cells bytes> SEP <scalars bytes> [SEP
// <second field's scalars>] (fuzz_common.h kSeparator).
#include "amr/readers.h"
#include "fuzz_common.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto parts = fuzz::splitParts(data, size, 3);
    const fuzz::Scratch scratch;
    const auto dir = scratch.path();
    fuzz::writeFile(dir / "f.cells", parts[0]);
    if (parts[2].empty()) {
        fuzz::writeFile(dir / "f.scalars", parts[1]);
    } else {
        fuzz::writeFile(dir / "f.a.scalars", parts[1]);
        fuzz::writeFile(dir / "f.b.scalars", parts[2]);
    }
    fuzz::expectOnlyAmrvkErrors("exabrick", [&] {
        amr::ReadOptions options;
        options.format = "auto";
        amr::readModel(dir / "f.cells", options);
    });
    fuzz::expectOnlyAmrvkErrors("exabrick(nan=drop)", [&] {
        amr::ReadOptions options;
        options.nanPolicy = amr::NanPolicy::Drop;
        amr::readModel(dir / "f", options);
    });
    return 0;
}
