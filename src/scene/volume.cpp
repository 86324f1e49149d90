#include "scene/volume.h"

#include "accel/brick_build.h"
#include "core/error.h"
#include "core/progress.h"

namespace amrvk::scene {

glm::ivec3 Volume::toLocal(glm::i64vec3 voxel) const {
    const glm::i64vec3 local = voxel - localOrigin;
    for (int a = 0; a < 3; ++a)
        AMRVK_CHECK(local[a] >= INT32_MIN && local[a] <= INT32_MAX, "voxel coordinate ", voxel[a],
                    " is more than 2^31 from the data's lower corner ", localOrigin[a]);
    return glm::ivec3(local);
}

shared::AabbGpu Volume::toLocal(const accel::BoxD& b) const {
    // Box faces lie on the half-voxel lattice: exact in float for local coordinates below 2^23.
    return {glm::vec3(toLocal(b.lo)), glm::vec3(toLocal(b.hi))};
}

uint64_t Volume::modelBytes() const {
    uint64_t bytes = model.cells.size() * model.cells.bytesPerCell();
    for (const amr::Field& f : model.fields) bytes += f.values.size() * sizeof(float);
    return bytes + slotValues.size() * sizeof(float);
}

namespace {
std::shared_ptr<Volume> makeMutableVolume(amr::Model model, std::string_view fieldName, const VolumeFrame* frame,
                                          accel::BrickSet* given);
}

std::shared_ptr<const Volume> makeVolume(amr::Model model, std::string_view fieldName, const VolumeOptions& options) {
    std::shared_ptr<Volume> v = makeMutableVolume(std::move(model), fieldName, nullptr, nullptr);
    if (options.releaseCells) {
        amr::CellArray().swap(v->model.cells);  // frees the memory, not just the size
        v->cellsReleased = true;
    }
    return v;
}

std::shared_ptr<const Volume> makeVolume(amr::Model model, std::string_view fieldName, accel::BrickSet given) {
    return makeMutableVolume(std::move(model), fieldName, nullptr, &given);
}

std::shared_ptr<const Volume> makeVolume(amr::Model model, std::string_view fieldName, const VolumeFrame& frame) {
    return makeMutableVolume(std::move(model), fieldName, &frame, nullptr);
}

namespace {
std::shared_ptr<Volume> makeMutableVolume(amr::Model model, std::string_view fieldName, const VolumeFrame* frame,
                                          accel::BrickSet* given) {
    auto v = std::make_shared<Volume>();
    v->cellCount = model.cells.size();
    const amr::Field& field = fieldName.empty() ? model.defaultField() : model.field(fieldName);
    v->fieldIndex = size_t(&field - model.fields.data());
    v->summary = amr::summarize(model);
    v->frameBounds = frame ? frame->bounds : v->summary.bounds;
    v->localOrigin = v->frameBounds.lower;
    if (frame) {
        AMRVK_CHECK(frame->minLevel <= v->summary.minLevel &&
                        glm::all(glm::lessThanEqual(frame->bounds.lower, v->summary.bounds.lower)) &&
                        glm::all(glm::lessThanEqual(v->summary.bounds.upper, frame->bounds.upper)),
                    "internal: a part reaches outside its frame");
        v->summary.minLevel = frame->minLevel;
    }
    // Local coordinates (what the GPU sees) are int32 and float: refuse a wider domain up front.
    for (int a = 0; a < 3; ++a)
        AMRVK_CHECK(v->summary.bounds.upper[a] - v->localOrigin[a] <= INT32_MAX, model.source, ": the data spans ",
                    v->summary.bounds.upper[a] - v->localOrigin[a], " finest cells along axis ", "xyz"[a],
                    ", more than 2^31 from the data's lower corner (the limit)");
    v->fieldStats = amr::computeFieldStats(model, field);
    if (frame) {
        v->fieldStats.minValue = frame->valueLo;
        v->fieldStats.maxValue = frame->valueHi;
        v->percentiles = frame->percentiles;
        v->volumeHistogram = frame->volumeHistogram;
    } else {
        ProgressStage stage("percentiles");
        v->percentiles = amr::percentilesOf(field.values);
        if (v->percentiles.count > 0)  // else no finite value: nothing to fit a TF to
            v->volumeHistogram = amr::volumeHistogramOf(model.cells, field.values, v->valueLo(), v->valueHi(),
                                                        v->summary.minLevel, v->frameBounds.volume());
    }
    if (given) {  // the model stays in its order; the field is copied into slot order
        v->bricks = std::move(*given);
        v->slotValues = accel::brickOrderValues(v->bricks, field);
    } else {
        // At most one brick per cell; the cells and values are reordered in place.
        ProgressStage stage(strCat("bricks of ", model.cells.size(), " cells"),
                            memoryNote(uint64_t(model.cells.size()) * sizeof(accel::Brick), true));
        v->bricks = accel::buildBricks(model, {}, &v->summary);  // its levels, count and bounds are the model's
        stage.setResult(strCat(v->bricks.bricks.size(), " bricks, ", formatBytes(v->bricks.memoryBytes())));
    }
    v->model = std::move(model);
    return v;
}
}  // namespace

}  // namespace amrvk::scene
