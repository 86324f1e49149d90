#include "viewer/logic/data_change.h"

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/strings.h"
#include "scene/tf_presets.h"
#include "viewer/logic/tf_editor.h"

namespace fs = std::filesystem;

namespace amrvk::viewer {

namespace {

std::string nanName(amr::NanPolicy p) { return p == amr::NanPolicy::Drop ? "drop" : "reject"; }

std::string dimsText(glm::ivec3 d) {
    return d == glm::ivec3(0) ? "from the name"
                              : std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

}  // namespace

DataChangeCheck dataChange(const session::Session& shown, const session::Session& next) {
    auto other = [](std::string why) { return DataChangeCheck{DataChange::Other, std::move(why)}; };
    const fs::path a = fs::absolute(shown.input).lexically_normal(), b = fs::absolute(next.input).lexically_normal();
    if (a != b) return other("another data set: " + b.string() + " (this viewer shows " + a.string() + ")");
    if (next.field != shown.field)
        return other("another field: '" + next.field + "' (this viewer shows '" + shown.field + "')");
    const amr::ReadOptions &r = shown.read, &n = next.read;
    if (n.format != r.format) return other("read.format " + n.format + " (this viewer read " + r.format + ")");
    if (n.nanPolicy != r.nanPolicy)
        return other("read.nan " + nanName(n.nanPolicy) + " (this viewer read " + nanName(r.nanPolicy) + ")");
    if (n.rawDims != r.rawDims)
        return other("read.dims " + dimsText(n.rawDims) + " (this viewer read " + dimsText(r.rawDims) + ")");
    if (n.rawType != r.rawType) return other("read.type '" + n.rawType + "' (this viewer read '" + r.rawType + "')");
    if (n.rawThreshold != r.rawThreshold)
        return other("read.threshold " + formatDouble(n.rawThreshold) + " (this viewer read " +
                     formatDouble(r.rawThreshold) + ")");
    // The floor matters on the log scale only.
    if (n.scale != r.scale || (n.scale == amr::FieldScale::Log && n.logFloor != r.logFloor))
        return {DataChange::Rescale, ""};
    return {};
}

scene::TfChannels refitTfRange(const scene::TfChannels& tf, float lo, float hi) {
    AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo <= hi, "the field's range [", lo, ", ", hi,
                "] is not a finite interval");
    scene::TfChannels out = TfEditor::editable(tf);
    TfEditor(out).setRange(lo, hi > lo ? hi : lo + 1.0f);
    return out;
}

scene::TfChannels tfOnNewScale(const scene::TfChannels& tf, const scene::Volume& shown, const scene::Volume& next) {
    if (scene::presetFollowsData(tf.name)) {
        // Compared in the editor's form: the viewer's panels hold the TF that way.
        const scene::TfChannels fitted =
            scene::TfChannels::split(scene::makePreset(tf.name, shown.percentiles, shown.volumeHistogram));
        if (TfEditor::editable(tf) == TfEditor::editable(fitted))
            return scene::TfChannels::split(scene::makePreset(tf.name, next.percentiles, next.volumeHistogram));
    }
    return refitTfRange(tf, next.valueLo(), next.valueHi());
}

}  // namespace amrvk::viewer
