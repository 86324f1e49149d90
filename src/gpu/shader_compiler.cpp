#include "gpu/shader_compiler.h"

#include <shaderc/shaderc.hpp>

#include <fstream>
#include <memory>
#include <sstream>

namespace fs = std::filesystem;

namespace amrvk::gpu {

namespace {

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Bounds on what a shader directory's preprocessing may do (a file that includes itself without
// a guard would expand without end): include depth and the bytes read for one compile.
constexpr size_t kMaxIncludeDepth = 32;
constexpr uint64_t kMaxSourceBytes = uint64_t(64) << 20;

// Resolves #include against the including file's folder, then the include folders.
class Includer : public shaderc::CompileOptions::IncluderInterface {
public:
    explicit Includer(std::vector<fs::path> dirs, uint64_t bytesSoFar) : mDirs(std::move(dirs)), mBytes(bytesSoFar) {}

    shaderc_include_result* GetInclude(const char* requested, shaderc_include_type, const char* requesting,
                                       size_t depth) override {
        auto* r = new Result;
        std::vector<fs::path> candidates{fs::path(requesting).parent_path() / requested};
        for (const fs::path& d : mDirs) candidates.push_back(d / requested);
        for (const fs::path& c : candidates) {
            std::error_code ec;
            if (!fs::is_regular_file(c, ec)) continue;
            const uint64_t size = fs::file_size(c, ec);
            if (depth > kMaxIncludeDepth) {
                r->content = "includes nested deeper than " + std::to_string(kMaxIncludeDepth) +
                             " levels (a file that includes itself?)";
            } else if (ec || mBytes + size > kMaxSourceBytes) {
                r->content = "the sources of one shader exceed " + std::to_string(kMaxSourceBytes >> 20) + " MiB";
            } else {
                r->name = fs::weakly_canonical(c, ec).string();
                r->content = readText(c);
                mBytes += r->content.size();
            }
            break;
        }
        if (r->name.empty() && r->content.empty()) r->content = std::string("cannot find '") + requested + "'";
        r->result = {r->name.c_str(), r->name.size(), r->content.c_str(), r->content.size(), r};
        return &r->result;
    }

    void ReleaseInclude(shaderc_include_result* data) override { delete static_cast<Result*>(data->user_data); }

private:
    struct Result {
        std::string name, content;
        shaderc_include_result result{};
    };
    std::vector<fs::path> mDirs;
    uint64_t mBytes;  // read so far for this compile
};

// "file:line: error: message" -> file, line; the first error line of the log is the summary.
ShaderCompileError compileError(const fs::path& source, const std::string& log, size_t errors) {
    std::istringstream lines(log);
    std::string line, first;
    while (std::getline(lines, line))
        if (line.find("error") != std::string::npos) {
            first = line;
            break;
        }
    if (first.empty()) first = source.string() + ": " + (log.empty() ? "compilation failed" : log);
    std::string file = source.string();
    int lineNo = 0;
    // shaderc writes "<name>:<line>: error: ..."; names may contain ':' only before the line number.
    const size_t err = first.find(": error");
    if (err != std::string::npos) {
        const size_t colon = first.rfind(':', err - 1);
        if (colon != std::string::npos) {
            try {
                lineNo = std::stoi(first.substr(colon + 1, err - colon - 1));
                file = first.substr(0, colon);
            } catch (const std::exception&) {
                lineNo = 0;
            }
        }
    }
    for (char& c : first)
        if (c == '\n' || c == '\r') c = ' ';
    const std::string summary = errors > 1 ? first + " (and " + std::to_string(errors - 1) + " more)" : first;
    return ShaderCompileError(file, lineNo, summary, log);
}

}  // namespace

std::vector<uint32_t> compileComputeShader(const fs::path& source, const std::vector<std::string>& defines,
                                           const std::vector<fs::path>& includeDirs) {
    std::error_code ec;
    AMRVK_CHECK(fs::is_regular_file(source, ec), source.string(), ": not a shader source file");
    const uint64_t size = fs::file_size(source, ec);
    AMRVK_CHECK(!ec && size <= kMaxSourceBytes, source.string(), ": larger than ", kMaxSourceBytes >> 20,
                " MiB (not a shader source?)");
    const std::string text = readText(source);
    shaderc::Compiler compiler;
    AMRVK_CHECK(compiler.IsValid(), "shaderc: the shader compiler failed to initialise");
    shaderc::CompileOptions options;
    options.SetTargetEnvironment(shaderc_target_env_vulkan, shaderc_env_version_vulkan_1_2);
    options.SetOptimizationLevel(AMRVK_SPIRV_OPT ? shaderc_optimization_level_performance
                                                 : shaderc_optimization_level_zero);
    for (const std::string& d : defines) {
        const size_t eq = d.find('=');
        if (eq == std::string::npos) options.AddMacroDefinition(d);
        else options.AddMacroDefinition(d.substr(0, eq), d.substr(eq + 1));
    }
    options.SetIncluder(std::make_unique<Includer>(includeDirs, text.size()));
    const shaderc::SpvCompilationResult result =
        compiler.CompileGlslToSpv(text, shaderc_compute_shader, source.string().c_str(), options);
    if (result.GetCompilationStatus() != shaderc_compilation_status_success)
        throw compileError(source, result.GetErrorMessage(), result.GetNumErrors());
    return {result.cbegin(), result.cend()};
}

}  // namespace amrvk::gpu
