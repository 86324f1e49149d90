#include "amr/sampler.h"

#include <cmath>
#include <limits>

#include "core/error.h"

namespace amrvk::amr {

double tentWeight(const Cell& cell, glm::dvec3 p) {
    const double w = double(cellWidth(cell.level));
    glm::dvec3 c = glm::dvec3(cell.lower) + 0.5 * w;
    double phi = 1.0;
    for (int a = 0; a < 3; ++a) phi *= std::max(0.0, 1.0 - std::abs(p[a] - c[a]) / w);
    return phi;
}

ReferenceSampler::ReferenceSampler(const Model& model, const Field& field)
    : mModel(model), mField(field), mHash(model.cells), mCellOrder(model.cellOrder) {}

void ReferenceSampler::checkOrder() const {
    AMRVK_CHECK(mModel.cellOrder == mCellOrder, "internal: ", mModel.source,
                " was reordered (bricks built) after its reference sampler indexed it; build bricks first");
}

template <typename Visit>
void ReferenceSampler::forEachContributing(glm::dvec3 p, Visit&& visit) const {
    checkOrder();
    for (int32_t level : mHash.levels()) {
        const double w = double(cellWidth(level));
        glm::dvec3 k0 = glm::floor(p / w - 0.5);
        for (int corner = 0; corner < 8; ++corner) {
            glm::dvec3 k = k0 + glm::dvec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
            glm::dvec3 lower = k * w;
            if (glm::any(glm::lessThan(lower, glm::dvec3(INT32_MIN))) ||
                glm::any(glm::greaterThan(lower, glm::dvec3(INT32_MAX))))
                continue;
            uint32_t idx = mHash.find(glm::ivec3(lower), level);
            if (idx == CellHash::kNone) continue;
            double phi = tentWeight(mModel.cells[idx], p);
            if (phi > 0 && !std::isnan(mField.values[idx])) visit(idx, phi);
        }
    }
}

Sample ReferenceSampler::sample(glm::dvec3 p) const {
    double sumW = 0, sumWV = 0;
    forEachContributing(p, [&](uint32_t idx, double phi) {
        sumW += phi;
        sumWV += phi * double(mField.values[idx]);
    });
    return Sample::fromSums(sumW, sumWV);
}

bool ReferenceSampler::insideLeafCell(glm::dvec3 p) const {
    checkOrder();
    for (int32_t level : mHash.levels()) {
        const double w = double(cellWidth(level));
        glm::dvec3 k = glm::floor(p / w);
        // A point on a face belongs to the cells on both sides: try the lower neighbours too.
        for (int c = 0; c < 8; ++c) {
            glm::dvec3 kk = k - glm::dvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            bool onFace = true;
            for (int a = 0; a < 3; ++a)
                if (((c >> a) & 1) && p[a] != k[a] * w) onFace = false;
            if (!onFace) continue;
            glm::dvec3 lower = kk * w;
            if (glm::any(glm::lessThan(lower, glm::dvec3(INT32_MIN))) ||
                glm::any(glm::greaterThan(lower, glm::dvec3(INT32_MAX))))
                continue;
            uint32_t idx = mHash.find(glm::ivec3(lower), level);
            if (idx != CellHash::kNone && !std::isnan(mField.values[idx])) return true;
        }
    }
    return false;
}

void ReferenceSampler::contributingRange(glm::dvec3 p, float& lo, float& hi) const {
    lo = std::numeric_limits<float>::infinity();
    hi = -lo;
    forEachContributing(p, [&](uint32_t idx, double) {
        lo = std::min(lo, mField.values[idx]);
        hi = std::max(hi, mField.values[idx]);
    });
}

}  // namespace amrvk::amr
