// GPU layout conformance: the C++ and GLSL views of every shared struct agree on every field.
// The C++ side fills each struct so that 32-bit word i holds the value i; the kernel
// (tests/shaders/test_layout.comp) reads every field through the GLSL declaration in declaration
// order and writes its words back. Each field must come back as the words at its C++ offset, and
// the fields listed here must tile each struct exactly (so a field missing from the test, or a
// hole in the layout, fails too).
#include <cstring>
#include <vector>

#include "gpu/buffer.h"
#include "gpu/compute_pipeline.h"
#include "gpu_fixture.h"
#include "shared/amr_gpu.h"
#include "shared/data_parallel_gpu.h"
#include "shared/render_params.h"
#include "shared/test_push.h"

using namespace amrvk;
using namespace amrvk::shared;

namespace {

struct Field {
    const char* name;
    size_t offset;  // bytes from the start of the struct
    size_t words;   // 32-bit words
};

#define AMRVK_FIELD(base, Struct, member, words) \
    Field { #Struct "." #member, (base) + offsetof(Struct, member), (words) }

// Every field of RenderParams, in declaration order (the kernel reads them in the same order).
std::vector<Field> renderParamsFields() {
    const size_t v = offsetof(RenderParams, view), s = offsetof(RenderParams, shading),
                 c = offsetof(RenderParams, scene), m = offsetof(RenderParams, majorants);
    std::vector<Field> f = {
        AMRVK_FIELD(v, ViewGpu, eye, 3),          AMRVK_FIELD(v, ViewGpu, width, 1),
        AMRVK_FIELD(v, ViewGpu, dir00, 3),        AMRVK_FIELD(v, ViewGpu, height, 1),
        AMRVK_FIELD(v, ViewGpu, du, 3),           AMRVK_FIELD(v, ViewGpu, seed, 1),
        AMRVK_FIELD(v, ViewGpu, dv, 3),           AMRVK_FIELD(v, ViewGpu, pad, 1),
        AMRVK_FIELD(s, ShadingGpu, ambient, 3),   AMRVK_FIELD(s, ShadingGpu, g, 1),
        AMRVK_FIELD(s, ShadingGpu, background, 3), AMRVK_FIELD(s, ShadingGpu, densityScale, 1),
        AMRVK_FIELD(s, ShadingGpu, lightCount, 1), AMRVK_FIELD(s, ShadingGpu, maxTrackingSteps, 1),
        AMRVK_FIELD(s, ShadingGpu, dvrStep, 1),   AMRVK_FIELD(s, ShadingGpu, dvrShading, 1),
        AMRVK_FIELD(s, ShadingGpu, dvrLightDir, 3), AMRVK_FIELD(s, ShadingGpu, dvrAmbient, 1),
        AMRVK_FIELD(s, ShadingGpu, dvrOpacityStop, 1), AMRVK_FIELD(s, ShadingGpu, pad0, 1),
        AMRVK_FIELD(s, ShadingGpu, pad1, 1),      AMRVK_FIELD(s, ShadingGpu, pad2, 1),
    };
    for (size_t l = 0; l < kMaxLights; ++l) {
        const size_t base = s + offsetof(ShadingGpu, lights) + l * sizeof(LightGpu);
        f.insert(f.end(), {AMRVK_FIELD(base, LightGpu, posOrDir, 3), AMRVK_FIELD(base, LightGpu, type, 1),
                           AMRVK_FIELD(base, LightGpu, radiance, 3), AMRVK_FIELD(base, LightGpu, pad, 1)});
    }
    f.insert(f.end(), {
        AMRVK_FIELD(c, SceneGpu, boundsHi, 3),     AMRVK_FIELD(c, SceneGpu, invFinestCellWidth, 1),
        AMRVK_FIELD(c, SceneGpu, gridDims, 3),     AMRVK_FIELD(c, SceneGpu, gridBlockShift, 1),
        AMRVK_FIELD(c, SceneGpu, gridOrigin, 3),   AMRVK_FIELD(c, SceneGpu, gridBvhQueryAfter, 1),
        AMRVK_FIELD(c, SceneGpu, gridCellSize, 3), AMRVK_FIELD(c, SceneGpu, pad2, 1),
        AMRVK_FIELD(c, SceneGpu, denseDims, 3),    AMRVK_FIELD(c, SceneGpu, denseLevel, 1),
        AMRVK_FIELD(c, SceneGpu, denseOrigin, 3),  AMRVK_FIELD(c, SceneGpu, denseSpacing, 1),
        AMRVK_FIELD(c, SceneGpu, bricks, 2),       AMRVK_FIELD(c, SceneGpu, brickValues, 2),
        AMRVK_FIELD(c, SceneGpu, samplerNodes, 2), AMRVK_FIELD(c, SceneGpu, samplerPrims, 2),
        AMRVK_FIELD(c, SceneGpu, samplerAccel, 2), AMRVK_FIELD(c, SceneGpu, abrs, 2),
        AMRVK_FIELD(c, SceneGpu, abrBrickList, 2), AMRVK_FIELD(c, SceneGpu, gridRanges, 2),
        AMRVK_FIELD(c, SceneGpu, denseValues, 2),  AMRVK_FIELD(c, SceneGpu, gridBrickLists, 2),
        AMRVK_FIELD(m, MajorantsGpu, tfPositions, 2),   AMRVK_FIELD(m, MajorantsGpu, tfColors, 2),
        AMRVK_FIELD(m, MajorantsGpu, tfNodeCount, 1),   AMRVK_FIELD(m, MajorantsGpu, domainCount, 1),
        AMRVK_FIELD(m, MajorantsGpu, domainAnyActive, 1), AMRVK_FIELD(m, MajorantsGpu, gridBlocks, 1),
        AMRVK_FIELD(m, MajorantsGpu, gridMajorants, 2), AMRVK_FIELD(m, MajorantsGpu, domainBoxes, 2),
        AMRVK_FIELD(m, MajorantsGpu, domainRanges, 2),  AMRVK_FIELD(m, MajorantsGpu, domainMajorants, 2),
        AMRVK_FIELD(m, MajorantsGpu, domainNodes, 2),   AMRVK_FIELD(m, MajorantsGpu, domainPrims, 2),
        AMRVK_FIELD(m, MajorantsGpu, domainAccel, 2),   AMRVK_FIELD(m, MajorantsGpu, tfAlphaTree, 2),
        AMRVK_FIELD(m, MajorantsGpu, subRefinement, 2), AMRVK_FIELD(m, MajorantsGpu, subMajorants, 2),
        AMRVK_FIELD(m, MajorantsGpu, subMajorantsOn, 1), AMRVK_FIELD(m, MajorantsGpu, subMajorantCheck, 1),
        AMRVK_FIELD(m, MajorantsGpu, gridMinorants, 2), AMRVK_FIELD(m, MajorantsGpu, tfAlphaMinTree, 2),
        AMRVK_FIELD(0, RenderParams, accum, 2),         AMRVK_FIELD(0, RenderParams, counters, 2),
        AMRVK_FIELD(0, RenderParams, pathStats, 2),
    });
    const size_t x = offsetof(RenderParams, cut);
    f.insert(f.end(), {AMRVK_FIELD(x, CutAwayGpu, cropLo, 3), AMRVK_FIELD(x, CutAwayGpu, flags, 1),
                       AMRVK_FIELD(x, CutAwayGpu, cropHi, 3), AMRVK_FIELD(x, CutAwayGpu, planeCount, 1)});
    for (size_t i = 0; i < kMaxClipPlanes; ++i)
        f.push_back({"CutAwayGpu.planes[i]", x + offsetof(CutAwayGpu, planes) + i * sizeof(glm::vec4), 4});
    return f;
}

// The structures the kernel reads through a buffer reference, packed one after another.
struct Structs {
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
static_assert(sizeof(Structs) == 32 + 32 + 32 + 24 + 8 + 64 + 96 + 16 + 88);

std::vector<Field> structFields() {
    const size_t b = offsetof(Structs, brick), n = offsetof(Structs, node), a = offsetof(Structs, abr),
                 x = offsetof(Structs, aabb), r = offsetof(Structs, range), p = offsetof(Structs, accum),
                 dp = offsetof(Structs, dpPath), dh = offsetof(Structs, dpHit), du = offsetof(Structs, dpPush);
    return {
        AMRVK_FIELD(b, BrickGpu, lower, 3),   AMRVK_FIELD(b, BrickGpu, level, 1),
        AMRVK_FIELD(b, BrickGpu, size, 3),    AMRVK_FIELD(b, BrickGpu, begin, 1),
        AMRVK_FIELD(n, BvhNodeGpu, lo, 3),    AMRVK_FIELD(n, BvhNodeGpu, first, 1),
        AMRVK_FIELD(n, BvhNodeGpu, hi, 3),    AMRVK_FIELD(n, BvhNodeGpu, count, 1),
        AMRVK_FIELD(a, AbrGpu, lo, 3),        AMRVK_FIELD(a, AbrGpu, brickBegin, 1),
        AMRVK_FIELD(a, AbrGpu, hi, 3),        AMRVK_FIELD(a, AbrGpu, brickCount, 1),
        AMRVK_FIELD(x, AabbGpu, lo, 3),       AMRVK_FIELD(x, AabbGpu, hi, 3),
        AMRVK_FIELD(r, ValueRangeGpu, lo, 1), AMRVK_FIELD(r, ValueRangeGpu, hi, 1),
        AMRVK_FIELD(p, AccumPixelGpu, sumHi, 4), AMRVK_FIELD(p, AccumPixelGpu, sumLo, 4),
        AMRVK_FIELD(p, AccumPixelGpu, sumSqHi, 4), AMRVK_FIELD(p, AccumPixelGpu, sumSqLo, 4),
        AMRVK_FIELD(dp, PathStateGpu, o, 3), AMRVK_FIELD(dp, PathStateGpu, rng, 1),
        AMRVK_FIELD(dp, PathStateGpu, d, 3), AMRVK_FIELD(dp, PathStateGpu, bounce, 1),
        AMRVK_FIELD(dp, PathStateGpu, throughput, 3), AMRVK_FIELD(dp, PathStateGpu, flags, 1),
        AMRVK_FIELD(dp, PathStateGpu, radiance, 3), AMRVK_FIELD(dp, PathStateGpu, pixel, 1),
        AMRVK_FIELD(dp, PathStateGpu, pending, 3), AMRVK_FIELD(dp, PathStateGpu, shadowDist, 1),
        AMRVK_FIELD(dp, PathStateGpu, shadowDir, 3), AMRVK_FIELD(dp, PathStateGpu, pad, 1),
        AMRVK_FIELD(dh, DataParallelHitGpu, t, 1), AMRVK_FIELD(dh, DataParallelHitGpu, color, 3),
        AMRVK_FIELD(du, DataParallelPush, params, 2), AMRVK_FIELD(du, DataParallelPush, paths, 2),
        AMRVK_FIELD(du, DataParallelPush, hits, 2), AMRVK_FIELD(du, DataParallelPush, shadow, 2),
        AMRVK_FIELD(du, DataParallelPush, counters, 2), AMRVK_FIELD(du, DataParallelPush, ownedLo, 3),
        AMRVK_FIELD(du, DataParallelPush, stage, 1), AMRVK_FIELD(du, DataParallelPush, ownedHi, 3),
        AMRVK_FIELD(du, DataParallelPush, count, 1), AMRVK_FIELD(du, DataParallelPush, sampleIndex, 1),
        AMRVK_FIELD(du, DataParallelPush, rankSeed, 1), AMRVK_FIELD(du, DataParallelPush, pad0, 1),
        AMRVK_FIELD(du, DataParallelPush, pad1, 1),
    };
}

// The words each field should read back, and a check that the fields tile [0, bytes) exactly.
std::vector<uint32_t> expectedWords(const std::vector<Field>& fields, size_t bytes, const char* what) {
    std::vector<uint32_t> out;
    size_t next = 0;
    for (const Field& f : fields) {
        EXPECT_EQ(f.offset, next) << what << ": " << f.name << " does not follow the previous field";
        for (size_t w = 0; w < f.words; ++w) out.push_back(uint32_t(f.offset / 4 + w));
        next = f.offset + 4 * f.words;
    }
    EXPECT_EQ(next, bytes) << what << ": the fields do not cover the whole struct";
    return out;
}

template <typename T>
T filledWithWordIndices() {
    static_assert(sizeof(T) % 4 == 0);
    T value;
    std::vector<uint32_t> words(sizeof(T) / 4);
    for (size_t i = 0; i < words.size(); ++i) words[i] = uint32_t(i);
    std::memcpy(&value, words.data(), sizeof(T));
    return value;
}

}  // namespace

class Layout : public test::GpuTest {};

TEST_F(Layout, EverySharedFieldHasTheSameOffsetInCppAndGlsl) {
    const std::vector<Field> paramFields = renderParamsFields(), objectFields = structFields();
    std::vector<uint32_t> expect = expectedWords(paramFields, sizeof(RenderParams), "RenderParams");
    const size_t paramWords = expect.size();
    const std::vector<uint32_t> objects = expectedWords(objectFields, sizeof(Structs), "BrickGpu..AccumPixelGpu");
    expect.insert(expect.end(), objects.begin(), objects.end());

    auto& c = ctx();
    const RenderParams params = filledWithWordIndices<RenderParams>();
    const Structs structs = filledWithWordIndices<Structs>();
    gpu::Buffer paramsBuf(c, sizeof params, gpu::MemoryKind::Device, "params");
    paramsBuf.upload(&params, sizeof params);
    gpu::Buffer structsBuf(c, sizeof structs, gpu::MemoryKind::Device, "structs");
    structsBuf.upload(&structs, sizeof structs);
    gpu::Buffer out(c, expect.size() * 4, gpu::MemoryKind::HostRead, "out");
    gpu::ComputePipeline pipe(c, gpu::loadShader("test_layout"), "test_layout", sizeof(TestLayoutPush));
    TestLayoutPush push{paramsBuf.address(), out.address(), structsBuf.address(), 0};
    c.submitAndWait([&](VkCommandBuffer cmd) { pipe.dispatch(cmd, &push, 1); });
    const std::vector<uint32_t> got = out.download<uint32_t>();
    ASSERT_EQ(got.size(), expect.size());
    size_t word = 0;
    for (const std::vector<Field>* fields : {&paramFields, &objectFields})
        for (const Field& f : *fields)
            for (size_t w = 0; w < f.words; ++w, ++word)
                EXPECT_EQ(got[word], expect[word]) << f.name << " word " << w;
    EXPECT_EQ(word, expect.size());
    EXPECT_EQ(paramWords, sizeof(RenderParams) / 4);
}
