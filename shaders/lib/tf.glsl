// Transfer function: piecewise linear in every channel between nodes (positions ascending, in
// field units); constant beyond the first and last node. tfMaxAlpha is the exact maximum of the
// same function over [lo, hi] (both ends interpolated, every node in [lo, hi] included, so a
// step exactly on an end counts), so majorants
// and lookups agree. CPU twin: scene/transfer_function.* (evaluate, maxAlpha).
#ifndef AMRVK_TF_GLSL
#define AMRVK_TF_GLSL

vec4 evalTf(float v) {
    FloatRef pos = FloatRef(P.majorants.tfPositions);
    Vec4Ref col = Vec4Ref(P.majorants.tfColors);
    int n = int(P.majorants.tfNodeCount);
    if (!(v > pos.v[0])) return col.v[0];  // also catches NaN
    if (v >= pos.v[n - 1]) return col.v[n - 1];
    int lo = 0, hi = n - 1;  // invariant: pos[lo] <= v < pos[hi]
    while (hi - lo > 1) {
        int mid = (lo + hi) >> 1;
        if (pos.v[mid] <= v) lo = mid;
        else hi = mid;
    }
    float span = pos.v[hi] - pos.v[lo];
    float f = span > 0.0 ? (v - pos.v[lo]) / span : 1.0;
    return mix(col.v[lo], col.v[hi], f);
}

float tfMaxAlpha(float lo, float hi) {
    if (lo > hi) return 0.0;  // empty range
    FloatRef pos = FloatRef(P.majorants.tfPositions);
    Vec4Ref col = Vec4Ref(P.majorants.tfColors);
    int n = int(P.majorants.tfNodeCount);
    float m = max(evalTf(lo).a, evalTf(hi).a);
    for (int i = 0; i < n; ++i)
        if (pos.v[i] >= lo && pos.v[i] <= hi) m = max(m, col.v[i].a);
    return m;
}

#endif
