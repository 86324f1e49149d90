#include "scene/render_settings.h"

#include <cmath>

#include "core/error.h"
#include "core/strings.h"
#include "scene/limits.h"
#include "shared/render_params.h"

namespace amrvk::scene {

namespace {
constexpr Named<Mode> kModes[] = {{"ae", Mode::Ae}, {"ss", Mode::Ss}, {"ms", Mode::Ms}, {"dvr", Mode::Dvr}};
}

Mode parseMode(const std::string& name) { return parseNamed(kModes, name, "--mode"); }
const char* modeName(Mode mode) { return nameOf(kModes, mode); }

namespace {
constexpr Named<Transmittance> kTransmittances[] = {{"ratio", Transmittance::Ratio}, {"ubrm", Transmittance::Ubrm}};
}

Transmittance parseTransmittance(const std::string& name) {
    return parseNamed(kTransmittances, name, "--transmittance");
}
const char* transmittanceName(Transmittance t) { return nameOf(kTransmittances, t); }

namespace {
constexpr Named<ControlExtinction> kControls[] = {{"none", ControlExtinction::None},
                                                  {"minorant", ControlExtinction::Minorant}};
}

ControlExtinction parseControlExtinction(const std::string& name) {
    return parseNamed(kControls, name, "--control-extinction");
}
const char* controlExtinctionName(ControlExtinction c) { return nameOf(kControls, c); }

namespace {
bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

void validateSettings(const RenderSettings& s) {
    AMRVK_CHECK(s.width > 0 && s.height > 0 && s.width <= kMaxImageSide && s.height <= kMaxImageSide, "--size ",
                s.width, "x", s.height, " is outside 1..", kMaxImageSide);
    AMRVK_CHECK(s.densityScale >= 0 && std::isfinite(s.densityScale), "--density-scale ", s.densityScale,
                " must be finite and >= 0");
    AMRVK_CHECK(s.dvrStep > 0 && std::isfinite(s.dvrStep), "--dt ", s.dvrStep, " must be finite and > 0");
    AMRVK_CHECK(std::isfinite(s.g), "--g ", s.g, " must be finite");
    AMRVK_CHECK(s.maxTrackingSteps >= 1, "internal: maxTrackingSteps must be >= 1");
    AMRVK_CHECK(finite(s.ambient) && glm::all(glm::greaterThanEqual(s.ambient, glm::dvec3(0.0))),
                "--ambient must be finite and >= 0");
    AMRVK_CHECK(!s.background || (finite(*s.background) &&
                                  glm::all(glm::greaterThanEqual(*s.background, glm::dvec3(0.0)))),
                "--background must be finite and >= 0");
    AMRVK_CHECK(s.lights.size() <= shared::kMaxLights, "at most ", shared::kMaxLights, " lights (got ",
                s.lights.size(), ")");
    for (const Light& L : s.lights) {
        AMRVK_CHECK(finite(L.posOrDir) && finite(L.radiance) &&
                        glm::all(glm::greaterThanEqual(L.radiance, glm::dvec3(0.0))),
                    L.point ? "--light-point" : "--light-dir", ": position, direction and radiance must be finite, "
                    "radiance >= 0");
        AMRVK_CHECK(L.point || glm::length(L.posOrDir) > 0, "--light-dir: the direction 0 0 0 points nowhere");
    }
    AMRVK_CHECK(validFov(s.camera.fovYDegrees), "--fov: ", s.camera.fovYDegrees, " is outside (0, ", kMaxFovDegrees,
                ")");
    AMRVK_CHECK(finite(s.camera.eye) && finite(s.camera.target) && finite(s.camera.up),
                "--camera: eye, target and up must be finite");
    validateCutAway(s.cut);
    const glm::dvec3 forward = s.camera.target - s.camera.eye;
    AMRVK_CHECK(glm::length(forward) > 0, "--camera: eye and target coincide");
    AMRVK_CHECK(glm::length(glm::cross(glm::normalize(forward), s.camera.up)) > 1e-12,
                "--camera: up vector is parallel to the view direction");
}

std::vector<VoxelLight> lightsInVoxelSpace(const RenderSettings& s, const amr::Transform& xf) {
    AMRVK_CHECK(s.lights.size() <= shared::kMaxLights, "at most ", shared::kMaxLights, " lights (got ",
                s.lights.size(), ")");
    const double meanScale = std::cbrt(xf.scale.x * xf.scale.y * xf.scale.z);
    std::vector<VoxelLight> out;
    for (const Light& L : s.lights) {
        if (L.point) {
            out.push_back({true, (L.posOrDir - xf.origin) / xf.scale, L.radiance / (meanScale * meanScale)});
        } else {
            AMRVK_CHECK(glm::length(L.posOrDir) > 0, "--light-dir: direction is zero");
            out.push_back({false, glm::normalize(L.posOrDir / xf.scale), L.radiance});
        }
    }
    return out;
}

}  // namespace amrvk::scene
