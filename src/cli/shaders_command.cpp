// amrvk shaders: the shader sources built into amrvk, as a starting point for --shader-dir.
#include <cstdio>

#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "gpu/shader_library.h"

namespace amrvk::shaders {
std::span<const gpu::ShaderSourceFile> passShaderSources();
}

namespace amrvk::cli {

namespace {
const char* kShadersHelp =
    "The GLSL sources amrvk was built with. --export DIR writes them (passes/*.comp, lib/*.glsl, shared/*.h) "
    "as a starting point for shader experiments: edit them, then run amrvk render or amrvk view with "
    "--shader-dir DIR; the viewer recompiles a saved change in process and resets the image "
    "(docs/shaders.md).";
}  // namespace

int runShaders(const std::vector<std::string>& argv) {
    CLI::App app(kShadersHelp, "amrvk shaders");
    setUpCommand(app);
    std::string dir;
    bool force = false, list = false;
    app.add_option("--export", dir, "write the sources into DIR (created)")->type_name("DIR");
    app.add_flag("--force", force, "with --export: overwrite files that exist");
    app.add_flag("--list", list, "list the embedded sources and their sizes");
    if (!parseCommandLine(app, argv)) return 0;
    AMRVK_CHECK(!dir.empty() || list, "nothing to do: give --export DIR or --list (see amrvk shaders --help)");
    const auto sources = shaders::passShaderSources();
    if (list)
        for (const gpu::ShaderSourceFile& f : sources) std::printf("%8zu  %s\n", f.size, f.path);
    if (!dir.empty()) {
        const auto written = gpu::exportShaderSources(sources, dir, force);
        std::printf("wrote %zu shader sources to %s; use them with --shader-dir %s\n", written.size(), dir.c_str(),
                    dir.c_str());
    }
    return 0;
}

}  // namespace amrvk::cli
