#pragma once
// GLSL -> SPIR-V in process (shaderc; no shell, no temporary files), for --shader-dir and hot
// reload. Targets Vulkan 1.2 SPIR-V, optimised by spirv-opt only where the build-time glslc is
// (CMake AMRVK_SPIRV_OPT, off by default: the driver's compiler optimises).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"

namespace amrvk::gpu {

// A failed compile: what() is one line, "<file>:<line>: <first error>" (+ how many more), so the
// CLI prints it as is; file and line are kept for the viewer's overlay and log holds every message.
class ShaderCompileError : public Error {
public:
    ShaderCompileError(std::string file, int line, const std::string& summary, std::string log)
        : Error(summary), mFile(std::move(file)), mLine(line), mLog(std::move(log)) {}
    const std::string& file() const { return mFile; }
    int line() const { return mLine; }  // 0 when the compiler named no line
    const std::string& log() const { return mLog; }

private:
    std::string mFile;
    int mLine;
    std::string mLog;
};

// Compiles the compute shader `source` with the given preprocessor defines (NAME or NAME=VALUE).
// #include "x" is looked up next to the including file, then in includeDirs in order.
std::vector<uint32_t> compileComputeShader(const std::filesystem::path& source, const std::vector<std::string>& defines,
                                           const std::vector<std::filesystem::path>& includeDirs);

}  // namespace amrvk::gpu
