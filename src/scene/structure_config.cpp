#include "scene/structure_config.h"

#include "core/error.h"
#include "core/strings.h"

namespace amrvk::scene {

namespace {
constexpr Named<SamplerKind> kSamplers[] = {{"ext-brick", SamplerKind::ExtBrick},
                                            {"abr", SamplerKind::Abr},
                                            {"dense", SamplerKind::Dense},
                                            {"grid", SamplerKind::Grid}};
constexpr Named<TraversalKind> kTraversals[] = {
    {"grid-dda", TraversalKind::GridDda}, {"grid-bvh", TraversalKind::GridBvh},   {"abr", TraversalKind::Abr},
    {"brick", TraversalKind::Brick},      {"ext-brick", TraversalKind::ExtBrick}, {"kdtree", TraversalKind::KdTree}};
constexpr Named<Backend> kBackends[] = {{"sw", Backend::Sw}, {"rq", Backend::Rq}, {"auto", Backend::Auto}};
}  // namespace

SamplerKind parseSampler(const std::string& name) { return parseNamed(kSamplers, name, "--sampler"); }
const char* samplerName(SamplerKind kind) { return nameOf(kSamplers, kind); }
TraversalKind parseTraversal(const std::string& name) { return parseNamed(kTraversals, name, "--traversal"); }
const char* traversalName(TraversalKind kind) { return nameOf(kTraversals, kind); }
Backend parseBackend(const std::string& name) { return parseNamed(kBackends, name, "--backend"); }
const char* backendName(Backend backend) { return nameOf(kBackends, backend); }

std::vector<TraversalKind> allTraversals() {
    std::vector<TraversalKind> out;
    for (const Named<TraversalKind>& n : kTraversals) out.push_back(n.value);
    return out;
}
std::vector<SamplerKind> allSamplers() { return {SamplerKind::ExtBrick, SamplerKind::Abr, SamplerKind::Grid}; }

void StructureConfig::validate() const {
    AMRVK_CHECK(sampler != SamplerKind::Dense || usesGrid(), "--sampler dense needs --traversal grid-dda or grid-bvh ",
                "(its majorants come from the dense samples), not ", traversalName(traversal));
}

std::string StructureConfig::label() const {
    return std::string(traversalName(traversal)) + "/" + samplerName(sampler) + "/" + backendName(backend);
}

std::string StructureConfig::labelWithGrid() const { return label() + (usesGrid() ? " grid " + grid : ""); }

TraversalKind fittingTraversal(double leafVolume, double boundsVolume, std::string* why) {
    const double coverage = boundsVolume > 0 ? leafVolume / boundsVolume : 1.0;
    if (coverage >= kGridMinCoverage) return TraversalKind::GridDda;
    if (why)
        *why = strCat("traversal abr: the cells fill ", coverage, " of their bounding box (below ", kGridMinCoverage,
                      "), so grid macrocells would be mostly empty space (give --traversal to choose)");
    return TraversalKind::Abr;
}

Backend resolveBackend(Backend requested, bool deviceHasRayQuery, const std::string& deviceName) {
    if (requested == Backend::Auto) return deviceHasRayQuery ? Backend::Rq : Backend::Sw;
    AMRVK_CHECK(requested != Backend::Rq || deviceHasRayQuery, "--backend rq: device '", deviceName,
                "' has no VK_KHR_ray_query (use --backend sw or auto)");
    return requested;
}

}  // namespace amrvk::scene
