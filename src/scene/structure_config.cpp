#include "scene/structure_config.h"

#include "core/error.h"

namespace amrvk::scene {

namespace {
struct Named {
    const char* name;
    int value;
};
constexpr Named kSamplers[] = {{"ext-brick", int(SamplerKind::ExtBrick)}, {"abr", int(SamplerKind::Abr)},
                               {"dense", int(SamplerKind::Dense)}, {"grid", int(SamplerKind::Grid)}};
constexpr Named kTraversals[] = {{"grid-dda", int(TraversalKind::GridDda)}, {"grid-bvh", int(TraversalKind::GridBvh)},
                                 {"abr", int(TraversalKind::Abr)},          {"brick", int(TraversalKind::Brick)},
                                 {"ext-brick", int(TraversalKind::ExtBrick)}, {"kdtree", int(TraversalKind::KdTree)}};
constexpr Named kBackends[] = {{"sw", int(Backend::Sw)}, {"rq", int(Backend::Rq)}, {"auto", int(Backend::Auto)}};

template <size_t N>
int parseNamed(const Named (&table)[N], const std::string& name, const char* option) {
    std::string choices;
    for (const Named& n : table) {
        if (name == n.name) return n.value;
        choices += choices.empty() ? n.name : std::string("|") + n.name;
    }
    AMRVK_CHECK(false, option, " '", name, "': expected ", choices);
    return 0;
}

template <size_t N>
const char* nameOf(const Named (&table)[N], int value) {
    for (const Named& n : table)
        if (n.value == value) return n.name;
    return "?";
}
}  // namespace

SamplerKind parseSampler(const std::string& name) { return SamplerKind(parseNamed(kSamplers, name, "--sampler")); }
const char* samplerName(SamplerKind kind) { return nameOf(kSamplers, int(kind)); }
TraversalKind parseTraversal(const std::string& name) {
    return TraversalKind(parseNamed(kTraversals, name, "--traversal"));
}
const char* traversalName(TraversalKind kind) { return nameOf(kTraversals, int(kind)); }
Backend parseBackend(const std::string& name) { return Backend(parseNamed(kBackends, name, "--backend")); }
const char* backendName(Backend backend) { return nameOf(kBackends, int(backend)); }

std::vector<TraversalKind> allTraversals() {
    std::vector<TraversalKind> out;
    for (const Named& n : kTraversals) out.push_back(TraversalKind(n.value));
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
