// RAMSES output (src/amr/ramses_reader.cpp): a directory output_00001 with info_00001.txt, an
// optional hydro_file_descriptor.txt and the amr_/hydro_ files of up to two domains. Input: the
// files in this order, joined by fuzz_common.h kSeparator:
//   info_00001.txt, hydro_file_descriptor.txt, amr_00001.out00001, hydro_00001.out00001,
//   amr_00001.out00002, hydro_00001.out00002
// (empty parts are left out, so "no such file" paths and the default names are reached too).
#include "amr/readers.h"
#include "fuzz_common.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const char* const kNames[] = {"info_00001.txt",       "hydro_file_descriptor.txt", "amr_00001.out00001",
                                         "hydro_00001.out00001", "amr_00001.out00002",        "hydro_00001.out00002"};
    const auto parts = fuzz::splitParts(data, size, std::size(kNames));
    const fuzz::Scratch scratch;
    const auto dir = scratch.path() / "output_00001";
    for (size_t i = 0; i < parts.size(); ++i)
        if (i == 0 || !parts[i].empty()) fuzz::writeFile(dir / kNames[i], parts[i]);
    fuzz::expectOnlyAmrvkErrors("ramses", [&] {
        amr::ReadOptions options;  // format auto: detectFormat sees info_00001.txt
        amr::readModel(dir, options);
    });
    return 0;
}
