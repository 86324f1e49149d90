#include "scene/render_settings.h"

#include <cmath>

#include "core/error.h"
#include "core/strings.h"
#include "shared/render_params.h"

namespace amrvk::scene {

namespace {
constexpr Named<Mode> kModes[] = {{"ae", Mode::Ae}, {"ss", Mode::Ss}, {"ms", Mode::Ms}, {"dvr", Mode::Dvr}};
}

Mode parseMode(const std::string& name) { return parseNamed(kModes, name, "--mode"); }
const char* modeName(Mode mode) { return nameOf(kModes, mode); }

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
