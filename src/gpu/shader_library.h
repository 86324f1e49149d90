#pragma once
// SPIR-V by shader name: embedded in the binary at build time (cmake/AmrvkShaders.cmake), or, from
// a ShaderLibrary over a directory DIR (--shader-dir), read from P/<name>.spv, or compiled in process from
// P/<source>.comp (gpu/shader_compiler.h) with the variant's define, where P is DIR/passes when
// DIR is a copy of shaders/ (as `amrvk shaders --export` writes) and DIR itself otherwise;
// includes resolve against P/.. and P (passes/*.comp include "lib/..." and "shared/...").
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

// A shader source file embedded at build time: its path under shaders/ (e.g. "lib/phase.glsl")
// and its text (size bytes, NUL-terminated).
struct ShaderSourceFile {
    const char* path;
    const char* text;
    size_t size;
};

// Writes the sources into dir (dir/passes, dir/lib, dir/shared), creating it. Refuses, before
// writing anything, when one of the files exists and overwrite is false, or a folder under dir is a
// symbolic link; never writes through a link (one at a source's name is replaced itself). Returns
// the files written.
std::vector<std::filesystem::path> exportShaderSources(std::span<const ShaderSourceFile> sources,
                                                       const std::filesystem::path& dir, bool overwrite);

// Makes embedded shaders findable by name (each set of embedded shaders registers once; the
// catalogue of what is compiled into the binary, the same for every library).
void registerShaders(std::span<const EmbeddedShader> shaders);
// The folder that holds passes/, lib/ and shared/ for a --shader-dir DIR: DIR itself when it has
// passes/, else DIR/.. (DIR is a passes folder). What the viewer watches for edits.
std::filesystem::path shaderSourceRoot(const std::filesystem::path& dir);

// Where a renderer's shaders come from: a directory first (when given), then the embedded ones.
// A value: each renderer holds its own, so two renderers in one process may use different
// directories (there is no process-wide shader directory).
class ShaderLibrary {
public:
    ShaderLibrary() = default;  // the embedded shaders only
    // DIR (--shader-dir) first; throws "--shader-dir DIR: not a directory".
    explicit ShaderLibrary(std::filesystem::path dir);
    const std::filesystem::path& directory() const { return mDir; }
    // " from --shader-dir DIR" with a directory, else "": the end of a pipeline's name, by which a
    // runaway or crashing dispatch is reported.
    std::string origin() const { return mDir.empty() ? "" : " from --shader-dir " + mDir.string(); }
    // The SPIR-V of `name`. Throws "shader 'X' not found (...)", or gpu::ShaderCompileError (one
    // line with file and line) when a source in the directory does not compile.
    std::vector<uint32_t> load(const std::string& name) const;
    bool operator==(const ShaderLibrary&) const = default;

private:
    std::filesystem::path mDir;
};

// The embedded SPIR-V of `name` (test kernels, the display pass): ShaderLibrary().load(name).
std::vector<uint32_t> loadShader(const std::string& name);

}  // namespace amrvk::gpu
