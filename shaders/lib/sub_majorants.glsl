// Sub-majorants (scene/sub_majorants.h): a loose macrocell of a grid traversal split into n^3
// sub-boxes with majorants m = M q / 255 <= M of their own, built per TF. sampleTmaj
// (lib/tracking.glsl) steps with the macrocell's M and consults m before a lookup: a delta-tracking
// collision whose uniform u has u >= q / 255 is null whatever the field (sigma <= m <= u M), so it
// is decided without a lookup, exactly as the lookup would have; ratio tracking thins its
// collisions to u < q / 255 and weights them with m. CPU twin of the bytes: scene::SubMajorantGrid::q.
#ifndef AMRVK_SUB_MAJORANTS_GLSL
#define AMRVK_SUB_MAJORANTS_GLSL

const uint kSubNotRefined = 0xffffffffu;

// A macrocell's refinement, read once per segment.
struct SubBoxes {
    uint word;    // kSubNotRefined, or (byte offset / 8) << 2 | log2 n - 1
    vec3 lower;   // the macrocell's lower corner (local voxel space)
    vec3 scale;   // sub-boxes per voxel unit per axis: n / macrocell size
};

// Macrocell `cell`'s sub-boxes (none where sub-majorants are off or it is not refined).
SubBoxes subBoxesOf(uint cell) {
    SubBoxes b;
    b.word = P.majorants.subMajorantsOn != 0u ? UintRef(P.majorants.subRefinement).v[cell] : kSubNotRefined;
    b.lower = vec3(0.0);
    b.scale = vec3(0.0);
    if (b.word != kSubNotRefined) {
        b.lower = P.scene.gridOrigin + vec3(ddaCellOfIndex(cell)) * P.scene.gridCellSize;
        b.scale = float(2u << (b.word & 3u)) / P.scene.gridCellSize;
    }
    return b;
}

// q / 255 of the sub-box holding local point p of a refined macrocell (a point rounded just
// outside the macrocell takes the nearest sub-box, whose range covers the same margin as the
// macrocell's): the share of the macrocell's majorant that bounds the extinction at p.
float subMajorantShare(SubBoxes b, vec3 p) {
    int n = 2 << (b.word & 3u);
    ivec3 s = clamp(ivec3(floor((p - b.lower) * b.scale)), ivec3(0), ivec3(n - 1));
    uint byte = (b.word >> 2) * 8u + uint(s.x + n * (s.y + n * s.z));
    uint q = (UintRef(P.majorants.subMajorants).v[byte >> 2] >> ((byte & 3u) * 8u)) & 255u;
    return float(q) * (1.0 / 255.0);
}

#endif
