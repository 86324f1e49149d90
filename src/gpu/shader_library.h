#pragma once
// SPIR-V by shader name: embedded in the binary at build time (cmake/AmrvkShaders.cmake), or,
// after setShaderDirectory(DIR), read from DIR/<name>.spv, or compiled from DIR/<name>.comp with
// glslc at run time (for experiments without relinking).
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace amrvk::gpu {

struct EmbeddedShader {
    const char* name;
    const uint32_t* words;
    size_t wordCount;
};

// Makes embedded shaders findable by name (each library of shaders registers once).
void registerShaders(std::span<const EmbeddedShader> shaders);
void setShaderDirectory(const std::filesystem::path& dir);
// The SPIR-V of `name`; throws "shader 'X' not found (...)" otherwise.
std::vector<uint32_t> loadShader(const std::string& name);

}  // namespace amrvk::gpu
