// Viewer scripts (src/viewer/logic/script.cpp): parseScript on the text, then checkScript with a shader
// directory (so edit-shader paths are resolved and confined) as `amrvk view --script` does before
// frame 0. Input: the script text.
#include "fuzz_common.h"
#include "viewer/logic/script.h"

using namespace amrvk;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const fuzz::Scratch scratch;
    const auto dir = scratch.path();
    fuzz::writeFile(dir / "shaders/passes/path_trace.comp", "void main() {}\n");
    fuzz::writeFile(dir / "shaders/lib/tf.glsl", "// tf\n");
    fuzz::writeFile(dir / "outside.txt", "precious\n");
    fuzz::expectOnlyAmrvkErrors("script", [&] {
        const std::vector<viewer::ScriptAction> actions = viewer::parseScript(text, "fuzz.txt");
        viewer::checkScript(actions, {dir / "shaders/passes", {}});
        for (const viewer::ScriptAction& a : actions)
            if (a.name == "edit-shader") {
                const std::filesystem::path p = viewer::confinedShaderPath(dir / "shaders/passes", a.args[0]);
                if (p.filename() == "outside.txt") std::abort();  // escaped the shader sources
            }
    });
    return 0;
}
