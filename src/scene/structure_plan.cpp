#include "scene/structure_plan.h"

#include "core/error.h"

namespace amrvk::scene {

const TraversalTraits& traitsOf(TraversalKind kind) {
    for (const TraversalTraits& t : kTraversalTraits)
        if (t.kind == kind) return t;
    AMRVK_CHECK(false, "internal: traversal ", uint32_t(kind), " has no row in kTraversalTraits");
    return kTraversalTraits[0];
}

const SamplerTraits& traitsOf(SamplerKind kind) {
    for (const SamplerTraits& s : kSamplerTraits)
        if (s.kind == kind) return s;
    AMRVK_CHECK(false, "internal: sampler ", uint32_t(kind), " has no row in kSamplerTraits");
    return kSamplerTraits[0];
}

StructurePlan planOf(TraversalKind traversal, SamplerKind sampler, Backend backend, bool subMajorants) {
    AMRVK_CHECK(backend != Backend::Auto, "internal: a structure plan needs a resolved back-end");
    const TraversalTraits& t = traitsOf(traversal);
    const SamplerTraits& s = traitsOf(sampler);
    const bool bvhLookup = s.lookup == Lookup::BrickDomainBvh || s.lookup == Lookup::AbrBvh;
    StructurePlan p;
    p.traversal = traversal;
    p.sampler = sampler;
    p.backend = backend;
    p.traversalBoxes = t.boxes;
    p.lookup = s.lookup;
    p.abrs = s.lookup == Lookup::AbrBvh || t.boxes == BoxSet::Abrs;
    p.samplerBvh = bvhLookup && backend == Backend::Sw;
    p.samplerBoxes = bvhLookup && backend == Backend::Rq;
    p.denseGrid = s.lookup == Lookup::Dense;
    p.macrocellRanges = t.macrocellRanges;
    p.subMajorants = subMajorants && p.macrocellRanges && s.amr;
    p.brickGrid = s.lookup == Lookup::BrickGrid || p.subMajorants;
    p.rangesFromDense = p.denseGrid && p.macrocellRanges;
    p.staticBoxes = t.boxes == BoxSet::Abrs || t.boxes == BoxSet::BrickBounds || t.boxes == BoxSet::BrickDomains;
    p.supportRangeQuery = t.boxes == BoxSet::KdLeaves;
    p.bricksOnDevice = s.amr;
    p.boxMajorants = t.boxes != BoxSet::None;
    p.boxesPerTf = t.boxes == BoxSet::KdLeaves;
    p.rayQueryCulling = p.boxMajorants && backend == Backend::Rq;
    return p;
}

}  // namespace amrvk::scene
