// The dvr ray-marching baseline (shaders/lib/ray_march.glsl) against closed forms: on a constant
// slab its jittered Riemann sum has a known expectation (including its step-size bias), which
// tends to the exact absorption+emission answer as the step shrinks; gradient shading scales the
// colour by the Lambert term of the field's gradient.
#include <cmath>

#include "gpu_fixture.h"
#include "image_compare.h"
#include "render/renderer.h"
#include "render_fixtures.h"

using namespace amrvk;

namespace {

class RayMarchGpu : public test::GpuTest {
protected:
    scene::RenderOutput renderDvr(const amr::Model& m, const scene::TransferFunction& tf,
                                   const scene::RenderSettings& s, uint32_t spp) {
        auto r = test::makeRenderer(ctx(), m, test::gridDda(scene::SamplerKind::ExtBrick, "16"));
        r->setTransferFunction(tf);
        scene::RenderOutput o = r->render(s, spp);
        EXPECT_EQ(o.stats.counter(shared::kCounterNanSamples), 0u);
        return o;
    }
};

// Level-0 slab [0,64)^2 x [0,4), viewed from above through a narrow field of view.
amr::Model slabModel() { return test::makeUniformBox({64, 64, 4}, 0, 1.0f); }
scene::Camera slabCamera() {
    scene::Camera c;
    c.eye = {32.0, 32.0, 100.0};
    c.target = {32.0, 32.0, 0.0};
    c.up = {0.0, 1.0, 0.0};
    c.fovYDegrees = 20.0;
    return c;
}

// Image mean against the mean of expected(path length in the slab) over every pixel's footprint
// (4x4 sub-samples), z-test on the per-pixel variances; returns the expected image mean (rgb avg).
double expectSlabMean(const scene::RenderOutput& o, const scene::RenderSettings& s,
                      const std::function<glm::dvec3(double)>& expected) {
    scene::RayBasis rb = scene::makeRayBasis(s.camera, s.width, s.height, amr::Transform{});
    const double z = test::sidakZ(1e-4, 3);
    glm::dvec3 sumDiff(0.0), var(0.0), sumExpect(0.0);
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const size_t i = size_t(y) * size_t(s.width) + size_t(x);
            glm::dvec3 e(0.0);
            for (int k = 0; k < 16; ++k) {
                glm::dvec3 d = glm::normalize(rb.dir00 + (x + (k % 4 + 0.5) / 4) * rb.du + (y + (k / 4 + 0.5) / 4) * rb.dv);
                e += expected(4.0 / std::abs(d.z));
            }
            e /= 16.0;
            sumExpect += e;
            for (int ch = 0; ch < 3; ++ch) {
                sumDiff[ch] += o.mean.pixels[i][ch] - e[ch];
                var[ch] += test::sampleVariance(o, i, ch) / o.spp;
            }
        }
    const double n = double(s.width) * s.height;
    for (int ch = 0; ch < 3; ++ch)
        EXPECT_LE(std::abs(sumDiff[ch] / n), z * std::sqrt(var[ch]) / n + 1e-5) << "channel " << ch;
    return (sumExpect.x + sumExpect.y + sumExpect.z) / (3.0 * n);
}

}  // namespace

// Samples at t0 + (u + k) h, u uniform: n = m + 1 samples when u < f, else m (D / h = m + f), each
// with opacity 1 - e^(-sigma h), so E = c + (bg - c) (f e^(-sigma h (m+1)) + (1 - f) e^(-sigma h m)).
TEST_F(RayMarchGpu, ConstantSlabMatchesTheJitteredRiemannSum) {
    amr::Model m = slabModel();
    const glm::dvec3 c(0.9, 0.5, 0.2), bg(0.1, 0.3, 0.6);
    const double sigma = 0.5;
    double biasCoarse = 0;
    for (double dt : {1.5, 0.125}) {
        scene::RenderSettings s;
        s.mode = scene::Mode::Dvr;
        s.dvrStep = dt;
        s.width = s.height = 32;
        s.densityScale = sigma;
        s.ambient = bg;
        s.camera = slabCamera();
        scene::RenderOutput o = renderDvr(m, test::constantTf(glm::vec3(c), 1.0f), s, 64);
        const double h = dt;
        const double dvrMean = expectSlabMean(o, s, [&](double D) {
            const double m_ = std::floor(D / h), f = D / h - m_;
            const double T = f * std::exp(-sigma * h * (m_ + 1)) + (1 - f) * std::exp(-sigma * h * m_);
            return c + (bg - c) * T;
        });
        // The exact absorption+emission answer for the same rays.
        double exactMean = 0;
        {
            scene::RayBasis rb = scene::makeRayBasis(s.camera, s.width, s.height, amr::Transform{});
            for (int y = 0; y < s.height; ++y)
                for (int x = 0; x < s.width; ++x)
                    for (int k = 0; k < 16; ++k) {
                        glm::dvec3 d = glm::normalize(rb.dir00 + (x + (k % 4 + 0.5) / 4) * rb.du + (y + (k / 4 + 0.5) / 4) * rb.dv);
                        const glm::dvec3 e = c + (bg - c) * std::exp(-sigma * 4.0 / std::abs(d.z));
                        exactMean += (e.x + e.y + e.z) / 3.0;
                    }
            exactMean /= 16.0 * s.width * s.height;
        }
        const double bias = std::abs(dvrMean - exactMean);
        if (dt == 1.5) {
            biasCoarse = bias;
            EXPECT_GT(bias, 1e-3) << "a step of 1.5 cells must show its bias";
        } else {
            EXPECT_LT(bias, 0.02 * biasCoarse) << "the bias shrinks with the step (second order)";
        }
    }
}

// A field linear in x: the gradient is +x inside, so a light along x leaves the colour unchanged
// and a light along y scales it to the ambient term 0.3; same seed, so the ratio is exact per pixel.
TEST_F(RayMarchGpu, GradientShadingFollowsTheLambertTerm) {
    amr::Model m = slabModel();
    for (size_t i = 0; i < m.cells.size(); ++i) m.fields[0].values[i] = float(m.cells[i].lower.x) + 0.5f;
    scene::RenderSettings s;
    s.mode = scene::Mode::Dvr;
    s.dvrShading = true;
    s.width = s.height = 16;
    s.densityScale = 0.2;
    s.ambient = glm::dvec3(0.0);
    s.camera = slabCamera();
    s.lights = {{false, {1.0, 0.0, 0.0}, glm::dvec3(1.0)}};
    const auto tf = test::constantTf(glm::vec3(0.8f, 0.6f, 0.4f), 1.0f);
    scene::RenderOutput lit = renderDvr(m, tf, s, 2);
    s.lights = {{false, {0.0, 1.0, 0.0}, glm::dvec3(1.0)}};
    scene::RenderOutput grazing = renderDvr(m, tf, s, 2);
    s.dvrShading = false;
    scene::RenderOutput flat = renderDvr(m, tf, s, 2);
    for (size_t i = 0; i < lit.mean.pixels.size(); ++i)
        for (int ch = 0; ch < 3; ++ch) {
            ASSERT_GT(flat.mean.pixels[i][ch], 0.01f);
            EXPECT_NEAR(lit.mean.pixels[i][ch] / flat.mean.pixels[i][ch], 1.0, 1e-3) << "pixel " << i;
            EXPECT_NEAR(grazing.mean.pixels[i][ch] / flat.mean.pixels[i][ch], 0.3, 1e-3) << "pixel " << i;
        }
}
