#include "gpu/shader_library.h"

#include <map>
#include <mutex>

#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"
#include "gpu/shader_compiler.h"

namespace fs = std::filesystem;

namespace amrvk::gpu {

namespace {
std::mutex gMutex;
std::map<std::string, EmbeddedShader> gShaders;  // the embedded catalogue

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
    // An entry already there from the same set stays untouched: a pipeline may be compiling from it
    // on another thread (render::warmPathTracer).
    for (const auto& s : shaders)
        if (auto it = gShaders.find(s.name); it == gShaders.end() || it->second.words != s.words) gShaders[s.name] = s;
}

ShaderLibrary::ShaderLibrary(fs::path dir) : mDir(std::move(dir)) {
    std::error_code ec;
    AMRVK_CHECK(mDir.empty() || fs::is_directory(mDir, ec), "--shader-dir ", mDir.string(), ": not a directory");
}

fs::path shaderSourceRoot(const fs::path& dir) { return fs::is_directory(dir / "passes") ? dir : dir / ".."; }

std::vector<uint32_t> loadShader(const std::string& name) { return ShaderLibrary().load(name); }

std::vector<uint32_t> ShaderLibrary::load(const std::string& name) const {
    const fs::path& dir = mDir;
    std::string source = name, define;
    const EmbeddedShader* embedded = nullptr;
    {
        std::lock_guard lock(gMutex);
        auto it = gShaders.find(name);
        if (it != gShaders.end()) {
            embedded = &it->second;
            source = it->second.source;
            define = it->second.define;
        }
    }
    if (!dir.empty()) {
        const fs::path root = shaderSourceRoot(dir), passes = root == dir ? dir / "passes" : dir;
        const fs::path spv = passes / (name + ".spv"), comp = passes / (source + ".comp");
        if (fs::exists(spv)) return readSpirv(spv);
        if (fs::exists(comp)) {
            // A variant's DEFINE or DEFINE,DEFINE,...
            return compileComputeShader(comp, splitList(define), {root, passes});
        }
    }
    AMRVK_CHECK(embedded, "shader '", name, "' not found",
                dir.empty() ? std::string(" among the embedded shaders") : " in " + dir.string() + " or embedded");
    return std::vector<uint32_t>(embedded->words, embedded->words + embedded->wordCount);
}

std::vector<fs::path> exportShaderSources(std::span<const ShaderSourceFile> sources, const fs::path& dir,
                                          bool overwrite) {
    std::error_code ec;
    fs::path root = dir;  // without a trailing '/'
    while (!root.has_filename() && root.has_relative_path()) root = root.parent_path();
    const bool exists = fs::is_directory(dir, ec);
    AMRVK_CHECK(exists || !fs::exists(fs::symlink_status(root, ec)), dir.string(), ": exists and is not a directory");
    // Never through a link: a linked folder under DIR would put the sources outside it (refused); a
    // link at a source's own name is replaced itself (DIR itself, named by the user, may be a link).
    std::vector<fs::path> out;
    for (const ShaderSourceFile& f : sources) {
        const fs::path p = dir / f.path;
        for (fs::path sub = fs::path(f.path).parent_path(); !sub.empty(); sub = sub.parent_path())
            AMRVK_CHECK(!fs::is_symlink(fs::symlink_status(dir / sub, ec)), (dir / sub).string(),
                        ": a symbolic link (refused: the sources would be written outside ", dir.string(), ")");
        const fs::file_status s = fs::symlink_status(p, ec);
        AMRVK_CHECK(overwrite || !fs::exists(s), p.string(), " exists (give --force to overwrite)");
        AMRVK_CHECK(!fs::is_directory(s), p.string(), ": is a directory");
        out.push_back(p);
    }
    // All or nothing: every source is written into a fresh folder (beside a new DIR, inside an
    // existing one: the same file system) and renamed into place only when all are complete, so a
    // failure (a full disk) leaves no DIR, or DIR as it was. The folder is removed either way.
    if (!exists && root.has_parent_path()) {
        fs::create_directories(root.parent_path(), ec);
        AMRVK_CHECK(!ec, root.parent_path().string(), ": cannot create (", ec.message(), ")");
    }
    const fs::path staging = makeTemporaryDirectory(exists ? root / ".export" : root);
    struct Remove {
        fs::path path;
        ~Remove() {
            std::error_code e;
            fs::remove_all(path, e);
        }
    } removeStaging{staging};
    for (size_t i = 0; i < sources.size(); ++i) {
        const fs::path p = staging / sources[i].path;
        fs::create_directories(p.parent_path(), ec);
        AMRVK_CHECK(!ec, out[i].parent_path().string(), ": cannot create (", ec.message(), "); nothing was exported");
        try {
            writeFileAtomic(p, std::string(sources[i].text, sources[i].size));
        } catch (const Error& e) {  // named by the file it was for
            const std::string m = e.what(), staged = p.string();
            throw Error(strCat(out[i].string(), m.rfind(staged, 0) == 0 ? m.substr(staged.size()) : ": " + m,
                               "; nothing was exported"));
        }
    }
    if (!exists) {
        fs::rename(staging, root, ec);
        AMRVK_CHECK(!ec, dir.string(), ": cannot rename the exported sources into place (", ec.message(), ")");
        return out;
    }
    for (size_t i = 0; i < sources.size(); ++i) {  // a rename replaces a link itself, never its target
        fs::create_directories(out[i].parent_path(), ec);
        AMRVK_CHECK(!ec, out[i].parent_path().string(), ": cannot create (", ec.message(), ")");
        fs::rename(staging / sources[i].path, out[i], ec);
        AMRVK_CHECK(!ec, out[i].string(), ": cannot rename into place (", ec.message(), ")");
    }
    return out;
}

}  // namespace amrvk::gpu
