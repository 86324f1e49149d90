// Field reconstruction at a local-voxel-space point (exabrick-reference.md 3.1-3.2): the tent-
// weighted sum f = sum(phi v) / sum(phi) gathered brick by brick (clamped trilinear over <= 8
// cells of each brick whose basis domain contains p). Bricks are found by a point query over
// brick domains (kSamplerExtBrick: every containing brick, summed in ascending id order so both
// back-ends give identical values) or over ABR boxes (kSamplerAbr: the one ABR containing p under
// half-open containment lo <= p < hi, then its sorted brick list). Back-ends: software BVH
// (kBackendSw) or a ray query of length 0 at p (kBackendRq). Never culled by the transfer function.
// kSamplerGrid: the macrocell containing p (one index computation) lists every brick whose domain
// meets it, in ascending id order: the ext-brick sum without a tree descent (accel/brick_grid.*).
// kSamplerDense: the field resampled at the finest cell centres (accel/dense_grid.*), clamped
// trilinear: the speed-of-light reference for sampling cost, not the AMR reconstruction.
// CPU twins: amr/sampler.* (brute force), accel/brick_sampler.* (same paths in double),
// accel/brick_grid.* (GridSampler),
// accel/dense_grid.* (sampleDense).
#ifndef AMRVK_AMR_SAMPLE_GLSL
#define AMRVK_AMR_SAMPLE_GLSL

struct FieldSample {
    float value;      // reconstructed value (0 when weightSum == 0)
    float weightSum;  // 0: p is outside every cell support
    bool inside;      // p lies in a leaf cell (the medium); outside it extinction is 0
    int finestLevel;  // finest level among the bricks with weight at p (dvr step); 0 for dense
};

// Basis-function domain test: p within the brick's bounds grown by half a cell (closed).
bool brickDomainContains(BrickGpu b, vec3 p) {
    vec3 rel = (p - vec3(b.lower)) / float(1 << b.level);
    return all(greaterThanEqual(rel, vec3(-0.5))) && all(lessThanEqual(rel, vec3(b.size) + 0.5));
}

void addBrickContribution(uint brickId, vec3 p, inout float sumW, inout float sumWV,
                          inout bool inside, inout int finestLevel) {
    BrickGpu b = BrickRef(P.scene.bricks).v[brickId];
    float w = float(1 << b.level);
    vec3 lower = vec3(b.lower);
    vec3 size = vec3(b.size);
    vec3 rel = (p - lower) / w;  // position in cells from the brick's lower corner
    // Domain test (bounds grown by half a cell): outside it the brick has no weight at p.
    if (any(lessThan(rel, vec3(-0.5))) || any(greaterThan(rel, size + 0.5))) return;
    bool inBounds = all(greaterThanEqual(rel, vec3(0.0))) && all(lessThanEqual(rel, size));
    vec3 local = rel - 0.5;
    vec3 i0 = floor(local);
    vec3 f = local - i0;
    FloatRef values = FloatRef(P.scene.brickValues);
    for (int c = 0; c < 8; ++c) {
        ivec3 bit = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        ivec3 idx = ivec3(i0) + bit;
        if (any(lessThan(idx, ivec3(0))) || any(greaterThanEqual(idx, b.size))) continue;
        vec3 wt = mix(1.0 - f, f, vec3(bit));
        float phi = wt.x * wt.y * wt.z;
        float v = values.v[b.begin + uint(idx.x + b.size.x * (idx.y + b.size.y * idx.z))];
        if (isnan(v) || phi <= 0.0) continue;
        sumW += phi;
        sumWV += phi * v;
        finestLevel = min(finestLevel, b.level);
    }
    // A point on the brick's bounds belongs to the medium when some cell there has a value.
    if (inBounds) inside = true;
}

// Half-open containment: every point of the union of ABRs lies in exactly one ABR.
bool abrContains(AbrGpu a, vec3 p) { return all(greaterThanEqual(p, a.lo)) && all(lessThan(p, a.hi)); }

