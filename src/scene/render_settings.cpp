#include "scene/render_settings.h"

#include <cmath>

#include "core/error.h"
#include "shared/render_params.h"

namespace amrvk::scene {

Mode parseMode(const std::string& name) {
    if (name == "ae") return Mode::Ae;
    if (name == "ss") return Mode::Ss;
    if (name == "ms") return Mode::Ms;
    if (name == "dvr") return Mode::Dvr;
    AMRVK_CHECK(false, "--mode '", name, "': expected ae, ss, ms or dvr");
    return Mode::Ms;
}

const char* modeName(Mode mode) {
    switch (mode) {
        case Mode::Ae: return "ae";
        case Mode::Ss: return "ss";
        case Mode::Dvr: return "dvr";
        default: return "ms";
    }
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
