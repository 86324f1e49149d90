#pragma once
// What a picture depends on besides the data, the TF and the structures: render mode, image size,
// seed, camera, medium scale and lighting. World space throughout; lightsInVoxelSpace converts
// the lights for the shaders and the CPU reference.
#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "amr/model.h"
#include "scene/camera.h"
#include "scene/cut_away.h"
#include "shared/kinds.h"

namespace amrvk::scene {

// ae | ss | ms: unbiased path tracing. dvr: the ray-marching baseline (biased by its step).
// Defined once for C++ and GLSL in shaders/shared/kinds.h.
using shared::Mode;
Mode parseMode(const std::string& name);
const char* modeName(Mode mode);

// Shadow rays' transmittance estimator (lib/unbiased_march.glsl): ratio (ratio tracking, the
// default) | ubrm (unbiased ray marching). Both are unbiased; they differ in cost and variance.
using shared::Transmittance;
Transmittance parseTransmittance(const std::string& name);
const char* transmittanceName(Transmittance t);
// The trackers' control extinction (lib/tracking.glsl): none (the default) | minorant (the least
// TF extinction over each macrocell's value range, on grid traversals over data whose leaf cells
// tile their bounds): free flight by decomposition tracking, ratio-tracked shadows by residual ratio
// tracking. Unbiased either way; fewer lookups where the medium is dense throughout a macrocell.
using shared::ControlExtinction;
ControlExtinction parseControlExtinction(const std::string& name);
const char* controlExtinctionName(ControlExtinction c);
// The modes whose paths cast shadow rays (the only ones the shadow estimator changes).
inline bool castsShadowRays(Mode mode) { return mode == Mode::Ss || mode == Mode::Ms; }

struct Light {
    bool point = false;
    glm::dvec3 posOrDir{0.0, 0.0, 1.0};  // world position, or world direction towards the light
    glm::dvec3 radiance{1.0};            // radiance (directional) or intensity (point, 1/d^2 in world units)
    bool operator==(const Light&) const = default;
};

// A light in voxel space: point position or unit direction towards the light; radiance
// (directional) or intensity scaled so that 1/d^2 with d in voxel units equals the world falloff.
struct VoxelLight {
    bool point = false;
    glm::dvec3 posOrDir{0.0};
    glm::dvec3 radiance{0.0};
};

struct RenderSettings {
    Mode mode = Mode::Ms;
    int width = 256, height = 256;
    uint32_t seed = 1;
    Camera camera;
    double densityScale = 1.0;
    double g = 0.0;                      // Henyey-Greenstein asymmetry, clamped to [-0.999, 0.999]
    glm::dvec3 ambient{1.0};             // environment radiance seen by escaping rays
    std::optional<glm::dvec3> background;  // seen by escaping primary rays; default = ambient
    std::vector<Light> lights;           // at most shared::kMaxLights
    uint32_t maxTrackingSteps = 1u << 22;  // per tracking call; paths reaching it are counted (biased)
    Transmittance transmittance = Transmittance::Ratio;  // ss and ms shadow rays
    ControlExtinction controlExtinction = ControlExtinction::None;  // ae, ss, ms trackers
    double dvrStep = 0.5;                // dvr: step / finest cell width at the sample (ExaBrick's dt)
    bool dvrShading = false;             // dvr: gradient shading by the first directional light (else a headlight)
    CutAway cut;                         // crop box and clip planes (world); the medium beyond is empty
    bool operator==(const RenderSettings&) const = default;
};

// Throws a one-line error naming the option for a value no renderer takes: size outside 1..16384,
// a negative or non-finite density scale, dt, ambient or background, more than kMaxLights lights,
// a camera whose eye and target coincide or whose up is parallel to the view, an invalid cut-away.
void validateSettings(const RenderSettings& settings);

std::vector<VoxelLight> lightsInVoxelSpace(const RenderSettings& settings, const amr::Transform& voxelToWorld);

}  // namespace amrvk::scene