const int kNoLevel = 1 << 30;

FieldSample finishSample(float sumW, float sumWV, bool inside, int finestLevel) {
    FieldSample s;
    s.weightSum = sumW;
    s.value = sumW > 0.0 ? sumWV / sumW : 0.0;
    s.inside = inside && sumW > 0.0;
    s.finestLevel = finestLevel;
    return s;
}

// Evaluates the bricks of one ABR (no lookup: used when traversal already knows the ABR).
FieldSample sampleInAbr(uint abrId, vec3 p) {
    AbrGpu a = AbrRef(P.scene.abrs).v[abrId];
    float sumW = 0.0, sumWV = 0.0;
    bool inside = false;
    int level = kNoLevel;
    UintRef list = UintRef(P.scene.abrBrickList);
    for (uint i = 0; i < a.brickCount; ++i)
        addBrickContribution(list.v[a.brickBegin + i], p, sumW, sumWV, inside, level);
    return finishSample(sumW, sumWV, inside, level);
}

// Bricks whose domain contains p, kept sorted by id. Beyond kMaxGather (never seen in practice:
// a point lies in at most 8 domains per level) contributions are added in arrival order.
const uint kMaxGather = 32u;
struct BrickGather {
    uint ids[kMaxGather];
    uint n;
    float sumW, sumWV;
    bool inside;
    int finestLevel;
};

BrickGather newGather() {
    BrickGather g;
    g.n = 0u;
    g.sumW = 0.0;
    g.sumWV = 0.0;
    g.inside = false;
    g.finestLevel = kNoLevel;
    return g;
}

// Ray queries may report a box more than once: a repeated id is ignored.
void gatherBrick(inout BrickGather g, uint id, vec3 p) {
    if (!brickDomainContains(BrickRef(P.scene.bricks).v[id], p)) return;
    uint pos = g.n;  // insertion position in the sorted list
    while (pos > 0u && g.ids[pos - 1u] > id) --pos;
    if (pos > 0u && g.ids[pos - 1u] == id) return;
    if (g.n == kMaxGather) {
        addBrickContribution(id, p, g.sumW, g.sumWV, g.inside, g.finestLevel);
        return;
    }
    for (uint i = g.n; i > pos; --i) g.ids[i] = g.ids[i - 1u];
    g.ids[pos] = id;
    g.n++;
}

FieldSample finishGather(inout BrickGather g, vec3 p) {
    for (uint i = 0u; i < g.n; ++i) addBrickContribution(g.ids[i], p, g.sumW, g.sumWV, g.inside, g.finestLevel);
    return finishSample(g.sumW, g.sumWV, g.inside, g.finestLevel);
}

FieldSample sampleFieldSw(uint samplerKind, vec3 p) {
    BvhRef nodes = BvhRef(P.scene.samplerNodes);
    UintRef prims = UintRef(P.scene.samplerPrims);
    BrickGather g = newGather();
    uint stack[kBvhStackSize];  // small: lavapipe keeps it per lane in memory
    int top = 0;
    stack[top++] = 0u;
    while (top > 0) {
        BvhNodeGpu n = nodes.v[stack[--top]];
        if (!(all(greaterThanEqual(p, n.lo)) && all(lessThanEqual(p, n.hi)))) continue;
        if (n.count == 0u) {
            stack[top++] = n.first + 1u;
            stack[top++] = n.first;
            continue;
        }
        for (uint i = 0; i < n.count; ++i) {
            uint prim = prims.v[n.first + i];
            if (samplerKind == kSamplerExtBrick) {
                gatherBrick(g, prim, p);
            } else if (abrContains(AbrRef(P.scene.abrs).v[prim], p)) {
                return sampleInAbr(prim, p);
            }
        }
    }
    return finishGather(g, p);
}

