// Field reconstruction at a local-voxel-space point (exabrick-reference.md 3.1-3.2): the tent-
// weighted sum f = sum(phi v) / sum(phi) gathered brick by brick (clamped trilinear over <= 8
// cells of each brick whose basis domain contains p). Bricks are found by a point query into a
// software BVH: over brick domains (kSampler == kSamplerExtBrick) or over ABR boxes, whose brick
// list is then evaluated (kSamplerAbr). Never culled by the transfer function.
// CPU twins: amr/sampler.* (brute force), accel/brick_sampler.* (same paths in double).
#ifndef AMRVK_AMR_SAMPLE_GLSL
#define AMRVK_AMR_SAMPLE_GLSL

struct FieldSample {
    float value;      // reconstructed value (0 when weightSum == 0)
    float weightSum;  // 0: p is outside every cell support
    bool inside;      // p lies in a leaf cell (the medium); outside it extinction is 0
};

void addBrickContribution(uint brickId, vec3 p, inout float sumW, inout float sumWV,
                          inout bool inside) {
    BrickGpu b = BrickRef(P.bricks).v[brickId];
    float w = float(1 << b.lowerLevel.w);
    vec3 lower = vec3(b.lowerLevel.xyz);
    vec3 size = vec3(b.sizeBegin.xyz);
    vec3 rel = (p - lower) / w;  // position in cells from the brick's lower corner
    // Domain test (bounds grown by half a cell): outside it the brick has no weight at p.
    if (any(lessThan(rel, vec3(-0.5))) || any(greaterThan(rel, size + 0.5))) return;
    bool inBounds = all(greaterThanEqual(rel, vec3(0.0))) && all(lessThanEqual(rel, size));
    vec3 local = rel - 0.5;
    vec3 i0 = floor(local);
    vec3 f = local - i0;
    FloatRef values = FloatRef(P.brickValues);
    for (int c = 0; c < 8; ++c) {
        ivec3 bit = ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        ivec3 idx = ivec3(i0) + bit;
        if (any(lessThan(idx, ivec3(0))) || any(greaterThanEqual(idx, b.sizeBegin.xyz))) continue;
        vec3 wt = mix(1.0 - f, f, vec3(bit));
        float phi = wt.x * wt.y * wt.z;
        float v = values.v[uint(b.sizeBegin.w) + uint(idx.x + b.sizeBegin.x * (idx.y + b.sizeBegin.y * idx.z))];
        if (isnan(v) || phi <= 0.0) continue;
        sumW += phi;
        sumWV += phi * v;
    }
    // A point on the brick's bounds belongs to the medium when some cell there has a value.
    if (inBounds) inside = true;
}

bool boxContains(vec3 lo, vec3 hi, vec3 p) {
    return all(greaterThanEqual(p, lo)) && all(lessThanEqual(p, hi));
}

// Evaluates the bricks of one ABR (no lookup: used when traversal already knows the ABR).
FieldSample sampleInAbr(uint abrId, vec3 p) {
    AbrGpu a = AbrRef(P.abrs).v[abrId];
    float sumW = 0.0, sumWV = 0.0;
    bool inside = false;
    UintRef list = UintRef(P.abrBrickList);
    for (uint i = 0; i < a.brickCount; ++i) addBrickContribution(list.v[a.brickBegin + i], p, sumW, sumWV, inside);
    FieldSample s;
    s.weightSum = sumW;
    s.value = sumW > 0.0 ? sumWV / sumW : 0.0;
    s.inside = inside && sumW > 0.0;
    return s;
}

FieldSample sampleField(uint samplerKind, vec3 p) {
    BvhRef nodes = BvhRef(P.samplerNodes);
    UintRef prims = UintRef(P.samplerPrims);
    float sumW = 0.0, sumWV = 0.0;
    bool inside = false;
    uint stack[kBvhStackSize];  // small: lavapipe keeps it per lane in memory
    int top = 0;
    stack[top++] = 0u;
    while (top > 0) {
        BvhNodeGpu n = nodes.v[stack[--top]];
        if (!boxContains(n.lo, n.hi, p)) continue;
        if (n.count == 0u) {
            stack[top++] = n.first + 1u;
            stack[top++] = n.first;
            continue;
        }
        for (uint i = 0; i < n.count; ++i) {
            uint prim = prims.v[n.first + i];
            if (samplerKind == kSamplerExtBrick) {
                addBrickContribution(prim, p, sumW, sumWV, inside);
            } else {
                AbrGpu a = AbrRef(P.abrs).v[prim];
                if (boxContains(a.lo, a.hi, p)) return sampleInAbr(prim, p);
            }
        }
    }
    FieldSample s;
    s.weightSum = sumW;
    s.value = sumW > 0.0 ? sumWV / sumW : 0.0;
    s.inside = inside && sumW > 0.0;
    return s;
}

#endif
