#include "scene/volume_scene.h"

#include "accel/brick_sampler.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"

namespace amrvk::scene {

glm::ivec3 VolumeScene::toLocal(glm::i64vec3 voxel) const {
    const glm::i64vec3 local = voxel - localOrigin;
    for (int a = 0; a < 3; ++a)
        AMRVK_CHECK(local[a] >= INT32_MIN && local[a] <= INT32_MAX, "voxel coordinate ", voxel[a],
                    " is more than 2^31 from the data's lower corner ", localOrigin[a]);
    return glm::ivec3(local);
}

const accel::SupportRangeQuery& VolumeScene::supportRangeQuery() const {
    AMRVK_CHECK(config.traversal == TraversalKind::KdTree, "internal: support ranges are kept for kdtree only");
    if (!supportRanges.query) supportRanges.query.emplace(bricks, brickValues);
    return *supportRanges.query;
}

shared::AabbGpu VolumeScene::toLocal(const accel::BoxD& b) const {
    // Box faces lie on the half-voxel lattice: exact in float for local coordinates below 2^23.
    return {glm::vec3(toLocal(b.lo)), glm::vec3(toLocal(b.hi))};
}

VolumeScene makeVolumeScene(amr::Model& model, const amr::Field& field) {
    VolumeScene s;
    s.model = &model;
    s.field = &field;
    amr::ModelSummary summary = amr::summarize(model);
    s.bounds = summary.bounds;
    s.localOrigin = summary.bounds.lower;
    // Local coordinates (what the GPU sees) are int32 and float: refuse a wider domain up front.
    for (int a = 0; a < 3; ++a)
        AMRVK_CHECK(summary.bounds.size()[a] <= INT32_MAX, model.source, ": the data spans ", summary.bounds.size()[a],
                    " finest cells along axis ", "xyz"[a], ", more than 2^31 from the data's lower corner (the limit)");
    s.minLevel = summary.minLevel;
    amr::FieldStats stats = amr::computeFieldStats(model, field);
    s.valueLo = stats.minValue;
    s.valueHi = stats.maxValue;
    ProgressStage stage("bricks");
    AMRVK_CHECK(&field >= model.fields.data() && &field < model.fields.data() + model.fields.size(),
                "internal: the scene's field is not one of the model's");
    s.bricks = accel::buildBricks(model);
    s.brickValues = field.values;
    s.buildSeconds.bricks = s.bricks.buildSeconds;
    return s;
}

void VolumeScene::configure(const StructureConfig& next) {
    AMRVK_CHECK(next.backend != Backend::Auto, "internal: configure() needs a resolved back-end");
    next.validate();
    const bool denseSampler = next.sampler == SamplerKind::Dense;
    const bool bvhSampler = !denseSampler && !next.usesBrickGrid();
    const bool rebuildSampler = bvhSampler && (config.sampler != next.sampler || config.backend != next.backend ||
                                                  (samplerBvh.nodes.empty() && samplerBoxes.empty()));
    const bool rebuildGrid = next.usesGrid() && (!grid || config.grid != next.grid ||
                                                 (config.sampler == SamplerKind::Dense) != denseSampler);
    const bool rebuildDomains = next.traversal != config.traversal || domains.boxes.empty();
    const bool rebuildBrickGrid = next.usesBrickGrid() && (!brickGrid || config.grid != next.grid);
    config = next;

    // Free what the new combination does not use.
    if (!next.usesAbrs()) abrs.reset();
    if (!next.usesGrid()) grid.reset();
    // Only the kd-tree keeps the support-range query (it rebuilds per TF); brick ranges use it once.
    if (next.traversal != TraversalKind::KdTree) supportRanges.query.reset();
    if (next.traversal == TraversalKind::KdTree && !supportRanges.query) {
        Timer t;
        supportRanges.query.emplace(bricks, brickValues);
        buildSeconds.domains = t.seconds();
    }
    if (rebuildDomains || !next.traversalUsesBoxes() || next.traversal == TraversalKind::GridBvh) domains = {};
    if (rebuildSampler || !bvhSampler) {
        samplerBvh = {};
        samplerBoxes = {};
    }
    if (!next.usesBrickGrid() || rebuildBrickGrid) brickGrid.reset();
    if (!denseSampler) dense.reset();
    if (denseSampler && !dense) {
        dense = accel::buildDenseGrid(*model, bricks, brickValues, bounds, minLevel, next.denseMaxBytes);
        buildSeconds.dense = dense->buildSeconds;
    }

    if (next.usesAbrs() && !abrs) {
        ProgressStage stage("active brick regions");
        abrs = accel::buildAbrs(bricks);
        buildSeconds.abrs = abrs->buildSeconds;
    }
    if (rebuildSampler) {
        Timer t;
        std::vector<accel::BoxD> boxes = next.sampler == SamplerKind::Abr ? accel::abrBoxes(*abrs)
                                                                         : accel::brickDomainBoxes(bricks);
        if (next.backend == Backend::Sw) {
            for (auto& b : boxes) b = {toLocal(b.lo), toLocal(b.hi)};
            samplerBvh = accel::buildBvh(boxes);
        } else {
            samplerBoxes.reserve(boxes.size());
            for (const auto& b : boxes) samplerBoxes.push_back(toLocal(b));
        }
        buildSeconds.samplerBvh = t.seconds();
    }
    if (rebuildBrickGrid) {
        ProgressStage stage("brick grid");
        brickGrid = accel::buildBrickGrid(bricks, bounds, accel::parseGridDims(next.grid, bounds));
        buildSeconds.brickGrid = brickGrid->buildSeconds;
    }
    if (rebuildGrid) {
        ProgressStage stage("macrocell value ranges");
        const glm::ivec3 dims = accel::parseGridDims(next.grid, bounds);
        if (denseSampler) {  // ranges from the dense samples, not from the cells
            Timer t;
            grid = accel::rangeGridLayout(bounds, dims);
            accel::assignDenseRanges(*dense, *grid);
            grid->buildSeconds = t.seconds();
        } else if (brickGrid && brickGrid->dims == dims) {
            grid = accel::buildRangeGrid(*brickGrid, bricks, brickValues);
        } else {  // the brick lists only while the ranges are made
            const accel::BrickGrid lists = accel::buildBrickGrid(bricks, bounds, dims);
            grid = accel::buildRangeGrid(lists, bricks, brickValues);
            grid->buildSeconds += lists.buildSeconds;
        }
        buildSeconds.grid = grid->buildSeconds;
    }
    if (rebuildDomains && (next.traversal == TraversalKind::Abr || next.traversal == TraversalKind::Brick ||
                           next.traversal == TraversalKind::ExtBrick)) {
        ProgressStage stage("traversal value ranges");
        Timer t;
        if (next.traversal == TraversalKind::Abr) {
            for (const accel::Abr& a : abrs->abrs) domains.boxes.push_back(toLocal({a.box.lower(), a.box.upper()}));
            domains.ranges = accel::computeAbrValueRanges(*abrs, bricks, brickValues);
        } else if (next.traversal == TraversalKind::Brick) {
            const accel::SupportRangeQuery query(bricks, brickValues);
            for (const accel::Brick& b : bricks.bricks) {
                amr::Box3l bb = b.bounds();
                domains.boxes.push_back(toLocal({glm::dvec3(bb.lower), glm::dvec3(bb.upper)}));
            }
            domains.ranges = accel::brickBoundsRanges(query, bricks);
        } else {
            const accel::SupportRangeQuery query(bricks, brickValues);
            for (const accel::Brick& b : bricks.bricks) {
                accel::HalfBox d = accel::brickDomain(b);
                domains.boxes.push_back(toLocal({d.lower(), d.upper()}));
            }
            domains.ranges = accel::brickDomainRanges(query, bricks);
        }
        buildSeconds.domains = t.seconds();
    }
}

std::vector<std::pair<std::string, uint64_t>> VolumeScene::hostBytes() const {
    std::vector<std::pair<std::string, uint64_t>> out;
    uint64_t modelBytes = model ? model->cells.size() * sizeof(amr::Cell) : 0;
    if (model)
        for (const amr::Field& f : model->fields) modelBytes += f.values.size() * sizeof(float);
    out.emplace_back("model", modelBytes);  // cells and loaded fields, in brick order: the brick values
    out.emplace_back("bricks", bricks.memoryBytes());
    if (abrs) out.emplace_back("abrs", abrs->memoryBytes());
    if (!samplerBvh.nodes.empty()) out.emplace_back("samplerBvh", samplerBvh.memoryBytes());
    if (!samplerBoxes.empty()) out.emplace_back("samplerBoxes", samplerBoxes.size() * sizeof(shared::AabbGpu));
    if (grid) out.emplace_back("macrocells", grid->memoryBytes());
    if (dense) out.emplace_back("denseGrid", dense->memoryBytes());
    if (brickGrid) out.emplace_back("brickGrid", brickGrid->memoryBytes());
    if (supportRanges.query) out.emplace_back("supportRangeQuery", supportRanges.query->memoryBytes());
    if (!domains.boxes.empty()) out.emplace_back("traversalBoxes", domains.memoryBytes());
    return out;
}

VolumeScene buildVolumeScene(amr::Model& model, const amr::Field& field, const StructureConfig& config) {
    VolumeScene s = makeVolumeScene(model, field);
    s.configure(config);
    return s;
}

VolumeScene buildVolumeScene(amr::Model& model, const amr::Field& field, SamplerKind sampler,
                             const std::string& gridSpec) {
    StructureConfig c;
    c.sampler = sampler;
    c.grid = gridSpec;
    return buildVolumeScene(model, field, c);
}

}  // namespace amrvk::scene
