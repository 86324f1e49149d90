// TF colours as display colours (scene/tf_colors.h, issue 35), against the answer: a constant slab
// of value 1, four cells thick, seen from above in ae mode on black. Opaque, every pixel is the TF
// colour itself (within 1/255 in 8 bits), through the picture entry, `amrvk render`'s PNG and
// `amrvk view`'s screenshot PNG alike (the Python module: tests/python/test_tf_colors.py); a colour
// between two nodes is the map interpolated as given. Of optical depth tau, the image mean is
// decode(c) (1 - exp(-tau)), composited in linear, and its 8-bit encoding is that value encoded once.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "amr/cells_writer.h"
#include "amr/readers.h"
#include "core/image_io.h"
#include "gpu_fixture.h"
#include "image_compare.h"
#include "picture/picture.h"
#include "render_fixtures.h"
#include "scene/camera.h"
#include "scene/tf_colors.h"
#include "scene/tf_files.h"
#include "test_data.h"

using namespace amrvk;
namespace fs = std::filesystem;
using scene::TfColors;

namespace {

class TfColorsGpu : public test::GpuTest {};

constexpr double kSlabCells = 4.0;  // the slab [0, 64)^2 x [0, 4) in finest cells

scene::Camera slabCamera() {
    scene::Camera c;
    c.eye = {32.0, 32.0, 100.0};
    c.target = {32.0, 32.0, 0.0};
    c.up = {0.0, 1.0, 0.0};
    c.fovYDegrees = 20.0;  // every ray crosses the slab's top and bottom faces
    return c;
}

// The slab picture with `tf` (display colours), extinction densityScale x alpha per cell width.
picture::Picture slabPicture(gpu::Context& ctx, const scene::TransferFunction& tf, double densityScale,
                             TfColors colors, uint32_t spp) {
    session::PictureDescription d;
    d.session.input = "slab";
    scene::RenderSettings& s = d.session.settings;
    s.mode = scene::Mode::Ae;
    s.width = s.height = 24;
    s.densityScale = densityScale;
    s.background = glm::dvec3(0.0);
    s.camera = slabCamera();
    d.session.spp = spp;
    d.session.tf = scene::TfChannels::split(tf);
    d.session.tfColors = colors;
    d.session.structure = test::gridDda(scene::SamplerKind::ExtBrick, "16");
    return picture::makePicture(ctx, scene::makeVolume(test::makeUniformBox({64, 64, 4}, 0, 1.0f)), d);
}

int code(double display) { return int(std::lround(std::clamp(display, 0.0, 1.0) * 255.0)); }

// Every pixel's 8-bit colour within one step of `expected` (0..255); returns the number checked.
int expectEveryPixel(const std::vector<glm::ivec3>& pixels, glm::ivec3 expected, const std::string& what) {
    int wrong = 0;
    for (size_t i = 0; i < pixels.size(); ++i)
        if (glm::any(glm::greaterThan(glm::abs(pixels[i] - expected), glm::ivec3(1))) && ++wrong <= 3)
            ADD_FAILURE() << what << ": pixel " << i << " is " << pixels[i].r << " " << pixels[i].g << " "
                          << pixels[i].b << ", expected " << expected.r << " " << expected.g << " " << expected.b;
    EXPECT_EQ(wrong, 0) << what;
    return int(pixels.size());
}

std::vector<glm::ivec3> encoded(const Image& mean) {
    std::vector<glm::ivec3> out;
    for (const glm::vec4& p : mean.pixels) out.emplace_back(encodeSrgb8(p.r), encodeSrgb8(p.g), encodeSrgb8(p.b));
    return out;
}

std::vector<glm::ivec3> pngPixels(const fs::path& file) {
    const Image8 png = readPng(file);
    std::vector<glm::ivec3> out;
    for (size_t i = 0; i + 3 < png.rgba.size(); i += 4) out.emplace_back(png.rgba[i], png.rgba[i + 1], png.rgba[i + 2]);
    return out;
}

const glm::vec3 kColour(0.2f, 0.4f, 0.6f);  // the ParaView colour: 51 102 153 in 8 bits

}  // namespace

