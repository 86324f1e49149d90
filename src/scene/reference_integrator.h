#pragma once
// CPU reference integrator: the estimators of path_trace.comp (ae, ss, ms with delta tracking,
// ratio-tracked shadow rays, Henyey-Greenstein phase, Russian roulette) in double precision, but
// built on independent parts: the brute-force reconstruction (amr::ReferenceSampler, no bricks)
// and one global majorant (max TF alpha over the data's value range) instead of macrocells.
// Slow by design; for tests on small images.
#include <glm/glm.hpp>

#include "amr/model.h"
#include "amr/sampler.h"
#include "scene/render_output.h"
#include "scene/render_settings.h"
#include "scene/transfer_function.h"

namespace amrvk::scene {

// The same RNG as shaders/lib/rng.glsl (a PCG hash), in double for the uniform variates.
class Rng {
public:
    explicit Rng(uint32_t seed) : mState(seed) {}
    static uint32_t pcgHash(uint32_t v);
    static uint32_t seed(uint32_t pixel, uint32_t frame, uint32_t seed);
    double next();  // [0, 1) with 24 random bits, like rand() in rng.glsl

private:
    uint32_t mState;
};

double henyeyGreenstein(double cosTheta, double g);
glm::dvec3 sampleHenyeyGreenstein(glm::dvec3 d, double g, double u1, double u2);

class ReferenceIntegrator {
public:
    ReferenceIntegrator(const amr::Model& model, const amr::Field& field, const TransferFunction& tf);
    // Renders `spp` samples per pixel; returns mean and per-pixel sum of squares like Renderer.
    RenderOutput render(const RenderSettings& settings, uint32_t spp) const;

    // Transmittance estimators along o + t d (voxel space, t in voxel units, [0, tMax]), both
    // consumers of sampleTmaj.
    bool deltaTrack(glm::dvec3 o, glm::dvec3 d, double tMax, Rng& rng, double& tHit, glm::dvec4& tf,
                    double densityScale) const;
    double ratioTrack(glm::dvec3 o, glm::dvec3 d, double tMax, Rng& rng, double densityScale) const;

private:
    // The one tracking loop (pbrt-v4's SampleT_maj; GLSL twin sampleTmaj in tracking.glsl) over
    // the single segment of the global majorant: exponential steps, each tentative collision
    // handed to onCollision(t, sigma, majorant, tf), which returns false to stop.
    template <typename OnCollision>
    void sampleTmaj(glm::dvec3 o, glm::dvec3 d, double tMax, Rng& rng, double densityScale,
                    OnCollision&& onCollision) const;
    double extinction(glm::dvec3 p, glm::dvec4& tf, double densityScale) const;
    glm::dvec3 radiance(const RenderSettings& s, glm::dvec3 o, glm::dvec3 d, Rng& rng) const;

    const amr::Model& mModel;
    const TransferFunction& mTf;
    amr::ReferenceSampler mSampler;
    amr::Box3l mBounds;
    double mInvFinest = 1;
    double mMaxAlpha = 0;  // global majorant before densityScale / finest width
};

}  // namespace amrvk::scene
