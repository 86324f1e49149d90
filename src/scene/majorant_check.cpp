#include "scene/majorant_check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "accel/majorant_bounds.h"
#include "amr/exact_range.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/stats.h"
#include "scene/sub_majorants.h"
#include "scene/volume_scene.h"

namespace amrvk::scene {

bool BoxSetCheck::ok() const {
    if (rangeFailures > 0) return false;
    for (const PerTf& t : tfs)
        if (t.failures > 0) return false;
    return true;
}

namespace {

constexpr double kViolationTolerance = 1e-6;  // the GPU counter's (lib/tracking.glsl)
constexpr size_t kChunks = 64;                // per batch, fixed: results do not depend on threads

struct Partial {
    uint64_t withData = 0, vertices = 0, rangeFailures = 0;
    double worstExcess = -1;
    size_t worstBox = 0;
    amr::ExactRange::Result worstExact;
    std::vector<uint64_t> tfFailures;
    std::vector<double> tfWorst;
};

std::string describe(const accel::BoxD& b, const accel::ValueRange& stored, const amr::ExactRange::Result& r,
                     size_t index) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "box %zu [%.9g %.9g %.9g]-[%.9g %.9g %.9g]: stored range [%.9g, %.9g], exact [%.17g, %.17g] "
                  "(minimum at %.9g %.9g %.9g, maximum at %.9g %.9g %.9g)",
                  index, b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z, double(stored.lo), double(stored.hi), r.lo,
                  r.hi, r.argLo.x, r.argLo.y, r.argLo.z, r.argHi.x, r.argHi.y, r.argHi.z);
    return line;
}

}  // namespace

void checkBoxSet(const amr::ExactRange& exact, const StoredBoxes& s, double margin,
                 const std::vector<const TransferFunction*>& tfs, const MajorantCheckOptions& options, BoxSetCheck& out) {
    AMRVK_CHECK(s.ranges.size() == s.boxes.size() && (s.majorants.empty() || s.majorants.size() == s.boxes.size()),
                "internal: ", s.boxes.size(), " boxes with ", s.ranges.size(), " ranges and ", s.majorants.size(),
                " majorants");
    Timer timer;
    const size_t n = s.boxes.size();
    out.count = n;
    out.tfs.clear();
    for (const TransferFunction* tf : tfs) out.tfs.push_back({tf->name(), 0, 0.0});
    const double eps = double(std::numeric_limits<float>::epsilon());
    auto map = [&](size_t lo, size_t hi) {
        Partial p;
        p.tfFailures.assign(tfs.size(), 0);
        p.tfWorst.assign(tfs.size(), 0.0);
        for (size_t i = lo; i < hi; ++i) {
            const accel::BoxD& b = s.boxes[i];
            const amr::ExactRange::Result r = exact.over(b.lo - margin, b.hi + margin, accel::kGpuErrorUlps * eps);
            if (r.empty()) continue;  // no cell support reaches the box: nothing to bound
            ++p.withData;
            p.vertices += r.vertices;
            const double needLo = r.roomLo, needHi = r.roomHi;
            const accel::ValueRange& stored = s.ranges[i];
            const double excess = stored.empty() ? std::numeric_limits<double>::infinity()
                                                 : std::max(double(stored.lo) - needLo, needHi - double(stored.hi));
            if (excess > 0) {
                ++p.rangeFailures;
                const double rel = excess / std::max(r.maxAbs, std::numeric_limits<double>::min());
                if (rel > p.worstExcess) {
                    p.worstExcess = rel;
                    p.worstBox = i;
                    p.worstExact = r;
                }
            }
            for (size_t t = 0; t < tfs.size(); ++t) {
                const float need = tfs[t]->maxAlpha(accel::roundDown(needLo), accel::roundUp(needHi));
                const float majorant = !s.majorants.empty() ? s.majorants[i]
                                       : stored.empty()     ? 0.0f
                                                            : tfs[t]->maxAlpha(stored.lo, stored.hi);
                if (double(need) > double(majorant) * (1.0 + kViolationTolerance)) {
                    ++p.tfFailures[t];
                    const double ratio = majorant > 0 ? double(need) / double(majorant)
                                                      : std::numeric_limits<double>::infinity();
                    p.tfWorst[t] = std::max(p.tfWorst[t], ratio);
                }
            }
        }
        return p;
    };
    auto combine = [](Partial& a, Partial&& b) {
        a.withData += b.withData;
        a.vertices += b.vertices;
        a.rangeFailures += b.rangeFailures;
        if (b.worstExcess > a.worstExcess) {
            a.worstExcess = b.worstExcess;
            a.worstBox = b.worstBox;
            a.worstExact = b.worstExact;
        }
        for (size_t t = 0; t < a.tfFailures.size(); ++t) {
            a.tfFailures[t] += b.tfFailures[t];
            a.tfWorst[t] = std::max(a.tfWorst[t], b.tfWorst[t]);
        }
    };
    // Batches of boxes, so progress can be shown between them.
    const size_t batch = std::max<size_t>(4096, n / 50);
    Partial total;
    total.tfFailures.assign(tfs.size(), 0);
    total.tfWorst.assign(tfs.size(), 0.0);
    for (size_t begin = 0; begin < n; begin += batch) {
        const size_t end = std::min(n, begin + batch);
        combine(total, parallelReduce<Partial>(begin, end, kChunks, map, combine));
        if (options.onProgress) options.onProgress(out.boxes, end, n);
    }
    out.withData = total.withData;
    out.vertices = total.vertices;
    out.rangeFailures = total.rangeFailures;
    if (total.rangeFailures > 0) {
        out.worstExcess = total.worstExcess;
        out.worst = describe(s.boxes[total.worstBox], s.ranges[total.worstBox], total.worstExact, total.worstBox);
    }
    for (size_t t = 0; t < tfs.size(); ++t) {
        out.tfs[t].failures = total.tfFailures[t];
        out.tfs[t].worstRatio = total.tfWorst[t];
    }
    out.seconds = timer.seconds();
}