TEST_F(TfColorsGpu, AnOpaqueSlabShowsTheTfColourItself) {
    const scene::TransferFunction tf = test::constantTf(kColour, 1.0f);
    // Optical depth 400: every sample hits, so every pixel is the albedo exactly.
    picture::Picture p = slabPicture(ctx(), tf, 100.0, TfColors::Srgb, 2);
    expectEveryPixel(encoded(p.render().mean), {51, 102, 153}, "srgb");
    // --tf-colors linear keeps the old meaning: the colour taken as linear, (124, 170, 203).
    p.setTfColors(TfColors::Linear);
    expectEveryPixel(encoded(p.render().mean), {code(scene::linearToSrgb(0.2)), code(scene::linearToSrgb(0.4)),
                                                code(scene::linearToSrgb(0.6))},
                     "linear");
    EXPECT_EQ(p.session().tfColors, TfColors::Linear);
    // Between two nodes the map is interpolated as given: halfway from black to white is display
    // 0.5 (128), not the linear midpoint (188).
    const scene::TransferFunction ramp({0.0f, 2.0f}, {glm::vec4(0, 0, 0, 1), glm::vec4(1, 1, 1, 1)});
    expectEveryPixel(encoded(slabPicture(ctx(), ramp, 100.0, TfColors::Srgb, 2).render().mean), {128, 128, 128},
                     "black to white at the middle");
}

TEST_F(TfColorsGpu, ASemiTransparentSlabIsCompositedInLinearAndEncodedOnce) {
    const glm::dvec3 c(0.9, 0.5, 0.2);
    const double sigma = 0.175;  // per cell width: tau = 0.7 straight down
    picture::Picture p = slabPicture(ctx(), test::constantTf(glm::vec3(c), 1.0f), sigma, TfColors::Srgb, 256);
    const scene::RenderOutput o = p.render();
    const scene::RenderSettings s = p.session().settings;
    // Expected per pixel: decode(c) (1 - exp(-sigma * path length)), over 4x4 sub-pixel rays.
    const glm::dvec3 albedo(scene::srgbToLinear(c.r), scene::srgbToLinear(c.g), scene::srgbToLinear(c.b));
    const scene::RayBasis rb = scene::makeRayBasis(s.camera, s.width, s.height, amr::Transform{});
    glm::dvec3 sumDiff(0.0), var(0.0), sumExpected(0.0), sumMean(0.0);
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const size_t i = size_t(y) * size_t(s.width) + size_t(x);
            double opacity = 0;
            for (int k = 0; k < 16; ++k) {
                const glm::dvec3 d =
                    glm::normalize(rb.dir00 + (x + (k % 4 + 0.5) / 4) * rb.du + (y + (k / 4 + 0.5) / 4) * rb.dv);
                opacity += (1.0 - std::exp(-sigma * kSlabCells / std::abs(d.z))) / 16.0;
            }
            sumExpected += albedo * opacity;
            for (int ch = 0; ch < 3; ++ch) {
                sumMean[ch] += o.mean.pixels[i][ch];
                sumDiff[ch] += o.mean.pixels[i][ch] - albedo[ch] * opacity;
                var[ch] += test::sampleVariance(o, i, ch) / o.spp;
            }
        }
    const double n = double(s.width) * s.height, z = test::sidakZ(1e-4, 3);
    for (int ch = 0; ch < 3; ++ch) {
        EXPECT_GT(var[ch], 0.0);
        EXPECT_LE(std::abs(sumDiff[ch]) / n, z * std::sqrt(var[ch]) / n) << "channel " << ch;
        // Encoded once: the 8-bit value of the linear mean is that of the answer.
        const double mean = sumMean[ch] / n, answer = sumExpected[ch] / n;
        EXPECT_LE(std::abs(int(encodeSrgb8(float(mean))) - code(scene::linearToSrgb(answer))), 1) << "channel " << ch;
        // Power: neither display-space compositing c (1 - exp(-tau)) (ParaView's blend) nor the old
        // linear meaning encode(c (1 - exp(-tau))) is within 5 steps of it.
        const double opacity = answer / albedo[ch];
        EXPECT_GT(std::abs(int(encodeSrgb8(float(mean))) - code(c[ch] * opacity)), 5) << "channel " << ch;
        EXPECT_GT(std::abs(int(encodeSrgb8(float(mean))) - code(scene::linearToSrgb(c[ch] * opacity))), 5)
            << "channel " << ch;
    }
}

