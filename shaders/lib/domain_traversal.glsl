// Majorant traversal over a set of boxes ("domains": ABRs, brick bounds, brick domains, non-empty
// macrocells or kd-tree leaves), front to back. One query per segment finds, at ray parameter t,
// the boxes covering t (majorant = their maximum, segment end = their nearest exit) and the
// nearest entry of a box ahead; the segment is [t, min(both)]. Boxes may overlap (ext-brick);
// disjoint boxes give exactly one covering box. Segments are contiguous and never skip a box with
// majorant > 0; where nothing covers t the ray skips to the next entry (majorant 0 there).
// grid-bvh steps its macrocells with the DDA and queries only to skip long runs of culled ones
// (gridBvhNext, traversal.glsl).
// Back-ends: software BVH over the non-empty boxes (kBackendSw) or a ray query over an AABB BLAS
// whose culled boxes are inactive (kBackendRq). Both filter candidates with the same exact slab
// test (rayBoxInterval, ray_box.glsl), so they yield identical segments.
// CPU check: tests/gpu/traversal_gpu_test.cpp compares segments with brute force over all boxes.
#ifndef AMRVK_DOMAIN_TRAVERSAL_GLSL
#define AMRVK_DOMAIN_TRAVERSAL_GLSL

#include "lib/ray_box.glsl"

// Box of domain `id`, local voxel space. Macrocells are computed from the grid (no storage); the
// same expression everywhere (precise: no fused multiply-add) so neighbours share faces exactly.
void domainBox(uint traversal, uint id, out vec3 lo, out vec3 hi) {
    if (traversal == kTraversalGridBvh) {
        ivec3 dims = P.scene.gridDims;
        uvec3 c = uvec3(id % uint(dims.x), (id / uint(dims.x)) % uint(dims.y), id / uint(dims.x * dims.y));
        precise vec3 l = P.scene.gridOrigin + vec3(c) * P.scene.gridCellSize;
        precise vec3 h = P.scene.gridOrigin + vec3(c + 1u) * P.scene.gridCellSize;
        lo = l;
        hi = h;
        return;
    }
    AabbGpu b = AabbRef(P.majorants.domainBoxes).v[id];
    lo = b.lo;
    hi = b.hi;
}

float domainMajorant(uint id) { return FloatRef(P.majorants.domainMajorants).v[id]; }

struct SegmentQuery {
    float end;     // segment end: nearest exit of a covering box or entry of a box ahead
    float maj;     // max TF alpha over the covering boxes (0 when none covers t)
    uint prim;     // covering box with the largest majorant (smallest id on ties); ~0u if none
    bool covered;
};

// Folds one candidate box (its interval ex) into the query at t. Only boxes that overlap the ray
// over a positive length ahead of t and have a majorant > 0 count: touching a box in one point,
// or a culled box reported by a ray query, changes nothing.
void foldCandidate(uint id, vec2 ex, float t, inout SegmentQuery q) {
    if (!(ex.x < ex.y) || ex.y <= t) return;  // misses, touches, or lies behind t
    float m = domainMajorant(id);
    if (!(m > 0.0)) return;
    if (ex.x <= t) {
        if (!q.covered || m > q.maj || (m == q.maj && id < q.prim)) {
            q.maj = m;
            q.prim = id;
        }
        q.covered = true;
        q.end = min(q.end, ex.y);
    } else {
        q.end = min(q.end, ex.x);
    }
}

SegmentQuery newSegmentQuery(float tEnd) {
    SegmentQuery q;
    q.end = tEnd;
    q.maj = 0.0;
    q.prim = ~0u;
    q.covered = false;
    return q;
}

SegmentQuery querySegmentSw(uint traversal, vec3 o, vec3 d, float t, float tEnd) {
    SegmentQuery q = newSegmentQuery(tEnd);
    if (P.majorants.domainAnyActive == 0u) return q;  // every box culled: no BVH
    BvhRef nodes = BvhRef(P.majorants.domainNodes);
    UintRef prims = UintRef(P.majorants.domainPrims);
    uint stack[kBvhStackSize];
    float stackEntry[kBvhStackSize];
    int top = 0;
    {
        BvhNodeGpu root = nodes.v[0];
        vec2 ex = rayBoxInterval(root.lo, root.hi, o, d);
        if (ex.x > ex.y || ex.y <= t) return q;
        stack[top] = 0u;
        stackEntry[top++] = ex.x;
    }
    while (top > 0) {
        --top;
        if (stackEntry[top] >= q.end) continue;  // cannot cover t nor end the segment earlier
        BvhNodeGpu n = nodes.v[stack[top]];
        if (n.count > 0u) {
            for (uint i = 0u; i < n.count; ++i) {
                uint id = prims.v[n.first + i];
                vec3 lo, hi;
                domainBox(traversal, id, lo, hi);
                foldCandidate(id, rayBoxInterval(lo, hi, o, d), t, q);
            }
            continue;
        }
        // Test both children now; push the far one first so the near one is visited first.
        BvhNodeGpu a = nodes.v[n.first], b = nodes.v[n.first + 1u];
        vec2 ea = rayBoxInterval(a.lo, a.hi, o, d), eb = rayBoxInterval(b.lo, b.hi, o, d);
        bool hitA = ea.x <= ea.y && ea.y > t && ea.x < q.end;
        bool hitB = eb.x <= eb.y && eb.y > t && eb.x < q.end;
        bool aFirst = ea.x <= eb.x;
        if (hitA && hitB) {
            stack[top] = aFirst ? n.first + 1u : n.first;
            stackEntry[top++] = aFirst ? eb.x : ea.x;
            stack[top] = aFirst ? n.first : n.first + 1u;
            stackEntry[top++] = aFirst ? ea.x : eb.x;
        } else if (hitA || hitB) {
            stack[top] = hitA ? n.first : n.first + 1u;
            stackEntry[top++] = hitA ? ea.x : eb.x;
        }
    }
    return q;
}

#ifdef AMRVK_RAY_QUERY
// Every AABB candidate is folded with the exact test; a committed hit at the current segment end
// lets the hardware cull boxes that start beyond it.
SegmentQuery querySegmentRq(uint traversal, vec3 o, vec3 d, float t, float tEnd) {
    SegmentQuery q = newSegmentQuery(tEnd);
    if (P.majorants.domainAnyActive == 0u) return q;
    rayQueryEXT rq;
    rayQueryInitializeEXT(rq, accelerationStructureEXT(P.majorants.domainAccel), gl_RayFlagsNoneEXT, 0xFFu, o, t, d, tEnd);
    while (rayQueryProceedEXT(rq)) {
        if (rayQueryGetIntersectionTypeEXT(rq, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
        uint id = uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, false));
        vec3 lo, hi;
        domainBox(traversal, id, lo, hi);
        float before = q.end;
        foldCandidate(id, rayBoxInterval(lo, hi, o, d), t, q);
        if (q.end < before) rayQueryGenerateIntersectionEXT(rq, q.end);
    }
    return q;
}
#endif

SegmentQuery querySegment(uint traversal, uint backend, vec3 o, vec3 d, float t, float tEnd) {
#ifdef AMRVK_RAY_QUERY
    if (backend == kBackendRq) return querySegmentRq(traversal, o, d, t, tEnd);
#endif
    return querySegmentSw(traversal, o, d, t, tEnd);
}

#endif
