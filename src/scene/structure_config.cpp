#include "scene/structure_config.h"

#include "core/error.h"
#include "core/strings.h"

namespace amrvk::scene {

namespace {
constexpr Named<Backend> kBackends[] = {{"sw", Backend::Sw}, {"rq", Backend::Rq}, {"auto", Backend::Auto}};

template <class Traits, size_t N>
auto parseByName(const Traits (&table)[N], const std::string& name, const char* option) {
    for (const Traits& t : table)
        if (name == t.name) return t.kind;
    std::vector<std::string> names;
    for (const Traits& t : table) names.push_back(t.name);
    AMRVK_CHECK(false, option, " '", name, "': expected ", join(names, "|"));
    return table[0].kind;
}
}  // namespace

SamplerKind parseSampler(const std::string& name) { return parseByName(kSamplerTraits, name, "--sampler"); }
const char* samplerName(SamplerKind kind) { return traitsOf(kind).name; }
TraversalKind parseTraversal(const std::string& name) { return parseByName(kTraversalTraits, name, "--traversal"); }
const char* traversalName(TraversalKind kind) { return traitsOf(kind).name; }
Backend parseBackend(const std::string& name) { return parseNamed(kBackends, name, "--backend"); }
const char* backendName(Backend backend) { return nameOf(kBackends, backend); }

std::vector<TraversalKind> allTraversals() {
    std::vector<TraversalKind> out;
    for (const TraversalTraits& t : kTraversalTraits) out.push_back(t.kind);
    return out;
}
std::vector<SamplerKind> allSamplers() {
    std::vector<SamplerKind> out;
    for (const SamplerTraits& s : kSamplerTraits)
        if (s.amr) out.push_back(s.kind);
    return out;
}

uint32_t parseSubMajorants(const std::string& text, const char* option) {
    for (uint32_t n : {0u, 2u, 4u, 8u, 16u})
        if (text == subMajorantsName(n)) return n;
    AMRVK_CHECK(false, option, " '", text, "': expected off, 2, 4, 8 or 16");
    return 0;
}

std::string subMajorantsName(uint32_t subMajorants) { return subMajorants == 0 ? "off" : std::to_string(subMajorants); }

bool StructureConfig::hasSubMajorants() const {
    return subMajorants > 0 && traitsOf(traversal).macrocellRanges && traitsOf(sampler).amr;
}

bool StructureConfig::usesGrid() const {
    return traitsOf(traversal).macrocellRanges || traitsOf(sampler).lookup == Lookup::BrickGrid;
}

void StructureConfig::validate() const {
    AMRVK_CHECK(traitsOf(sampler).amr || traitsOf(traversal).macrocellRanges, "--sampler ", samplerName(sampler),
                " needs --traversal grid-dda or grid-bvh (its majorants come from the dense samples), not ",
                traversalName(traversal));
    (void)parseSubMajorants(subMajorantsName(subMajorants));  // off, 2, 4, 8 or 16
}

std::string StructureConfig::label() const {
    return std::string(traversalName(traversal)) + "/" + samplerName(sampler) + "/" + backendName(backend);
}

std::string StructureConfig::labelWithSub() const {
    return label() + (hasSubMajorants() ? " sub " + std::to_string(subMajorants) : "");
}

std::string StructureConfig::labelWithGrid() const {
    return label() + (usesGrid() ? " grid " + grid : "") + (hasSubMajorants() ? " sub " + std::to_string(subMajorants) : "");
}

TraversalKind fittingTraversal(double leafVolume, double boundsVolume, std::string* why) {
    const double coverage = boundsVolume > 0 ? leafVolume / boundsVolume : 1.0;
    if (coverage >= kGridMinCoverage) return TraversalKind::GridDda;
    if (why)
        *why = strCat("traversal abr: the cells fill ", coverage, " of their bounding box (below ", kGridMinCoverage,
                      "), so grid macrocells would be mostly empty space (give --traversal to choose)");
    return TraversalKind::Abr;
}

BackendChoice resolveBackend(const StructureConfig& config, const DeviceTraits& device) {
    if (config.backend != Backend::Auto) {
        AMRVK_CHECK(config.backend != Backend::Rq || device.rayQuery, "--backend rq: device '", device.name,
                    "' has no VK_KHR_ray_query (use --backend sw or auto)");
        return {config.backend, ""};
    }
    const StructurePlan sw = planOf(config.traversal, config.sampler, Backend::Sw, false);
    if (!sw.boxMajorants && !sw.samplerBvh)
        return {Backend::Sw, "--backend auto: sw (" + config.label() + " uses no box hierarchy)"};
    if (device.cpu)
        return {Backend::Sw, "--backend auto: sw (on CPU devices ray queries were measured 3-4x slower than the "
                             "software BVH; --backend rq to use them)"};
    if (!device.rayQuery) return {Backend::Sw, "--backend auto: sw (device '" + device.name + "' has no ray queries)"};
    return {Backend::Sw, "--backend auto: sw (ray queries are not measured faster on GPUs yet; --backend rq to use "
                         "them, --traversal auto measures both)"};
}

}  // namespace amrvk::scene