TEST_F(TfColorsGpu, RenderAndViewScreenshotPngsShowTheTfColour) {
    const std::string binary = std::string(AMRVK_BINARY_DIR) + "/bin/amrvk";
    if (!fs::exists(binary)) GTEST_SKIP() << "amrvk binary not built: " << binary;
    const fs::path dir = test::scratchDir();
    amr::writeExaBrick(test::makeUniformBox({64, 64, 4}, 0, 1.0f), dir / "slab", true);
    {
        std::ofstream tf(dir / "tf.json");
        tf << scene::paraViewPresetJson(scene::TfChannels::split(test::constantTf(kColour, 1.0f)));
    }
    const std::string picture = " --tf " + (dir / "tf.json").string() +
                                " --mode ae --background 0 0 0 --density-scale 100 --size 24x24 --camera 32 32 100 32 "
                                "32 0 0 1 0 --fov 20 --grid 16 --backend sw";
    const std::string slab = (dir / "slab.cells").string();
    auto run = [&](const std::string& args, const std::string& tag) {
        const std::string command = binary + " " + args + " >" + (dir / (tag + ".out")).string() + " 2>" +
                                    (dir / (tag + ".err")).string();
        EXPECT_EQ(std::system(command.c_str()), 0) << command << "\n" << test::readAll(dir / (tag + ".err"));
    };
    run("render " + slab + picture + " --spp 2 -o " + (dir / "render.png").string(), "render");
    // The viewer's own TF path too: a script edit sets the TF again (its range; the colour is constant).
    {
        std::ofstream script(dir / "script.txt");
        script << "1 tf-range 0.5 1.5\n";
    }
    run("view " + slab + picture + " --spp 2 --headless --frames 20 --script " + (dir / "script.txt").string() +
            " --screenshot " + (dir / "view.png").string(),
        "view");
    run("render " + slab + picture + " --tf-colors linear --spp 2 -o " + (dir / "linear.png").string(), "linear");
    // The viewer's switch (the "sRGB colours" checkbox's script twin), and its session says so.
    {
        std::ofstream script(dir / "switch.txt");
        script << "1 tf-colors linear\n";
    }
    run("view " + slab + picture + " --spp 2 --headless --frames 20 --script " + (dir / "switch.txt").string() +
            " --screenshot " + (dir / "view-linear.png").string() + " --save-session " + (dir / "s.json").string(),
        "view-linear");
    expectEveryPixel(pngPixels(dir / "view-linear.png"), {124, 170, 203}, "view after tf-colors linear");
    EXPECT_EQ(session::loadSession(dir / "s.json").tfColors, TfColors::Linear);
    EXPECT_EQ(expectEveryPixel(pngPixels(dir / "render.png"), {51, 102, 153}, "render"), 24 * 24);
    EXPECT_EQ(expectEveryPixel(pngPixels(dir / "view.png"), {51, 102, 153}, "view screenshot"), 24 * 24);
    expectEveryPixel(pngPixels(dir / "linear.png"), {124, 170, 203}, "render --tf-colors linear");
}
