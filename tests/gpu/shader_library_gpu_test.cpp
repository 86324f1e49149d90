// Shaders from a --shader-dir: compiled in process (no shell, whatever the folder is called),
// variants rebuilt from their source with their define, a compile error reported in one line with
// the file and line of the fault, and a renderer that keeps its previous pipeline when a reload
// fails.
#include <fstream>

#include "gpu/compute_pipeline.h"
#include "gpu/shader_compiler.h"
#include "gpu/shader_library.h"
#include "gpu_fixture.h"
#include "model_fixtures.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "scene/camera.h"
#include "scene/tf_presets.h"
#include "test_data.h"

using namespace amrvk;
namespace fs = std::filesystem;

namespace {

// A copy of shaders/ (passes, lib, shared) under `root`; returns its passes folder.
fs::path copyShaders(const fs::path& root) {
    fs::remove_all(root);
    fs::create_directories(root);
    fs::copy(fs::path(AMRVK_SOURCE_DIR) / "shaders", root / "shaders", fs::copy_options::recursive);
    return root / "shaders" / "passes";
}

void replaceInFile(const fs::path& file, const std::string& from, const std::string& to) {
    std::string text = test::readAll(file);
    const size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from << " not in " << file;
    text.replace(at, from.size(), to);
    test::writeAll(file, text);
}

int lineOf(const fs::path& file, const std::string& text) {
    std::ifstream in(file);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
        if (line.find(text) != std::string::npos) return n;
    return 0;
}

}  // namespace

class ShaderLibraryGpu : public test::GpuTest {};

TEST_F(ShaderLibraryGpu, CompilesInProcessWhateverTheFolderIsCalled) {
    const fs::path root = test::scratchDir() / "x'$(touch PWNED)'x";
    const fs::path passes = copyShaders(root);
    const gpu::ShaderLibrary use(passes);
    const std::vector<uint32_t> majorants = use.load("majorants");
    ASSERT_GT(majorants.size(), 5u);
    EXPECT_EQ(majorants[0], 0x07230203u);
    gpu::ComputePipeline pipe(ctx(), majorants, "majorants", sizeof(shared::StructurePush));
    EXPECT_TRUE(pipe.valid());
    EXPECT_FALSE(fs::exists("PWNED") || fs::exists(root / "PWNED") || fs::exists(test::scratchDir() / "PWNED"))
        << "a folder name is never run as a command";
    // The ray-query variant is rebuilt from path_trace.comp with its define.
    if (ctx().hasRayQuery()) {
        const std::vector<uint32_t> rq = use.load("path_trace_rq");
        const std::vector<uint32_t> sw = use.load("path_trace");
        EXPECT_NE(rq, sw) << "the variant must differ from the plain build";
    }
    // A variant of two defines (ray queries and unbiased ray-marching shadows) gets both.
    const std::vector<uint32_t> ubrm = use.load("path_trace_ubrm"), both = use.load("path_trace_rq_ubrm");
    EXPECT_NE(both, ubrm) << "path_trace_rq_ubrm needs AMRVK_RAY_QUERY as well";
    EXPECT_NE(both, use.load("path_trace_rq")) << "path_trace_rq_ubrm needs AMRVK_UBRM as well";
}

TEST_F(ShaderLibraryGpu, ACompileErrorNamesTheFileAndLineInOneLine) {
    const fs::path passes = copyShaders(test::scratchDir() / "broken");
    const fs::path lib = passes.parent_path() / "lib" / "tf.glsl";
    replaceInFile(lib, "if (lo > hi) return 0.0;  // empty range", "if (lo > hi) return 0.0 +;  // empty range");
    const int line = lineOf(lib, "return 0.0 +;");
    ASSERT_GT(line, 0);
    const gpu::ShaderLibrary use(passes);
    try {
        use.load("majorants");
        FAIL() << "a syntax error must not compile";
    } catch (const gpu::ShaderCompileError& e) {
        EXPECT_EQ(fs::path(e.file()).filename(), "tf.glsl") << e.what();
        EXPECT_EQ(e.line(), line) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
        EXPECT_NE(std::string(e.what()).find("tf.glsl:" + std::to_string(line)), std::string::npos) << e.what();
        EXPECT_FALSE(e.log().empty());
    }
}

TEST_F(ShaderLibraryGpu, AFailedReloadKeepsThePreviousPipeline) {
    const std::shared_ptr<const scene::Volume> volume = scene::makeVolume(test::makeThreeLevelCloud());
    render::Renderer r(ctx(), volume, test::gridDda(scene::SamplerKind::ExtBrick, "8"));
    r.setTransferFunction(scene::makePreset("ramp", volume->valueLo(), volume->valueHi()));
    scene::RenderSettings s;
    s.width = s.height = 16;
    s.mode = scene::Mode::Ae;
    s.camera = scene::defaultCamera(glm::dvec3(volume->bounds().lower), glm::dvec3(volume->bounds().upper));
    const scene::RenderOutput before = r.render(s, 2);

    const fs::path passes = copyShaders(test::scratchDir() / "reload");
    replaceInFile(passes / "path_trace.comp", "void main() {", "void main() { syntax error here;");
    EXPECT_THROW(r.setShaders(gpu::ShaderLibrary(passes)), gpu::ShaderCompileError);
    EXPECT_TRUE(r.shaders().directory().empty()) << "the failed library is not taken";
    const scene::RenderOutput after = r.render(s, 2);
    ASSERT_EQ(after.mean.pixels.size(), before.mean.pixels.size());
    for (size_t i = 0; i < after.mean.pixels.size(); ++i)
        ASSERT_EQ(after.mean.pixels[i], before.mean.pixels[i]) << "pixel " << i << ": the old pipeline renders on";

    // A working edit is picked up: background radiance doubled in the shader.
    copyShaders(test::scratchDir() / "reload");
    replaceInFile(passes / ".." / "lib" / "estimator.glsl", "? color : P.shading.background;",
                  "? color : 2.0 * P.shading.background;");
    s.camera.eye = s.camera.target + glm::dvec3(0.0, 0.0, 1e4);  // looks past the data: background only
    s.camera.target += glm::dvec3(1e4, 0.0, 0.0);
    const scene::RenderOutput plain = r.render(s, 1);
    r.setShaders(gpu::ShaderLibrary(passes));
    const scene::RenderOutput doubled = r.render(s, 1);
    EXPECT_FLOAT_EQ(plain.mean.pixels[0].r, 1.0f);
    EXPECT_FLOAT_EQ(doubled.mean.pixels[0].r, 2.0f);

    // No process-wide shader directory: a second renderer in the same process, made now, still
    // renders with the embedded shaders, while the first keeps its own directory.
    render::Renderer other(ctx(), volume, test::gridDda(scene::SamplerKind::ExtBrick, "8"));
    other.setTransferFunction(scene::makePreset("ramp", volume->valueLo(), volume->valueHi()));
    EXPECT_FLOAT_EQ(other.render(s, 1).mean.pixels[0].r, 1.0f);
    EXPECT_FLOAT_EQ(r.render(s, 1).mean.pixels[0].r, 2.0f);
}
