#include "scene/volume_scene.h"

#include <optional>

#include "accel/brick_sampler.h"
#include "accel/majorant_bounds.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"

namespace amrvk::scene {

VolumeScene::VolumeScene(std::shared_ptr<const Volume> volume, const StructureConfig& config)
    : mVolume(std::move(volume)) {
    AMRVK_CHECK(mVolume != nullptr, "internal: a scene needs a volume");
    configure(config);
}

void VolumeScene::configure(const StructureConfig& next) {
    next.validate();
    const StructurePlan p = next.plan();  // throws for an unresolved back-end
    const Volume& v = *mVolume;
    // What the previous combination built and this one can keep.
    const bool was = mConfigured;
    const bool sameGrid = was && mConfig.grid == next.grid;
    const bool keepSampler = was && (mPlan.samplerBvh || mPlan.samplerBoxes) && mPlan.lookup == p.lookup &&
                             mPlan.backend == p.backend;
    const bool keepGrid = sameGrid && mPlan.rangesFromDense == p.rangesFromDense;
    const bool keepDomains = was && mPlan.traversalBoxes == p.traversalBoxes;

    // Free what the new combination does not use (or must build again).
    if (!p.abrs) abrs.reset();
    if (!p.macrocellRanges || !keepGrid) grid.reset();
    if (!p.supportRangeQuery) supportRanges.reset();
    if (!p.staticBoxes || !keepDomains) domains = {};
    if (!(p.samplerBvh || p.samplerBoxes) || !keepSampler) {
        samplerBvh = {};
        samplerBoxes = {};
    }
    if (!p.brickGrid || !sameGrid) brickGrid.reset();
    if (!p.denseGrid) dense.reset();
    mConfig = next;
    mPlan = p;
    mConfigured = false;  // until every structure below is built: a failed build rebuilds next time

    if (p.supportRangeQuery && !supportRanges) {
        Timer t;
        ProgressStage stage("support ranges of the bricks");
        supportRanges.emplace(v.bricks, v.brickValues());
        stage.setResult(formatBytes(supportRanges->memoryBytes()));
        buildSeconds.domains = t.seconds();
    }
    if (p.denseGrid && !dense) {
        dense = accel::buildDenseGrid(v.model, v.bricks, v.brickValues(), v.bounds(), v.minLevel(), next.denseMaxBytes);
        buildSeconds.dense = dense->buildSeconds;
    }
    if (p.abrs && !abrs) {
        ProgressStage stage("active brick regions");
        abrs = accel::buildAbrs(v.bricks);
        stage.setResult(strCat(abrs->abrs.size(), " regions, ", formatBytes(abrs->memoryBytes())));
        buildSeconds.abrs = abrs->buildSeconds;
    }
    if ((p.samplerBvh || p.samplerBoxes) && samplerBvh.nodes.empty() && samplerBoxes.empty()) {
        Timer t;
        std::vector<accel::BoxD> boxes =
            p.lookup == Lookup::AbrBvh ? accel::abrBoxes(*abrs) : accel::brickDomainBoxes(v.bricks);
        if (p.samplerBvh) {
            for (auto& b : boxes) b = {v.toLocal(b.lo), v.toLocal(b.hi)};
            ProgressStage stage(strCat("sampler BVH over ", boxes.size(), " boxes"));
            samplerBvh = accel::buildBvh(boxes);
            stage.setResult(formatBytes(samplerBvh.memoryBytes()));
        } else {
            samplerBoxes.reserve(boxes.size());
            for (const auto& b : boxes) samplerBoxes.push_back(v.toLocal(b));
        }
        buildSeconds.samplerBvh = t.seconds();
    }
    if (p.brickGrid && !brickGrid) {
        ProgressStage stage("brick grid");
        brickGrid = accel::buildBrickGrid(v.bricks, v.bounds(), accel::parseGridDims(next.grid, v.bounds(), v.cellCount));
        stage.setResult(formatBytes(brickGrid->memoryBytes()));
        buildSeconds.brickGrid = brickGrid->buildSeconds;
    }
    if (p.macrocellRanges && !grid) buildMacrocellRanges();
    if (p.staticBoxes && domains.boxes.empty()) buildStaticBoxes();
    mConfigured = true;
}

// The macrocell value ranges of mConfig's grid: from the dense samples, from the brick grid
// when it has the same layout, else from brick lists made for the purpose and dropped.
void VolumeScene::buildMacrocellRanges() {
    const Volume& v = *mVolume;
    const StructurePlan& p = mPlan;
    const glm::ivec3 dims = accel::parseGridDims(mConfig.grid, v.bounds(), v.cellCount);
    const uint64_t macrocells = uint64_t(dims.x) * uint64_t(dims.y) * uint64_t(dims.z);
    ProgressStage stage(strCat("macrocell value ranges of ", dims.x, "x", dims.y, "x", dims.z),
                        memoryNote(macrocells * sizeof(accel::ValueRange)));
    if (p.rangesFromDense) {  // ranges from the dense samples, not from the cells
        Timer t;
        grid = accel::rangeGridLayout(v.bounds(), dims);
        accel::assignDenseRanges(*dense, *grid);
        grid->buildSeconds = t.seconds();
    } else if (brickGrid && brickGrid->dims == dims) {
        grid = accel::buildRangeGrid(*brickGrid, v.bricks, v.brickValues());
    } else {  // the brick lists only while the ranges are made
        const accel::BrickGrid lists = accel::buildBrickGrid(v.bricks, v.bounds(), dims);
        grid = accel::buildRangeGrid(lists, v.bricks, v.brickValues());
        grid->buildSeconds += lists.buildSeconds;
    }
    buildSeconds.grid = grid->buildSeconds;
}

// The static traversal boxes (ABRs, brick bounds or brick domains, local voxel space) with the
// support range of each, grown by the position margin.
void VolumeScene::buildStaticBoxes() {
    const Volume& v = *mVolume;
    const StructurePlan& p = mPlan;
    const uint64_t boxes = p.traversalBoxes == BoxSet::Abrs ? abrs->abrs.size() : v.bricks.bricks.size();
    ProgressStage stage(strCat("traversal value ranges of ", boxes, " boxes"),
                        memoryNote(boxes * (sizeof(shared::AabbGpu) + sizeof(accel::ValueRange))));
    Timer t;
    const accel::SupportRangeQuery query(v.bricks, v.brickValues());
    const double margin = accel::positionMargin(v.bounds());
    if (p.traversalBoxes == BoxSet::Abrs) {
        for (const accel::Abr& a : abrs->abrs) domains.boxes.push_back(v.toLocal({a.box.lower(), a.box.upper()}));
        domains.ranges = accel::computeAbrValueRanges(*abrs, query, margin);
    } else {
        for (const accel::Brick& b : v.bricks.bricks) {
            if (p.traversalBoxes == BoxSet::BrickBounds) {
                const amr::Box3l bb = b.bounds();
                domains.boxes.push_back(v.toLocal({glm::dvec3(bb.lower), glm::dvec3(bb.upper)}));
            } else {
                const accel::HalfBox d = accel::brickDomain(b);
                domains.boxes.push_back(v.toLocal({d.lower(), d.upper()}));
            }
        }
        domains.ranges = p.traversalBoxes == BoxSet::BrickBounds ? accel::brickBoundsRanges(query, v.bricks, margin)
                                                                : accel::brickDomainRanges(query, v.bricks, margin);
    }
    buildSeconds.domains = t.seconds();
}

accel::KdTree VolumeScene::kdTreeFor(const TransferFunction& tf) const {
    AMRVK_CHECK(supportRanges.has_value(), "internal: a kd-tree needs the kdtree traversal's support ranges");
    accel::KdTreeParams params;
    // Never more leaves than cells: a leaf finer than the cells tightens little, and --kd-leaves
    // 16777215 on 32,768 cells reserved a 1 GB tree.
    params.maxLeaves = uint32_t(std::max<uint64_t>(1, std::min<uint64_t>(mConfig.kdLeaves, mVolume->cellCount)));
    // Rebuilt at every TF change (the viewer's edits): a line only where the data makes it long.
    std::optional<ProgressStage> stage;
    if (mVolume->bricks.bricks.size() >= (size_t(1) << 16))
        stage.emplace(strCat("kd-tree of at most ", params.maxLeaves, " leaves for the transfer function"));
    accel::KdTree tree = accel::buildKdTree(*supportRanges, mVolume->bounds(),
                                            [&tf](float lo, float hi) { return tf.maxAlpha(lo, hi); }, params);
    if (stage) stage->setResult(strCat(tree.leaves.size(), " leaves, ", formatBytes(tree.memoryBytes())));
    return tree;
}

double VolumeScene::combinationBuildSeconds() const {
    const StructurePlan& p = mPlan;
    return mVolume->bricks.buildSeconds + (p.abrs ? buildSeconds.abrs : 0.0) +
           (p.denseGrid    ? buildSeconds.dense
            : p.brickGrid ? buildSeconds.brickGrid
                          : buildSeconds.samplerBvh) +
           (p.macrocellRanges ? buildSeconds.grid : 0.0) +
           (p.staticBoxes || p.supportRangeQuery ? buildSeconds.domains : 0.0);
}

std::vector<std::pair<std::string, uint64_t>> VolumeScene::hostBytes() const {
    std::vector<std::pair<std::string, uint64_t>> out;
    out.emplace_back("model", mVolume->modelBytes());  // cells and loaded fields, in brick order: the brick values
    out.emplace_back("bricks", mVolume->bricks.memoryBytes());
    if (abrs) out.emplace_back("abrs", abrs->memoryBytes());
    if (!samplerBvh.nodes.empty()) out.emplace_back("samplerBvh", samplerBvh.memoryBytes());
    if (!samplerBoxes.empty()) out.emplace_back("samplerBoxes", samplerBoxes.size() * sizeof(shared::AabbGpu));
    if (grid) out.emplace_back("macrocells", grid->memoryBytes());
    if (dense) out.emplace_back("denseGrid", dense->memoryBytes());
    if (brickGrid) out.emplace_back("brickGrid", brickGrid->memoryBytes());
    if (supportRanges) out.emplace_back("supportRangeQuery", supportRanges->memoryBytes());
    if (!domains.boxes.empty()) out.emplace_back("traversalBoxes", domains.memoryBytes());
    return out;
}

}  // namespace amrvk::scene
