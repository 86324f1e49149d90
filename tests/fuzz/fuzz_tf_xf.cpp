// `.xf` transfer functions (src/scene/tf_files.cpp loadXf, and loadTransferFunction's
// detection by magic). Input: the file's bytes. A TF that loads is evaluated at a few values.
#include <cmath>

#include "fuzz_common.h"
#include "scene/tf_files.h"
#include "scene/transfer_function.h"

using namespace amrvk;

namespace {
void exercise(const scene::TransferFunction& tf) {
    for (float v : {-1.0f, 0.0f, 0.5f, 1.0f, 2.0f, NAN}) (void)tf.evaluate(v);
    (void)tf.maxAlpha(0.0f, 1.0f);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const fuzz::Scratch scratch;
    const auto dir = scratch.path();
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    fuzz::writeFile(dir / "tf.xf", bytes);
    fuzz::writeFile(dir / "tf.bin", bytes);
    fuzz::expectOnlyAmrvkErrors("tf_xf", [&] { exercise(scene::loadXf(dir / "tf.xf", 0.0f, 1.0f)); });
    fuzz::expectOnlyAmrvkErrors("tf_xf(detect)", [&] {
        exercise(scene::loadTransferFunction((dir / "tf.bin").string(), -2.0f, 3.0f));
    });
    return 0;
}
