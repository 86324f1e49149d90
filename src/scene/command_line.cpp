#include "scene/command_line.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace amrvk::scene {

namespace {
std::string vec(glm::dvec3 v) { return formatNumber(v.x) + " " + formatNumber(v.y) + " " + formatNumber(v.z); }
}  // namespace

std::string shellQuote(const std::string& s) {
    if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:@%") ==
                          std::string::npos)
        return s;
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string formatNumber(double v) {
    char s[64];
    if (v == std::trunc(v) && std::fabs(v) < 1e15) {  // whole numbers as such: 10, not 1e+01
        std::snprintf(s, sizeof s, "%.0f", v);
        return s;
    }
    // Shortest text that reads back the same double (17 digits for NaN, which never does).
    for (int digits = 1; digits <= 17; ++digits) {
        std::snprintf(s, sizeof s, "%.*g", digits, v);
        if (std::strtod(s, nullptr) == v) break;
    }
    return s;
}

std::string settingsOptions(const RenderSettings& s, bool withCamera) {
    const RenderSettings d;
    std::string o = std::string(" --mode ") + modeName(s.mode);
    o += " --size " + std::to_string(s.width) + "x" + std::to_string(s.height);
    o += " --seed " + std::to_string(s.seed);
    if (withCamera) o += " --camera " + vec(s.camera.eye) + " " + vec(s.camera.target) + " " + vec(s.camera.up);
    if (withCamera || s.camera.fovYDegrees != d.camera.fovYDegrees) o += " --fov " + formatNumber(s.camera.fovYDegrees);
    if (s.densityScale != d.densityScale) o += " --density-scale " + formatNumber(s.densityScale);
    if (s.g != d.g) o += " --g " + formatNumber(s.g);
    if (s.ambient != d.ambient) o += " --ambient " + vec(s.ambient);
    // Always stated: render's own default (black) is not RenderSettings' (the ambient's), so a
    // command without it renders another picture (bench's references did).
    o += " --background " + vec(s.background ? *s.background : s.ambient);
    for (const Light& L : s.lights)
        o += std::string(L.point ? " --light-point " : " --light-dir ") + vec(L.posOrDir) + " " + vec(L.radiance);
    if (s.dvrStep != d.dvrStep) o += " --dt " + formatNumber(s.dvrStep);
    if (s.dvrShading) o += " --dvr-shading";
    if (s.transmittance != d.transmittance) o += std::string(" --transmittance ") + transmittanceName(s.transmittance);
    if (s.controlExtinction != d.controlExtinction)
        o += std::string(" --control-extinction ") + controlExtinctionName(s.controlExtinction);
    if (s.cut.crop) o += " --crop " + vec(s.cut.crop->lo) + " " + vec(s.cut.crop->hi);
    for (const ClipPlane& c : s.cut.clips) o += " --clip " + vec(c.point) + " " + vec(c.normal);
    return o;
}

std::string structureOptions(const StructureConfig& c) {
    const StructureConfig d;
    std::string o = std::string(" --traversal ") + traversalName(c.traversal) + " --sampler " + samplerName(c.sampler) +
                    " --backend " + backendName(c.backend);
    if (c.usesGrid() || c.grid != d.grid) o += " --grid " + shellQuote(c.grid);
    if (c.kdLeaves != d.kdLeaves) o += " --kd-leaves " + std::to_string(c.kdLeaves);
    if (c.subMajorants != d.subMajorants) o += " --sub-majorants " + subMajorantsName(c.subMajorants);
    if (c.denseMaxBytes != d.denseMaxBytes) o += " --dense-max-mib " + std::to_string(c.denseMaxBytes >> 20);
    return o;
}

}  // namespace amrvk::scene
