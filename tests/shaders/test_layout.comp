#version 460
// Layout conformance: reads every field of every shared struct through its GLSL declaration, in
// declaration order, and writes the raw 32-bit words to `out`. The C++ side fills the structs so
// that word i holds the value i and checks that each field's words are the ones at its C++ offset
// (tests/gpu/layout_test.cpp). Pads are read too, so the words must tile each struct exactly.
#include "lib/common.glsl"
#include "shared/test_push.h"
#include "shared/data_parallel_gpu.h"
layout(push_constant, scalar) uniform Push { TestLayoutPush tp; };
layout(local_size_x = 1) in;

layout(buffer_reference, scalar) readonly buffer StructsRef {
    BrickGpu brick;
    BvhNodeGpu node;
    AbrGpu abr;
    AabbGpu aabb;
    ValueRangeGpu range;
    AccumPixelGpu accum;
    PathStateGpu dpPath;
    DataParallelHitGpu dpHit;
    DataParallelPush dpPush;
};

uint k = 0u;
void u(uint v) { UintRW(tp.results).v[k++] = v; }
void i(int v) { u(uint(v)); }
void f(float v) { u(floatBitsToUint(v)); }
void u64(uint64_t v) { u(uint(v)); u(uint(v >> 32)); }
void f3(vec3 v) { f(v.x); f(v.y); f(v.z); }
void i3(ivec3 v) { i(v.x); i(v.y); i(v.z); }
void f4(vec4 v) { f(v.x); f(v.y); f(v.z); f(v.w); }

void main() {
    gParams = ParamsRef(tp.params);
    // RenderParams.view
    f3(P.view.eye); u(P.view.width); f3(P.view.dir00); u(P.view.height);
    f3(P.view.du); u(P.view.seed); f3(P.view.dv); u(P.view.pad);
    // RenderParams.shading
    f3(P.shading.ambient); f(P.shading.g); f3(P.shading.background); f(P.shading.densityScale);
    u(P.shading.lightCount); u(P.shading.maxTrackingSteps); f(P.shading.dvrStep); u(P.shading.dvrShading);
    f3(P.shading.dvrLightDir); f(P.shading.dvrAmbient); f(P.shading.dvrOpacityStop);
    f(P.shading.pad0); f(P.shading.pad1); f(P.shading.pad2);
    for (uint l = 0u; l < kMaxLights; ++l) {
        f3(P.shading.lights[l].posOrDir); u(P.shading.lights[l].type);
        f3(P.shading.lights[l].radiance); f(P.shading.lights[l].pad);
    }
    // RenderParams.scene
    f3(P.scene.boundsHi); f(P.scene.invFinestCellWidth); i3(P.scene.gridDims); u(P.scene.gridBlockShift);
    f3(P.scene.gridOrigin); u(P.scene.gridBvhQueryAfter); f3(P.scene.gridCellSize); f(P.scene.pad2);
    i3(P.scene.denseDims); i(P.scene.denseLevel); f3(P.scene.denseOrigin); f(P.scene.denseSpacing);
    u64(P.scene.bricks); u64(P.scene.brickValues); u64(P.scene.samplerNodes); u64(P.scene.samplerPrims);
    u64(P.scene.samplerAccel); u64(P.scene.abrs); u64(P.scene.abrBrickList); u64(P.scene.gridRanges);
    u64(P.scene.denseValues); u64(P.scene.gridBrickLists);
    // RenderParams.majorants
    u64(P.majorants.tfPositions); u64(P.majorants.tfColors); u(P.majorants.tfNodeCount);
    u(P.majorants.domainCount); u(P.majorants.domainAnyActive); u(P.majorants.gridBlocks);
    u64(P.majorants.gridMajorants); u64(P.majorants.domainBoxes); u64(P.majorants.domainRanges);
    u64(P.majorants.domainMajorants); u64(P.majorants.domainNodes); u64(P.majorants.domainPrims);
    u64(P.majorants.domainAccel); u64(P.majorants.tfAlphaTree);
    u64(P.majorants.subRefinement); u64(P.majorants.subMajorants);
    u(P.majorants.subMajorantsOn); u(P.majorants.subMajorantCheck);
    u64(P.majorants.gridMinorants); u64(P.majorants.tfAlphaMinTree);
    // RenderParams tail
    u64(P.accum); u64(P.counters); u64(P.pathStats);
    f3(P.cut.cropLo); u(P.cut.flags); f3(P.cut.cropHi); u(P.cut.planeCount);
    for (uint i = 0u; i < kMaxClipPlanes; ++i) f4(P.cut.planes[i]);
    // The structures read through buffer references.
    StructsRef s = StructsRef(tp.structs);
    i3(s.brick.lower); i(s.brick.level); i3(s.brick.size); u(s.brick.begin);
    f3(s.node.lo); u(s.node.first); f3(s.node.hi); u(s.node.count);
    f3(s.abr.lo); u(s.abr.brickBegin); f3(s.abr.hi); u(s.abr.brickCount);
    f3(s.aabb.lo); f3(s.aabb.hi);
    f(s.range.lo); f(s.range.hi);
    f4(s.accum.sumHi); f4(s.accum.sumLo); f4(s.accum.sumSqHi); f4(s.accum.sumSqLo);
    f3(s.dpPath.o); u(s.dpPath.rng); f3(s.dpPath.d); u(s.dpPath.bounce);
    f3(s.dpPath.throughput); u(s.dpPath.flags); f3(s.dpPath.radiance); u(s.dpPath.pixel);
    f3(s.dpPath.pending); f(s.dpPath.shadowDist); f3(s.dpPath.shadowDir); u(s.dpPath.pad);
    f(s.dpHit.t); f3(s.dpHit.color);
    u64(s.dpPush.params); u64(s.dpPush.paths); u64(s.dpPush.hits); u64(s.dpPush.shadow); u64(s.dpPush.counters);
    f3(s.dpPush.ownedLo); u(s.dpPush.stage); f3(s.dpPush.ownedHi); u(s.dpPush.count);
    u(s.dpPush.sampleIndex); u(s.dpPush.rankSeed); u(s.dpPush.pad0); u(s.dpPush.pad1);
}
