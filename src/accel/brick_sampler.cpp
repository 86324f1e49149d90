#include "accel/brick_sampler.h"

#include <cmath>

namespace amrvk::accel {

TentAxis tentAxis(double local, int32_t size) {
    TentAxis t{};
    const double i0 = std::floor(local), f = local - i0;
    for (int bit = 0; bit < 2; ++bit) {
        const double i = i0 + double(bit);
        if (i < 0 || i >= double(size)) continue;
        t.cell[t.count] = int(i);
        t.weight[t.count++] = bit ? f : 1.0 - f;
    }
    return t;
}

namespace {

// Adds brick b's tent weights at voxel-space p to (sumW, sumWV); p must lie in the brick domain.
// NaN (empty) slots are skipped.
void addBrickContribution(const Brick& b, std::span<const float> brickValues, glm::dvec3 p, double& sumW,
                          double& sumWV) {
    const double w = double(b.cellWidth());
    // Cell-centre-aligned coordinates: cell k's centre sits at local = k.
    const glm::dvec3 local = (p - glm::dvec3(b.lower)) / w - 0.5;
    addTentCells(b, brickValues, tentAxis(local.x, b.size.x), tentAxis(local.y, b.size.y), tentAxis(local.z, b.size.z),
                 sumW, sumWV);
}

bool halfBoxContains(const HalfBox& box, glm::dvec3 p) {
    glm::dvec3 lo = box.lower(), hi = box.upper();
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
}

}  // namespace

std::vector<BoxD> brickDomainBoxes(const BrickSet& bricks) {
    std::vector<BoxD> boxes;
    boxes.reserve(bricks.bricks.size());
    for (const Brick& b : bricks.bricks) {
        HalfBox d = brickDomain(b);
        boxes.push_back({d.lower(), d.upper()});
    }
    return boxes;
}

std::vector<BoxD> abrBoxes(const AbrSet& abrs) {
    std::vector<BoxD> boxes;
    boxes.reserve(abrs.abrs.size());
    for (const Abr& a : abrs.abrs) boxes.push_back({a.box.lower(), a.box.upper()});
    return boxes;
}

amr::Sample sampleBricks(std::span<const uint32_t> ids, const BrickSet& bricks, std::span<const float> brickValues,
                         glm::dvec3 p) {
    double sumW = 0, sumWV = 0;
    for (uint32_t id : ids) {
        const Brick& b = bricks.bricks[id];
        if (halfBoxContains(brickDomain(b), p)) addBrickContribution(b, brickValues, p, sumW, sumWV);
    }
    return amr::Sample::fromSums(sumW, sumWV);
}

ExtBrickSampler::ExtBrickSampler(const BrickSet& bricks, std::span<const float> brickValues)
    : mBricks(bricks), mValues(brickValues) {
    mDomains.reserve(bricks.bricks.size());
    for (const Brick& b : bricks.bricks) mDomains.push_back(brickDomain(b));
    mBvh = buildBvh(brickDomainBoxes(bricks));
}

amr::Sample ExtBrickSampler::sample(glm::dvec3 p) const {
    double sumW = 0, sumWV = 0;
    mBvh.forEachContaining(p, [&](uint32_t bi) {
        if (halfBoxContains(mDomains[bi], p))
            addBrickContribution(mBricks.bricks[bi], mValues, p, sumW, sumWV);
    });
    return amr::Sample::fromSums(sumW, sumWV);
}

AbrSampler::AbrSampler(const AbrSet& abrs, const BrickSet& bricks,
                       std::span<const float> brickValues)
    : mAbrs(abrs), mBricks(bricks), mValues(brickValues) {
    mBvh = buildBvh(abrBoxes(abrs));
}

int64_t AbrSampler::findAbr(glm::dvec3 p) const {
    int64_t found = -1;
    mBvh.forEachContaining(p, [&](uint32_t ai) {
        if (found < 0 && halfBoxContains(mAbrs.abrs[ai].box, p)) found = ai;
    });
    return found;
}

amr::Sample AbrSampler::sampleInAbr(const Abr& abr, glm::dvec3 p) const {
    double sumW = 0, sumWV = 0;
    for (uint32_t bi : mAbrs.bricksOf(abr))
        addBrickContribution(mBricks.bricks[bi], mValues, p, sumW, sumWV);
    return amr::Sample::fromSums(sumW, sumWV);
}

amr::Sample AbrSampler::sample(glm::dvec3 p) const {
    int64_t ai = findAbr(p);
    if (ai < 0) return {};
    return sampleInAbr(mAbrs.abrs[size_t(ai)], p);
}

}  // namespace amrvk::accel