#ifdef AMRVK_RAY_QUERY
// A short ray from p towards +xyz is reported by every box containing p with positive-length
// overlap, in particular the ABR that holds p under half-open containment (p may lie on its lower
// faces, which a zero-length ray can miss); boxes merely touching p carry zero weight there.
// The exact tests decide.
FieldSample sampleFieldRq(uint samplerKind, vec3 p) {
    BrickGather g = newGather();
    rayQueryEXT rq;
    rayQueryInitializeEXT(rq, accelerationStructureEXT(P.scene.samplerAccel), gl_RayFlagsNoneEXT, 0xFFu, p, 0.0,
                          vec3(1.0), 1e-3);
    while (rayQueryProceedEXT(rq)) {
        if (rayQueryGetIntersectionTypeEXT(rq, false) != gl_RayQueryCandidateIntersectionAABBEXT) continue;
        uint prim = uint(rayQueryGetIntersectionPrimitiveIndexEXT(rq, false));
        if (samplerKind == kSamplerExtBrick) {
            gatherBrick(g, prim, p);
        } else if (abrContains(AbrRef(P.scene.abrs).v[prim], p)) {
            rayQueryTerminateEXT(rq);
            return sampleInAbr(prim, p);
        }
    }
    return finishGather(g, p);
}
#endif

// The macrocell's list holds every brick whose domain meets it (grown by a margin far above the
// float rounding of p and of the index), so the domain test in addBrickContribution keeps exactly
// the bricks ext-brick gathers, visited in the same ascending id order.
FieldSample sampleGrid(vec3 p) {
    ivec3 dims = P.scene.gridDims;
    ivec3 c = clamp(ivec3(floor((p - P.scene.gridOrigin) / P.scene.gridCellSize)), ivec3(0), dims - 1);
    UintRef lists = UintRef(P.scene.gridBrickLists);
    uint cell = uint(c.x + dims.x * (c.y + dims.y * c.z));
    uint end = lists.v[cell + 1u];
    float sumW = 0.0, sumWV = 0.0;
    bool inside = false;
    int level = kNoLevel;
    for (uint i = lists.v[cell]; i < end; ++i) addBrickContribution(lists.v[i], p, sumW, sumWV, inside, level);
    return finishSample(sumW, sumWV, inside, level);
}

// Clamped trilinear interpolation of the dense samples; NaN samples (outside the medium) are
// skipped and the remaining weights renormalised. inside = the sample of the dense cell holding p
// is a value. CPU twin: accel/dense_grid.cpp (sampleDense).
FieldSample sampleDense(vec3 p) {
    FloatRef values = FloatRef(P.scene.denseValues);
    ivec3 dims = P.scene.denseDims;
    vec3 q = (p - P.scene.denseOrigin) / P.scene.denseSpacing;
    ivec3 cell = clamp(ivec3(floor(q)), ivec3(0), dims - 1);
    bool inside = !isnan(values.v[cell.x + dims.x * (cell.y + dims.y * cell.z)]);
    vec3 local = q - 0.5;
    vec3 i0 = floor(local);
    vec3 f = local - i0;
    float sumW = 0.0, sumWV = 0.0;
    for (int c = 0; c < 8; ++c) {
        ivec3 bit = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        ivec3 idx = clamp(ivec3(i0) + bit, ivec3(0), dims - 1);
        vec3 wt = mix(1.0 - f, f, vec3(bit));
        float phi = wt.x * wt.y * wt.z;
        float v = values.v[idx.x + dims.x * (idx.y + dims.y * idx.z)];
        if (isnan(v) || phi <= 0.0) continue;
        sumW += phi;
        sumWV += phi * v;
    }
    return finishSample(sumW, sumWV, inside, P.scene.denseLevel);
}

FieldSample sampleField(uint samplerKind, uint backend, vec3 p) {
    if (samplerKind == kSamplerDense) return sampleDense(p);
    if (samplerKind == kSamplerGrid) return sampleGrid(p);
#ifdef AMRVK_RAY_QUERY
    if (backend == kBackendRq) return sampleFieldRq(samplerKind, p);
#endif
    return sampleFieldSw(samplerKind, p);
}

#endif
