#pragma once
// SPIR-V by shader name: embedded in the binary at build time (cmake/AmrvkShaders.cmake), or,
// after setShaderDirectory(DIR), read from DIR/<name>.spv, or compiled in process from
// DIR/<source>.comp (gpu/shader_compiler.h) with the variant's define, includes resolved against
// DIR/.. and DIR (the layout of shaders/: passes/*.comp include "lib/..." and "shared/...").
// A variant (e.g. path_trace_rq = path_trace.comp with AMRVK_RAY_QUERY) is compiled from its
// source, so an edited path_trace.comp changes both.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace amrvk::gpu {

struct EmbeddedShader {
    const char* name;      // e.g. "path_trace_rq"
    const uint32_t* words;
    size_t wordCount;
    const char* source;    // the .comp it is built from, without extension (e.g. "path_trace")
    const char* define;    // preprocessor define of the variant, or "" (e.g. "AMRVK_RAY_QUERY")
};

// Makes embedded shaders findable by name (each library of shaders registers once).
void registerShaders(std::span<const EmbeddedShader> shaders);
// Where loadShader looks first; an empty path goes back to the embedded shaders only.
void setShaderDirectory(const std::filesystem::path& dir);
std::filesystem::path shaderDirectory();
// The SPIR-V of `name`. Throws "shader 'X' not found (...)", or gpu::ShaderCompileError (one line
// with file and line) when a source in the shader directory does not compile.
std::vector<uint32_t> loadShader(const std::string& name);

}  // namespace amrvk::gpu
