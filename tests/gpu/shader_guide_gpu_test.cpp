// The worked example of docs/shaders.md, run as the page says: `amrvk shaders --export`, the
// page's two-lobe phase function pasted into lib/phase.glsl, the edited shaders loaded with
// --shader-dir. Checked by an independent route: single scattering is linear in the phase
// function, so the edited picture at g equals the mean of the stock pictures at g and -g.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <regex>

#include "gpu/shader_compiler.h"
#include "gpu/shader_library.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "render/renderer.h"
#include "render_fixtures.h"
#include "test_data.h"

using namespace amrvk;
namespace fs = std::filesystem;

namespace {

std::string amrvkBinary() { return std::string(AMRVK_BINARY_DIR) + "/bin/amrvk"; }

// The ```glsl block after the page's "worked-example: lib/phase.glsl" marker.
std::string workedExampleBlock() {
    const std::string page = test::readAll(fs::path(AMRVK_SOURCE_DIR) / "docs/shaders.md");
    const size_t marker = page.find("<!-- worked-example: lib/phase.glsl");
    if (marker == std::string::npos) return {};
    const size_t open = page.find("```glsl\n", marker);
    const size_t close = page.find("\n```", open + 8);
    if (open == std::string::npos || close == std::string::npos) return {};
    return page.substr(open + 8, close - open - 8 + 1);
}

// Removes the definition of function `name` (its signature line through its closing brace,
// with the comment lines right above it) from GLSL source `s`. False when it is not there.
bool removeFunction(std::string& s, const std::string& signature) {
    size_t at = s.find(signature);
    if (at == std::string::npos) return false;
    size_t brace = s.find('{', at);
    int depth = 0;
    size_t end = brace;
    for (; end < s.size(); ++end) {
        if (s[end] == '{') ++depth;
        if (s[end] == '}' && --depth == 0) break;
    }
    if (end >= s.size()) return false;
    size_t begin = at;  // take the comment lines above with it
    while (begin > 0) {
        const size_t lineStart = s.rfind('\n', begin - 2) == std::string::npos ? 0 : s.rfind('\n', begin - 2) + 1;
        if (s.compare(lineStart, 2, "//") != 0) break;
        begin = lineStart;
    }
    s.erase(begin, end + 2 - begin);
    return true;
}

// The mean of two independent renders as a render: per-pixel sample variance (s_a^2 + s_b^2) / 4
// with the same sample count, so the z-test sees the variance of the average.
scene::RenderOutput average(const scene::RenderOutput& a, const scene::RenderOutput& b) {
    scene::RenderOutput m = a;
    const double n = a.spp;
    for (size_t i = 0; i < m.mean.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double mean = 0.5 * (double(a.mean.pixels[i][c]) + double(b.mean.pixels[i][c]));
            const double var = 0.25 * (test::sampleVariance(a, i, c) + test::sampleVariance(b, i, c));
            m.mean.pixels[i][c] = float(mean);
            m.sumSq[i][c] = float((n - 1) * var + n * mean * mean);
        }
    return m;
}

class ShaderGuideGpu : public test::GpuTest {};

TEST_F(ShaderGuideGpu, TwoLobePhaseFunctionOfTheGuideEqualsTheMeanOfTwoStockRenders) {
    if (!fs::exists(amrvkBinary())) GTEST_SKIP() << "amrvk binary not built: " << amrvkBinary();
    const fs::path dir = test::scratchDir() / "shader-guide";
    fs::remove_all(dir);
    const std::string cmd = amrvkBinary() + " shaders --export " + (dir / "shaders").string() + " >" +
                            (dir.string() + ".out") + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << test::readAll(dir.string() + ".out");
    const fs::path phase = dir / "shaders/lib/phase.glsl";
    ASSERT_TRUE(fs::exists(phase));

    // The edit the page describes.
    const std::string block = workedExampleBlock();
    ASSERT_NE(block.find("float henyeyGreenstein("), std::string::npos) << "docs/shaders.md lost its example";
    std::string source = test::readAll(phase);
    ASSERT_TRUE(removeFunction(source, "float henyeyGreenstein(float cosTheta, float g)"));
    ASSERT_TRUE(removeFunction(source, "vec3 sampleHenyeyGreenstein(vec3 d, float g, float u1, float u2)"));
    const size_t endif = source.rfind("#endif");
    ASSERT_NE(endif, std::string::npos);
    source.insert(endif, block + "\n");
    test::writeAll(phase, source);

    // A uniform scattering cube seen from +z, lit from behind (forward scattering towards the
    // camera) and by a dim environment, which ss reaches through the phase sampler.
    auto renderer = test::makeRenderer(ctx(), test::makeUniformBox({16, 16, 16}, 0, 1.0f),
                                       test::gridDda(scene::SamplerKind::ExtBrick, "8"));
    render::Renderer& r = *renderer;
    r.setTransferFunction(test::constantTf(glm::vec3(0.9f), 0.12f));
    scene::RenderSettings s;
    s.mode = scene::Mode::Ss;
    s.width = s.height = 32;
    s.camera.eye = {8.0, 8.0, 44.0};
    s.camera.target = {8.0, 8.0, 8.0};
    s.camera.up = {0.0, 1.0, 0.0};
    s.camera.fovYDegrees = 40.0;
    s.ambient = glm::dvec3(0.5);
    s.background = glm::dvec3(0.0);
    s.lights = {scene::Light{false, {0.3, 0.2, -1.0}, {4.0, 4.0, 4.0}}};
    const uint32_t spp = 256;
    auto renderAt = [&](double g, uint32_t seed) {
        s.g = g;
        s.seed = seed;
        scene::RenderOutput o = r.render(s, spp);
        EXPECT_EQ(o.stats.counter(shared::kCounterNanSamples), 0u);
        return o;
    };
    const scene::RenderOutput forward = renderAt(0.7, 1), backward = renderAt(-0.7, 2);
    r.setShaders(gpu::ShaderLibrary(dir / "shaders"));
    const scene::RenderOutput edited = renderAt(0.7, 3);

    test::expectSameImage(edited, average(forward, backward), 4, "two-lobe-vs-mean-of-stock");
    // Power: the same test tells the edited picture from the stock one at g.
    EXPECT_GT(test::countDifferingTiles(edited, forward, 4, 1e-4, 1e-6), 8)
        << "the edit did not change the picture enough for the check to mean anything";
}

TEST_F(ShaderGuideGpu, ExportRefusesToOverwriteAndTheCopyCompilesUnchanged) {
    if (!fs::exists(amrvkBinary())) GTEST_SKIP() << "amrvk binary not built: " << amrvkBinary();
    const fs::path dir = test::scratchDir() / "shader-export";
    fs::remove_all(dir);
    const std::string exportCmd = amrvkBinary() + " shaders --export " + dir.string() + " >/dev/null 2>" +
                                  (dir.string() + ".err");
    ASSERT_EQ(std::system(exportCmd.c_str()), 0);
    const int again = std::system(exportCmd.c_str());
    EXPECT_TRUE(WIFEXITED(again) && WEXITSTATUS(again) == 1);
    EXPECT_NE(test::readAll(dir.string() + ".err").find("exists (give --force to overwrite)"), std::string::npos);
    // Every embedded shader compiles from the exported copy (passes/ found under the root).
    const gpu::ShaderLibrary copy(dir);
    for (const char* name : {"path_trace", "majorants", "domain_aabbs", "display"})
        EXPECT_GT(copy.load(name).size(), 5u) << name;
    // ... and it is the copy that is compiled: a broken copy is an error naming its file and line.
    test::writeAll(dir / "passes/majorants.comp", "#version 460\nvoid main() { undeclared = 1; }\n");
    try {
        copy.load("majorants");
        ADD_FAILURE() << "the broken copy compiled";
    } catch (const gpu::ShaderCompileError& e) {
        EXPECT_NE(e.file().find("majorants.comp"), std::string::npos) << e.what();
        EXPECT_EQ(e.line(), 2) << e.what();
    }
}

}  // namespace
