// ExaBrick `.bricks` files (src/accel/bricks_file.cpp readBricksFile), as `amrvk info --bricks` reads
// them: against the model of a .cells/.scalars pair. Input, joined by fuzz_common.h kSeparator:
//   <cells bytes>, <scalars bytes>, <bricks bytes>
// When the model is valid, the bricks built from it (buildBricks) are checked too.
#include "accel/brick_build.h"
#include "accel/bricks.h"
#include "accel/bricks_file.h"
#include "amr/readers.h"
#include "fuzz_common.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto parts = fuzz::splitParts(data, size, 3);
    const fuzz::Scratch scratch;
    const auto dir = scratch.path();
    fuzz::writeFile(dir / "m.cells", parts[0]);
    fuzz::writeFile(dir / "m.scalars", parts[1]);
    fuzz::writeFile(dir / "m.bricks", parts[2]);
    fuzz::expectOnlyAmrvkErrors("bricks", [&] {
        amr::Model model = amr::readModel(dir / "m.cells", {});
        (void)accel::readBricksFile(dir / "m.bricks", model);  // against the file's cell order
        (void)accel::buildBricks(model);                       // then reorders the model
    });
    return 0;
}
