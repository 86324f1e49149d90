#include "scene/cut_away.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "accel/ray_box.h"
#include "core/error.h"

namespace amrvk::scene {

namespace {
bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

glm::dvec3 unitNormal(glm::dvec3 n) {
    const double largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
    return largest > 0 ? glm::normalize(n / largest) : glm::dvec3(0.0);
}

void validateCutAway(const CutAway& cut) {
    if (cut.crop) {
        const CropBox& b = *cut.crop;
        AMRVK_CHECK(finite(b.lo) && finite(b.hi), "--crop: corners must be finite");
        for (int a = 0; a < 3; ++a)
            AMRVK_CHECK(b.lo[a] < b.hi[a], "--crop: lower corner ", b.lo[a], " is not below upper corner ", b.hi[a],
                        " on axis ", "xyz"[a]);
    }
    AMRVK_CHECK(cut.clips.size() <= shared::kMaxClipPlanes, "--clip: at most ", shared::kMaxClipPlanes,
                " planes (got ", cut.clips.size(), ")");
    for (const ClipPlane& p : cut.clips) {
        AMRVK_CHECK(finite(p.point) && finite(p.normal), "--clip: point and normal must be finite");
        AMRVK_CHECK(p.normal != glm::dvec3(0.0), "--clip: the normal 0 0 0 points nowhere");
    }
}

bool keeps(const CutAway& cut, glm::dvec3 p) {
    if (cut.crop && (glm::any(glm::lessThan(p, cut.crop->lo)) || glm::any(glm::greaterThan(p, cut.crop->hi))))
        return false;
    for (const ClipPlane& c : cut.clips)
        if (glm::dot(unitNormal(c.normal), p - c.point) > 0) return false;
    return true;
}

bool keepsNothingOf(const CutAway& cut, glm::dvec3 lo, glm::dvec3 hi) {
    if (cut.crop) {
        lo = glm::max(lo, cut.crop->lo);
        hi = glm::min(hi, cut.crop->hi);
    }
    if (glm::any(glm::greaterThanEqual(lo, hi))) return true;
    // The region { p : n_i . p <= b_i }: the box's six faces and the planes, each narrowed by the
    // margin, so a region of no volume (a sheet between two opposite planes) has no point left.
    const double margin = 1e-9 * glm::length(hi - lo);
    std::vector<std::pair<glm::dvec3, double>> halfSpaces;
    for (int a = 0; a < 3; ++a) {
        glm::dvec3 e(0.0);
        e[a] = 1.0;
        halfSpaces.push_back({e, hi[a] - margin});
        halfSpaces.push_back({-e, -lo[a] - margin});
    }
    for (const ClipPlane& c : cut.clips) {
        const glm::dvec3 n = unitNormal(c.normal);
        halfSpaces.push_back({n, glm::dot(n, c.point) - margin});
    }
    const size_t m = halfSpaces.size();
    for (size_t i = 0; i < m; ++i)
        for (size_t j = i + 1; j < m; ++j)
            for (size_t k = j + 1; k < m; ++k) {
                const glm::dmat3 rows =
                    glm::transpose(glm::dmat3(halfSpaces[i].first, halfSpaces[j].first, halfSpaces[k].first));
                const double det = glm::determinant(rows);
                if (!(std::abs(det) > 1e-12)) continue;  // (nearly) parallel planes: no vertex
                const glm::dvec3 p =
                    glm::inverse(rows) * glm::dvec3(halfSpaces[i].second, halfSpaces[j].second, halfSpaces[k].second);
                bool kept = true;
                for (const auto& [n, b] : halfSpaces) kept = kept && glm::dot(n, p) <= b + 0.5 * margin;
                if (kept) return false;
            }
    return true;
}

bool keptInterval(const CutAway& cut, glm::dvec3 o, glm::dvec3 d, double& tMin, double& tMax) {
    if (cut.crop && !accel::clipRay(cut.crop->lo, cut.crop->hi, o, d, tMin, tMax)) return false;
    for (const ClipPlane& c : cut.clips) {
        const glm::dvec3 n = unitNormal(c.normal);
        const double s = glm::dot(n, c.point - o), dn = glm::dot(n, d);
        if (dn == 0) {
            if (s < 0) return false;
        } else if (dn > 0) {
            tMax = std::min(tMax, s / dn);
        } else {
            tMin = std::max(tMin, s / dn);
        }
    }
    return tMin < tMax;
}

CutAway cutAwayInVoxelSpace(const CutAway& cut, const amr::Transform& xf) {
    CutAway v;
    if (cut.crop) {
        const glm::dvec3 a = (cut.crop->lo - xf.origin) / xf.scale, b = (cut.crop->hi - xf.origin) / xf.scale;
        v.crop = CropBox{glm::min(a, b), glm::max(a, b)};  // a negative scale swaps the corners
    }
    // n . (origin + scale v - p) <= 0  <=>  (n * scale) . (v - (p - origin) / scale) <= 0
    for (const ClipPlane& c : cut.clips)
        v.clips.push_back({(c.point - xf.origin) / xf.scale, unitNormal(c.normal) * xf.scale});
    return v;
}

shared::CutAwayGpu cutAwayGpu(const CutAway& cut, const amr::Transform& xf, glm::dvec3 localOrigin) {
    validateCutAway(cut);
    const CutAway v = cutAwayInVoxelSpace(cut, xf);
    shared::CutAwayGpu g{};
    if (v.crop) {
        g.flags |= shared::kCutCrop;
        g.cropLo = glm::vec3(v.crop->lo - localOrigin);
        g.cropHi = glm::vec3(v.crop->hi - localOrigin);
    }
    g.planeCount = uint32_t(v.clips.size());
    for (size_t i = 0; i < v.clips.size(); ++i) {
        const glm::dvec3 n = unitNormal(v.clips[i].normal);
        g.planes[i] = glm::vec4(glm::vec3(n), float(glm::dot(n, v.clips[i].point - localOrigin)));
    }
    return g;
}

}  // namespace amrvk::scene
