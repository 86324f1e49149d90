// ParaView colour-map JSON (src/scene/tf_files.cpp): parseParaViewPreset on the text
// (a session's "transferFunction"), and loadParaViewPreset / loadParaViewPresets on it as a file.
// Input: the JSON text. A TF that loads is merged, evaluated and written back.
#include <cmath>

#include "fuzz_common.h"
#include "scene/tf_files.h"
#include "scene/transfer_function.h"

using namespace amrvk;

namespace {
void exercise(const scene::TransferFunction& tf) {
    for (float v : {-1.0f, 0.0f, 0.5f, 1.0f, 2.0f, NAN}) (void)tf.evaluate(v);
    (void)tf.maxAlpha(0.0f, 1.0f);
    (void)tf.rescaled(0.0f, 1.0f);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    fuzz::expectOnlyAmrvkErrors("tf_json(parse)", [&] {
        const scene::TfChannels ch = scene::parseParaViewPreset(text, "fuzz");
        exercise(ch.merged());
        (void)scene::paraViewPresetJson(ch);
    });
    const fuzz::Scratch scratch;
    const auto dir = scratch.path();
    fuzz::writeFile(dir / "tf.json", text);
    fuzz::expectOnlyAmrvkErrors("tf_json(load)", [&] {
        exercise(scene::loadParaViewPreset(dir / "tf.json"));
    });
    fuzz::expectOnlyAmrvkErrors("tf_json(loadAll)", [&] {
        for (const auto& ch : scene::loadParaViewPresets(dir / "tf.json").presets) exercise(ch.merged());
    });
    return 0;
}
