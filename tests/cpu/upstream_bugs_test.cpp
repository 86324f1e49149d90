// Regression tests named after the upstream ExaBrick bugs of exabrick-reference.md section 8 that
// live in loaders and transfer functions. The others are next to the code they concern:
//   UpstreamBug_BrickNeighbourSplatting, UpstreamBug_KdTreeModelBoundsBeforeInit (cpu/support_range,
//   cpu/kdtree), UpstreamBug_RelDomainAppliedTwice (cpu/transfer_function),
//   UpstreamBug_OpacityScaleMismatch (gpu/render), UpstreamBug_TfCulledSamplingBvh (gpu/traversal).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "amr/readers.h"
#include "scene/transfer_function.h"
#include "test_data.h"

using namespace amrvk;

namespace {
std::string floatBytes(const std::vector<float>& v) {
    std::string s(v.size() * sizeof(float), '\0');
    std::memcpy(s.data(), v.data(), s.size());
    return s;
}
}  // namespace

// owlExaBrick sizes the scalar array by the byte count: 4x too long, zero-padded, so the value
// range always includes 0. Here the field has one value per cell and its range is the data's.
TEST(UpstreamBug_ScalarLoaderSize, OneValuePerCellAndNoSpuriousZero) {
    const auto dir = test::scratchDir();
    amr::Model m;
    m.source = "test";
    for (int i = 0; i < 6; ++i) m.cells.push_back({glm::ivec3(i, 0, 0), 0});
    m.fields.push_back({"scalars", {2.0f, 2.5f, 3.0f, 2.25f, 2.75f, 2.1f}});
    m.availableFields = {"scalars"};
    amr::writeExaBrick(m, dir / "s", true);
    amr::Model back = amr::readModel(dir / "s.cells", {});
    ASSERT_EQ(back.fields.size(), 1u);
    EXPECT_EQ(back.fields[0].values.size(), 6u);
    const amr::FieldStats st = amr::computeFieldStats(back, back.fields[0]);
    EXPECT_EQ(st.minValue, 2.0f);
    EXPECT_EQ(st.maxValue, 3.0f);
    // A scalars file sized like upstream's buffer (4x the floats) is an error naming both counts.
    std::vector<float> padded(24, 0.0f);
    std::copy(m.fields[0].values.begin(), m.fields[0].values.end(), padded.begin());
    test::writeAll(dir / "s.scalars", floatBytes(padded));
    test::expectError([&] { amr::readModel(dir / "s.cells", {}); }, {"s.scalars", "24 values", "6 cells"});
}

// Upstream computes the majorant over texels int(lo * (N-1)) .. int(hi * (N-1)) + 1 while the
// shader's filtered texture lookup of value s blends the texels around s * N - 0.5, so a range
// starting just above a texel boundary misses the lower neighbour (lo = 0.080, N = 128: the
// lookup needs texel 9, the range starts at 10). Our pair is consistent: maxAlpha is exact for
// the piecewise-linear function evaluate() computes, so it bounds every lookup in the range.
TEST(UpstreamBug_HalfTexelMajorantRange, MajorantBoundsEveryLookupInTheRange) {
    const int n = 128;
    std::vector<float> alpha(n, 0.0f);
    alpha[9] = 1.0f;
    // The upstream pair on this table, to show the test guards against a real failure.
    auto upstreamLookup = [&](float v) {
        const float x = std::clamp(v * float(n) - 0.5f, 0.0f, float(n - 1));
        const int i0 = int(std::floor(x)), i1 = std::min(n - 1, i0 + 1);
        return alpha[size_t(i0)] + (alpha[size_t(i1)] - alpha[size_t(i0)]) * (x - float(i0));
    };
    auto upstreamMajorant = [&](float lo, float hi) {
        float m = 0.0f;
        for (int i = std::clamp(int(lo * float(n - 1)), 0, n - 1); i <= std::clamp(int(hi * float(n - 1)) + 1, 0, n - 1); ++i)
            m = std::max(m, alpha[size_t(i)]);
        return m;
    };
    EXPECT_GT(upstreamLookup(0.080f), upstreamMajorant(0.080f, 0.081f)) << "the upstream pair is not conservative";
    // Ours, on the same table as nodes, over many ranges including that one.
    std::vector<float> pos(n);
    std::vector<glm::vec4> col(n);
    for (int i = 0; i < n; ++i) {
        pos[size_t(i)] = float(i) / float(n - 1);
        col[size_t(i)] = glm::vec4(1.0f, 1.0f, 1.0f, alpha[size_t(i)]);
    }
    const scene::TransferFunction tf(pos, col, "texel-9");
    for (int r = 0; r < 400; ++r) {
        const float lo = 0.05f + 0.0001f * float(r), hi = lo + 0.001f * float(1 + r % 7);
        const float m = tf.maxAlpha(lo, hi);
        for (int k = 0; k <= 200; ++k) {
            const float v = lo + (hi - lo) * float(k) / 200.0f;
            ASSERT_LE(tf.evaluate(v).a, m) << "value " << v << " in [" << lo << ", " << hi << "]";
        }
    }
}