namespace {

StructureConfig configFor(TraversalKind traversal, const MajorantCheckOptions& options) {
    StructureConfig c;
    c.traversal = traversal;
    c.sampler = SamplerKind::ExtBrick;  // the traversal's boxes do not depend on the sampler
    c.backend = Backend::Sw;
    c.grid = options.grid;
    c.kdLeaves = options.kdLeaves;
    return c;
}

// The boxes of a static box set (abr, brick, ext-brick) as the GPU holds them, back in voxel space.
StoredBoxes staticBoxes(const VolumeScene& scene) {
    StoredBoxes s;
    const glm::dvec3 origin(scene.volume().localOrigin);
    for (const shared::AabbGpu& b : scene.domains.boxes)
        s.boxes.push_back({glm::dvec3(b.lo) + origin, glm::dvec3(b.hi) + origin});
    s.ranges = scene.domains.ranges;
    return s;
}

}  // namespace

std::vector<BoxSetCheck> checkMajorants(const std::shared_ptr<const Volume>& volume, const MajorantCheckOptions& options) {
    AMRVK_CHECK(volume != nullptr, "internal: majorant check without a volume");
    const Volume& v = *volume;
    const amr::ExactRange exact(v.model, v.field());
    const double margin = accel::positionMargin(v.bounds());
    std::vector<const TransferFunction*> all;
    for (const TransferFunction& tf : options.tfs) all.push_back(&tf);
    std::vector<BoxSetCheck> out;

    {  // Macrocells: grid-dda steps them, grid-bvh traverses the non-empty ones.
        VolumeScene scene(volume, configFor(TraversalKind::GridDda, options));
        const accel::RangeGrid& g = *scene.grid;
        StoredBoxes s;
        s.boxes.reserve(g.cellCount());
        for (size_t i = 0; i < g.cellCount(); ++i) {
            const glm::dvec3 c(g.coordOf(i));
            s.boxes.push_back({g.origin + c * g.cellSize, g.origin + (c + 1.0) * g.cellSize});
        }
        s.ranges = g.ranges;
        BoxSetCheck check;
        check.boxes = "macrocells " + options.grid;
        check.traversals = "grid-dda, grid-bvh";
        checkBoxSet(exact, s, margin, all, options, check);
        out.push_back(std::move(check));
    }
    const struct {
        TraversalKind traversal;
        const char* boxes;
    } statics[] = {{TraversalKind::Abr, "abrs"},
                   {TraversalKind::Brick, "brick bounds"},
                   {TraversalKind::ExtBrick, "brick domains"}};
    for (const auto& st : statics) {
        VolumeScene scene(volume, configFor(st.traversal, options));
        BoxSetCheck check;
        check.boxes = st.boxes;
        check.traversals = traversalName(st.traversal);
        checkBoxSet(exact, staticBoxes(scene), margin, all, options, check);
        out.push_back(std::move(check));
    }
    {  // kd leaves: a tree per TF, checked under that TF.
        VolumeScene scene(volume, configFor(TraversalKind::KdTree, options));
        for (const TransferFunction& tf : options.tfs) {
            const accel::KdTree tree = scene.kdTreeFor(tf);
            StoredBoxes s{tree.leaves, tree.leafRanges, tree.leafMajorants};
            BoxSetCheck check;
            check.boxes = "kd leaves";
            check.traversals = "kdtree";
            check.tf = tf.name();
            checkBoxSet(exact, s, margin, {&tf}, options, check);
            out.push_back(std::move(check));
        }
    }
    if (options.subMajorants > 0) {  // sub-boxes: built per TF for the macrocells it makes loose
        StructureConfig c = configFor(TraversalKind::GridDda, options);
        c.subMajorants = options.subMajorants;
        VolumeScene scene(volume, c);
        const accel::RangeGrid& g = *scene.grid;
        const accel::SubRangeMaker maker(*scene.brickGrid, v.bricks, v.brickValues());
        for (const TransferFunction& tf : options.tfs) {
            const SubMajorantGrid sub =
                buildSubMajorants(g, maker, tf,
                                  {.maxDivision = int(options.subMajorants),
                                   .budgetBytes = kDefaultSubMajorantBudget,
                                   .chordInFinestCells = chordOf(g, double(amr::cellWidth(v.minLevel())))});
            if (sub.refined == 0) continue;  // a smooth TF: nothing built, nothing to check
            BoxSetCheck check;
            check.boxes = "sub-boxes";
            check.traversals = "grid-dda, grid-bvh";
            check.tf = tf.name();
            check.sampledEvery = (sub.subBoxes + options.maxSubBoxes - 1) / std::max<uint64_t>(options.maxSubBoxes, 1);
            StoredBoxes s;
            std::vector<accel::ValueRange> ranges;
            uint64_t refinedSeen = 0;
            for (size_t cell = 0; cell < g.cellCount(); ++cell) {
                const auto [n, offset] = sub.refinementOf(cell);
                if (n == 1 || refinedSeen++ % check.sampledEvery != 0) continue;
                maker.ranges(cell, n, ranges);
                // The majorant the GPU derives: the macrocell's, times q / 255, in float.
                const float M = tf.maxAlpha(g.ranges[cell].lo, g.ranges[cell].hi);
                const glm::dvec3 size = g.cellSize / double(n);
                const glm::dvec3 corner = g.origin + g.cellSize * glm::dvec3(g.coordOf(cell));
                for (size_t k = 0; k < ranges.size(); ++k) {
                    const glm::dvec3 lo = corner + size * glm::dvec3(double(k % size_t(n)), double(k / size_t(n) % size_t(n)),
                                                                    double(k / (size_t(n) * size_t(n))));
                    s.boxes.push_back({lo, lo + size});
                    s.ranges.push_back(ranges[k]);
                    s.majorants.push_back(M * (float(sub.q(cell, k)) * (1.0f / 255.0f)));
                }
            }
            checkBoxSet(exact, s, margin, {&tf}, options, check);
            out.push_back(std::move(check));
        }
    }
    return out;
}

}  // namespace amrvk::scene
