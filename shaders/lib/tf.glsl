// Transfer function: piecewise linear in every channel between nodes (positions ascending, in
// field units); constant beyond the first and last node. tfMaxAlpha is the exact maximum of the
// same function over [lo, hi] (both ends interpolated, every node in [lo, hi] included, so a
// step exactly on an end counts), so majorants and lookups agree. Both cost O(log nodes): binary
// searches and a max tree over the node alphas, so a TF of 10^6 nodes costs what one of 20 does
// per macrocell. tfMinAlpha is the same for the minimum (minorants). CPU twin:
// scene/transfer_function.* (evaluate, maxAlpha, minAlpha).
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

// The largest alpha of nodes a..b (inclusive) from the max tree (MajorantsGpu::tfAlphaTree).
float tfNodesMaxAlpha(int a, int b) {
    FloatRef tree = FloatRef(P.majorants.tfAlphaTree);
    int n = int(P.majorants.tfNodeCount);
    int leaves = n <= 1 ? 1 : 1 << (findMSB(n - 1) + 1);
    float m = 0.0;
    for (int l = a + leaves, r = b + leaves + 1; l < r; l >>= 1, r >>= 1) {
        if ((l & 1) != 0) m = max(m, tree.v[l++]);
        if ((r & 1) != 0) m = max(m, tree.v[--r]);
    }
    return m;
}

// Nodes with lo <= position <= hi as [first, last), found as std::lower_bound(lo) and
// std::upper_bound(hi) find them (the same predicates, so a NaN end gives the same nodes as on the CPU).
void tfNodesIn(float lo, float hi, out int first, out int last) {
    FloatRef pos = FloatRef(P.majorants.tfPositions);
    int n = int(P.majorants.tfNodeCount);
    first = 0;
    int end = n;
    while (first < end) {
        int mid = (first + end) >> 1;
        if (pos.v[mid] < lo) first = mid + 1;
        else end = mid;
    }
    last = first;
    end = n;
    while (last < end) {
        int mid = (last + end) >> 1;
        if (!(hi < pos.v[mid])) last = mid + 1;
        else end = mid;
    }
}

float tfMaxAlpha(float lo, float hi) {
    if (lo > hi) return 0.0;  // empty range
    float m = max(evalTf(lo).a, evalTf(hi).a);
    int first, last;
    tfNodesIn(lo, hi, first, last);
    if (first < last) m = max(m, tfNodesMaxAlpha(first, last - 1));
    return m;
}

// The least alpha over [lo, hi] (TransferFunction::minAlpha), from MajorantsGpu::tfAlphaMinTree;
// +inf for an empty range.
float tfMinAlpha(float lo, float hi) {
    if (lo > hi) return kInf;
    float m = min(evalTf(lo).a, evalTf(hi).a);
    int first, last;
    tfNodesIn(lo, hi, first, last);
    if (first >= last) return m;
    FloatRef tree = FloatRef(P.majorants.tfAlphaMinTree);
    int n = int(P.majorants.tfNodeCount);
    int leaves = n <= 1 ? 1 : 1 << (findMSB(n - 1) + 1);
    for (int l = first + leaves, r = last + leaves; l < r; l >>= 1, r >>= 1) {
        if ((l & 1) != 0) m = min(m, tree.v[l++]);
        if ((r & 1) != 0) m = min(m, tree.v[--r]);
    }
    return m;
}

#endif
