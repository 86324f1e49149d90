#include "scene/invalidation.h"

namespace amrvk::scene {

Invalidation invalidatedBy(ChangeSet c) {
    Invalidation v;
    v.accumulation = !c.empty();
    v.accumulationBuffer = c.has(Change::ImageSize);
    v.viewParams = c.has(Change::Camera) || c.has(Change::ImageSize) || c.has(Change::Seed);
    v.shadingParams = c.has(Change::Lighting) || c.has(Change::Medium) || c.has(Change::DvrOptions) ||
                      c.has(Change::Camera);  // dvr's headlight follows the camera
    v.pipelines = c.has(Change::Structure) || c.has(Change::Shaders);
    v.majorants = c.has(Change::TransferFunction) || c.has(Change::Structure) || c.has(Change::Control);
    v.minorants = c.has(Change::Control);
    v.culling = v.majorants;
    v.kdTree = v.majorants;
    v.deviceScene = c.has(Change::Structure);
    return v;
}

ChangeSet settingsChanges(const RenderSettings& a, const RenderSettings& b) {
    ChangeSet c;
    if (a.camera != b.camera) c |= Change::Camera;
    if (a.width != b.width || a.height != b.height) c |= Change::ImageSize;
    if (a.seed != b.seed) c |= Change::Seed;
    if (a.mode != b.mode) c |= Change::Mode;
    if (a.ambient != b.ambient || a.background != b.background || a.lights != b.lights)
        c |= Change::Lighting;
    if (a.densityScale != b.densityScale || a.g != b.g || a.maxTrackingSteps != b.maxTrackingSteps ||
        a.transmittance != b.transmittance || a.cut != b.cut)
        c |= Change::Medium;
    if (a.controlExtinction != b.controlExtinction) c |= Change::Control;
    if (a.dvrStep != b.dvrStep || a.dvrShading != b.dvrShading) c |= Change::DvrOptions;
    return c;
}

std::string describe(ChangeSet c) {
    static const std::pair<Change, const char*> kNames[] = {
        {Change::Camera, "camera"},         {Change::ImageSize, "image size"}, {Change::Seed, "seed"},
        {Change::Mode, "mode"},             {Change::Lighting, "lighting"},    {Change::Medium, "medium"},
        {Change::DvrOptions, "dvr options"}, {Change::TransferFunction, "transfer function"},
        {Change::Structure, "structure"},   {Change::Shaders, "shaders"},          {Change::Control, "control extinction"}};
    std::string out;
    for (const auto& [change, name] : kNames) {
        if (!c.has(change)) continue;
        if (!out.empty()) out += '|';
        out += name;
    }
    return out.empty() ? "nothing" : out;
}

}  // namespace amrvk::scene
