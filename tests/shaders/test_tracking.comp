#version 460
// One tracking estimate per invocation along the ray (origin, direction) over [0, tMax], eight
// floats per invocation: 1 if delta tracking escapes (else 0), the ratio-tracking transmittance,
// delta tracking's collision distance (tMax when it escapes), the calls stopped at the step cap
// (of all three estimators), then the two tracking calls' lookups, collisions decided by
// sub-majorants, majorant violations (of all three), and the unbiased ray-marching transmittance
// (with tp.withUbrm, else 0).
#include "lib/common.glsl"
#include "lib/rng.glsl"
#include "lib/tf.glsl"
#include "lib/amr_sample.glsl"
#include "lib/majorant_dda.glsl"
#include "lib/domain_traversal.glsl"
#include "lib/traversal.glsl"
#include "lib/sub_majorants.glsl"
#include "lib/tracking.glsl"
#include "lib/unbiased_march.glsl"
#include "shared/test_push.h"
layout(push_constant, scalar) uniform Push { TestTrackingPush tp; };
layout(local_size_x = 64) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= tp.count) return;
    gParams = ParamsRef(tp.params);
    uint rng = seedRng(i, 0u, 12345u);
    Counters c = newCounters();
    float tHit;
    vec4 tf;
    bool hit = deltaTrack(tp.origin.xyz, tp.dir.xyz, tp.dir.w, StructureConfig(tp.samplerKind, tp.traversal, kBackendSw), rng, c, tHit, tf);
    float tr = ratioTrack(tp.origin.xyz, tp.dir.xyz, tp.dir.w, StructureConfig(tp.samplerKind, tp.traversal, kBackendSw), rng, c);
    Counters u = newCounters();
    float ubrm = 0.0;
    if (tp.withUbrm != 0u)
        ubrm = ubrmTransmittance(tp.origin.xyz, tp.dir.xyz, tp.dir.w, StructureConfig(tp.samplerKind, tp.traversal, kBackendSw), rng, u);
    FloatRW o = FloatRW(tp.results);
    o.v[8u * i] = hit ? 0.0 : 1.0;
    o.v[8u * i + 1u] = tr;
    o.v[8u * i + 2u] = tHit;
    o.v[8u * i + 3u] = float(c.capped + u.capped);
    o.v[8u * i + 4u] = float(c.lookups);
    o.v[8u * i + 5u] = float(c.thinned);
    o.v[8u * i + 6u] = float(c.violations + u.violations);
    o.v[8u * i + 7u] = ubrm;
}
