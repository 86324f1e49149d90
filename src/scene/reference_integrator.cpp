#include "scene/reference_integrator.h"

#include <algorithm>
#include <cmath>

#include "accel/ray_box.h"
#include "core/error.h"

namespace amrvk::scene {

uint32_t Rng::pcgHash(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint32_t Rng::seed(uint32_t pixel, uint32_t frame, uint32_t s) { return pcgHash(pixel ^ pcgHash(frame ^ pcgHash(s))); }

double Rng::next() {
    mState = mState * 747796405u + 2891336453u;
    uint32_t word = ((mState >> ((mState >> 28u) + 4u)) ^ mState) * 277803737u;
    word = (word >> 22u) ^ word;
    return double(word >> 8) * (1.0 / 16777216.0);
}

double henyeyGreenstein(double cosTheta, double g) {
    double denom = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * M_PI * denom * std::sqrt(std::max(denom, 1e-300)));
}

glm::dvec3 sampleHenyeyGreenstein(glm::dvec3 d, double g, double u1, double u2) {
    double cosTheta;
    if (std::abs(g) < 1e-3) {
        cosTheta = 1.0 - 2.0 * u1;
    } else {
        double sq = (1.0 - g * g) / (1.0 - g + 2.0 * g * u1);
        cosTheta = (1.0 + g * g - sq * sq) / (2.0 * g);
    }
    cosTheta = std::clamp(cosTheta, -1.0, 1.0);
    double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    double phi = 2.0 * M_PI * u2;
    // Any orthonormal basis around d (a different construction from the shader's on purpose).
    glm::dvec3 helper = std::abs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 t = glm::normalize(glm::cross(d, helper)), b = glm::cross(d, t);
    return glm::normalize(sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + cosTheta * d);
}

ReferenceIntegrator::ReferenceIntegrator(const amr::Model& model, const amr::Field& field,
                                         const TransferFunction& tf)
    : mModel(model), mTf(tf), mSampler(model, field) {
    amr::ModelSummary s = amr::summarize(model);
    mBounds = s.bounds;
    mInvFinest = 1.0 / double(amr::cellWidth(s.minLevel));
    amr::FieldStats st = amr::computeFieldStats(model, field);
    mMaxAlpha = tf.maxAlpha(st.minValue, st.maxValue);
}

double ReferenceIntegrator::extinction(glm::dvec3 p, glm::dvec4& tf, double densityScale) const {
    amr::Sample s = mSampler.sample(p);
    if (!s.valid() || !mSampler.insideLeafCell(p)) {
        tf = glm::dvec4(0.0);
        return 0.0;
    }
    tf = glm::dvec4(mTf.evaluate(float(s.value)));
    return tf.a * densityScale * mInvFinest;
}

template <typename OnCollision>
void ReferenceIntegrator::sampleTmaj(glm::dvec3 o, glm::dvec3 d, double tMax, Rng& rng, double densityScale,
                                     OnCollision&& onCollision) const {
    double t0 = 0, t1 = tMax;
    const double maj = mMaxAlpha * densityScale * mInvFinest;
    if (!accel::clipRay(glm::dvec3(mBounds.lower), glm::dvec3(mBounds.upper), o, d, t0, t1) || !(maj > 0)) return;
    for (double t = t0;;) {
        t -= std::log(1.0 - rng.next()) / maj;
        if (t >= t1) return;
        glm::dvec4 tf;
        const double sigma = extinction(o + d * t, tf, densityScale);
        if (!onCollision(t, sigma, maj, tf)) return;
    }
}

bool ReferenceIntegrator::deltaTrack(glm::dvec3 o, glm::dvec3 d, double tMax, Rng& rng, double& tHit,
                                     glm::dvec4& tf, double densityScale) const {
    bool hit = false;
    sampleTmaj(o, d, tMax, rng, densityScale, [&](double t, double sigma, double maj, const glm::dvec4& tfc) {
        if (rng.next() * maj < sigma) {
            hit = true;
            tHit = t;
            tf = tfc;
            return false;
        }
        return true;
    });
    return hit;
}

double ReferenceIntegrator::ratioTrack(glm::dvec3 o, glm::dvec3 d, double tMax, Rng& rng, double densityScale) const {
    double tr = 1.0;
    sampleTmaj(o, d, tMax, rng, densityScale, [&](double, double sigma, double maj, const glm::dvec4&) {
        tr *= std::max(0.0, 1.0 - sigma / maj);
        if (tr < 0.05) {
            if (rng.next() * 0.05 >= tr) {
                tr = 0.0;
                return false;
            }
            tr = 0.05;
        }
        return true;
    });
    return tr;
}

glm::dvec3 ReferenceIntegrator::radiance(const RenderSettings& s, glm::dvec3 o, glm::dvec3 d, Rng& rng) const {
    const glm::dvec3 background = s.background.value_or(s.ambient);
    const double g = std::clamp(s.g, -0.999, 0.999), ds = s.densityScale;
    const auto lights = lightsInVoxelSpace(s, mModel.voxelToWorld);
    double tHit = 0;
    glm::dvec4 tf;
    auto lightTerm = [&](glm::dvec3 p, glm::dvec3 dir, size_t k) -> glm::dvec3 {
        if (k == lights.size()) {
            glm::dvec3 wi = sampleHenyeyGreenstein(dir, g, rng.next(), rng.next());
            return s.ambient * ratioTrack(p, wi, INFINITY, rng, ds);
        }
        const VoxelLight& L = lights[k];
        glm::dvec3 wi = L.posOrDir, Le = L.radiance;
        double dist = INFINITY;
        if (L.point) {
            glm::dvec3 to = L.posOrDir - p;
            dist = glm::length(to);
            if (!(dist > 0)) return glm::dvec3(0.0);
            wi = to / dist;
            Le /= dist * dist;
        }
        return Le * henyeyGreenstein(glm::dot(dir, wi), g) * ratioTrack(p, wi, dist, rng, ds);
    };
    if (s.mode == Mode::Ae) return deltaTrack(o, d, INFINITY, rng, tHit, tf, ds) ? glm::dvec3(tf) : background;
    if (s.mode == Mode::Ss) {
        if (!deltaTrack(o, d, INFINITY, rng, tHit, tf, ds)) return background;
        bool ambientOn = glm::any(glm::greaterThan(s.ambient, glm::dvec3(0.0)));
        size_t n = lights.size() + (ambientOn ? 1 : 0);
        if (n == 0) return glm::dvec3(0.0);
        size_t k = std::min(size_t(rng.next() * double(n)), n - 1);
        return glm::dvec3(tf) * double(n) * lightTerm(o + d * tHit, d, k);
    }
    glm::dvec3 throughput(1.0), L(0.0);
    for (uint32_t bounce = 0;; ++bounce) {
        if (!deltaTrack(o, d, INFINITY, rng, tHit, tf, ds)) {
            L += throughput * (bounce == 0 ? background : s.ambient);
            break;
        }
        if (bounce + 1 >= shared::kMaxBounces) break;
        throughput *= glm::dvec3(tf);
        o += d * tHit;
        if (!lights.empty()) {
            size_t k = std::min(size_t(rng.next() * double(lights.size())), lights.size() - 1);
            L += throughput * double(lights.size()) * lightTerm(o, d, k);
        }
        double q = std::max({throughput.r, throughput.g, throughput.b});
        if (!(q > 0)) break;
        if (q < 0.25) {
            double survive = q / 0.25;
            if (rng.next() >= survive) break;
            throughput /= survive;
        }
        d = sampleHenyeyGreenstein(d, g, rng.next(), rng.next());
    }
    return L;
}

RenderOutput ReferenceIntegrator::render(const RenderSettings& s, uint32_t spp) const {
    RayBasis rb = makeRayBasis(s.camera, s.width, s.height, mModel.voxelToWorld);
    RenderOutput out;
    out.spp = spp;
    out.mean = Image(s.width, s.height);
    out.sumSq.assign(out.mean.pixels.size(), glm::vec4(0.0f));
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const uint32_t pixel = uint32_t(y * s.width + x);
            glm::dvec3 sum(0.0), sumSq(0.0);
            for (uint32_t f = 0; f < spp; ++f) {
                Rng rng(Rng::seed(pixel, f, s.seed ^ 0x5bd1e995u));
                double jx = rng.next(), jy = rng.next();
                glm::dvec3 d = glm::normalize(rb.dir00 + (x + jx) * rb.du + (y + jy) * rb.dv);
                glm::dvec3 L = radiance(s, rb.eye, d, rng);
                sum += L;
                sumSq += L * L;
            }
            out.mean.pixels[pixel] = glm::vec4(glm::vec3(sum / double(spp)), 1.0f);
            out.sumSq[pixel] = glm::vec4(glm::vec3(sumSq), float(spp));
        }
    out.stats.paths = uint64_t(spp) * uint64_t(s.width) * uint64_t(s.height);
    return out;
}

}  // namespace amrvk::scene
