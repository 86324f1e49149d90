#include "render/volume_scene.h"

#include "accel/brick_sampler.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"

namespace amrvk::render {

SamplerKind parseSampler(const std::string& name) {
    if (name == "ext-brick") return SamplerKind::ExtBrick;
    if (name == "abr") return SamplerKind::Abr;
    AMRVK_CHECK(false, "--sampler '", name, "': expected ext-brick or abr");
    return SamplerKind::ExtBrick;
}

const char* samplerName(SamplerKind kind) { return kind == SamplerKind::Abr ? "abr" : "ext-brick"; }

VolumeScene buildVolumeScene(const amr::Model& model, const amr::Field& field, SamplerKind sampler,
                             const std::string& gridSpec) {
    VolumeScene s;
    s.model = &model;
    s.field = &field;
    s.sampler = sampler;
    amr::ModelSummary summary = amr::summarize(model);
    s.bounds = summary.bounds;
    s.localOrigin = summary.bounds.lower;
    s.minLevel = summary.minLevel;
    amr::FieldStats stats = amr::computeFieldStats(model, field);
    s.valueLo = stats.minValue;
    s.valueHi = stats.maxValue;
    {
        ProgressStage stage("bricks");
        s.bricks = accel::buildBricks(model);
        s.brickValues = accel::brickOrderValues(s.bricks, field);
        s.buildSeconds.bricks = s.bricks.buildSeconds;
    }
    const glm::dvec3 origin(s.localOrigin);
    std::vector<accel::BoxD> boxes;
    if (sampler == SamplerKind::Abr) {
        ProgressStage stage("active brick regions");
        s.abrs = accel::buildAbrs(s.bricks);
        s.buildSeconds.abrs = s.abrs->buildSeconds;
        boxes = accel::abrBoxes(*s.abrs);
    } else {
        boxes = accel::brickDomainBoxes(s.bricks);
    }
    {
        Timer t;
        for (auto& b : boxes) {
            b.lo -= origin;
            b.hi -= origin;
        }
        s.samplerBvh = accel::buildBvh(boxes);
        s.buildSeconds.bvh = t.seconds();
    }
    {
        ProgressStage stage("macrocell value ranges");
        s.grid = accel::buildRangeGrid(model, field, accel::parseGridDims(gridSpec, s.bounds));
        s.buildSeconds.grid = s.grid.buildSeconds;
    }
    return s;
}

}  // namespace amrvk::render
