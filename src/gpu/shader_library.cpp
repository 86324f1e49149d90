#include "gpu/shader_library.h"

#include <unistd.h>

#include <cstdlib>
#include <map>
#include <mutex>

#include "core/error.h"
#include "core/file_io.h"

namespace fs = std::filesystem;

namespace amrvk::gpu {

namespace {
std::mutex gMutex;
std::map<std::string, EmbeddedShader> gShaders;
fs::path gDirectory;

std::vector<uint32_t> readSpirv(const fs::path& p) {
    BinaryReader in(p);
    AMRVK_CHECK(in.size() % 4 == 0 && in.size() >= 20, p.string(), ": not a SPIR-V file (size ", in.size(), ")");
    std::vector<uint32_t> words;
    in.readArray(words, in.size() / 4);
    AMRVK_CHECK(words[0] == 0x07230203u, p.string(), ": not a SPIR-V file (bad magic)");
    return words;
}
}  // namespace

void registerShaders(std::span<const EmbeddedShader> shaders) {
    std::lock_guard lock(gMutex);
    for (const auto& s : shaders) gShaders[s.name] = s;
}

void setShaderDirectory(const fs::path& dir) {
    AMRVK_CHECK(fs::is_directory(dir), "--shader-dir ", dir.string(), ": not a directory");
    std::lock_guard lock(gMutex);
    gDirectory = dir;
}

std::vector<uint32_t> loadShader(const std::string& name) {
    fs::path dir;
    {
        std::lock_guard lock(gMutex);
        dir = gDirectory;
    }
    if (!dir.empty()) {
        fs::path spv = dir / (name + ".spv"), comp = dir / (name + ".comp");
        if (fs::exists(spv)) return readSpirv(spv);
        if (fs::exists(comp)) {
            fs::path out = fs::temp_directory_path() / ("amrvk-" + name + "-" + std::to_string(::getpid()) + ".spv");
            std::string cmd = "glslc --target-env=vulkan1.2 -O -I '" + (dir / "..").string() + "' -I '" +
                              dir.string() + "' -o '" + out.string() + "' '" + comp.string() + "'";
            int rc = std::system(cmd.c_str());
            AMRVK_CHECK(rc == 0, comp.string(), ": glslc failed (exit ", rc, ")");
            auto words = readSpirv(out);
            fs::remove(out);
            return words;
        }
    }
    std::lock_guard lock(gMutex);
    auto it = gShaders.find(name);
    AMRVK_CHECK(it != gShaders.end(), "shader '", name, "' not found",
                dir.empty() ? std::string(" among the embedded shaders") : " in " + dir.string() + " or embedded");
    return std::vector<uint32_t>(it->second.words, it->second.words + it->second.wordCount);
}

}  // namespace amrvk::gpu
