// amr::VolumeHistogram (amr/volume_histogram.h) against volumes counted by hand (cells of three
// levels, a finest level above 0, values at the range's ends and NaN), parts that sum to the
// whole (data-parallel MPI), the typical histogram of a series (shares averaged over outputs on the
// union range, by hand), and the layers preset it sizes (scene/tf_presets.h): a layer
// gets alpha 0.15 / (share x chord), capped at 1, so a slab of one layer's apex value across the
// data has optical depth 0.15 along a chord.
#include "amr/volume_histogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "model_fixtures.h"
#include "scene/tf_presets.h"
#include "scene/transfer_function.h"
#include "scene/volume.h"

using namespace amrvk;

namespace {

// A 4x4x4 box (finest cells of level 1, i.e. 2 voxels wide): the lower half in 32 level-1 cells
// of value 1, the upper half in 4 level-2 cells of value 3.
amr::Model twoLevelBox() {
    amr::Model m;
    m.source = "two-level box";
    m.fields.push_back({"v", {}});
    for (int z = 0; z < 4; z += 2)
        for (int y = 0; y < 8; y += 2)
            for (int x = 0; x < 8; x += 2) {
                m.cells.push_back({{x, y, z}, 1});
                m.fields[0].values.push_back(1.0f);
            }
    for (int y = 0; y < 8; y += 4)
        for (int x = 0; x < 8; x += 4) {
            m.cells.push_back({{x, y, 4}, 2});
            m.fields[0].values.push_back(3.0f);
        }
    return m;
}

}  // namespace

TEST(VolumeHistogram, VolumesInFinestCellsByHand) {
    const amr::Model m = twoLevelBox();
    const amr::VolumeHistogram h = amr::volumeHistogramOf(m.cells, m.fields[0].values, 1.0f, 3.0f, 1, 512.0);
    ASSERT_EQ(h.volume.size(), size_t(amr::VolumeHistogram::kBins));
    EXPECT_EQ(h.boundsVolume, 64.0);  // 8^3 voxels = 4^3 finest cells
    EXPECT_DOUBLE_EQ(h.depth(), 4.0);
    EXPECT_EQ(h.binOf(1.0f), 0);
    EXPECT_EQ(h.binOf(3.0f), amr::VolumeHistogram::kBins - 1);  // the top end is in the last bin
    EXPECT_EQ(h.binOf(std::numeric_limits<float>::quiet_NaN()), -1);
    EXPECT_EQ(h.volume.front(), 32.0);  // 32 cells of one finest cell each
    EXPECT_EQ(h.volume.back(), 32.0);   // 4 cells of 8 finest cells each
    double total = 0;
    for (double v : h.volume) total += v;
    EXPECT_EQ(total, 64.0);  // the cells fill the box
    // The volume makes the same (its minLevel and bounds), and NaN cells add nothing.
    amr::Model withNan = twoLevelBox();
    withNan.fields[0].values[0] = std::numeric_limits<float>::quiet_NaN();
    const amr::VolumeHistogram n = amr::volumeHistogramOf(withNan.cells, withNan.fields[0].values, 1.0f, 3.0f, 1, 512.0);
    EXPECT_EQ(n.volume.front(), 31.0);
    const auto v = scene::makeVolume(twoLevelBox());
    EXPECT_EQ(v->volumeHistogram, h);
}

TEST(VolumeHistogram, PartsSumToTheWhole) {
    const amr::Model m = test::makeRefinedModel(7, glm::ivec3(4), 3, 0.5);
    amr::Model withField = m;
    test::addRandomField(withField, "r", 11);
    const std::vector<float>& values = withField.fields.back().values;
    const amr::CellArray& cells = withField.cells;
    const float lo = *std::min_element(values.begin(), values.end());
    const float hi = *std::max_element(values.begin(), values.end());
    const auto whole = amr::volumeHistogramOf(cells, values, lo, hi, 0, 1e6);
    const size_t half = cells.size() / 2;
    amr::CellArray first, second;
    for (size_t i = 0; i < cells.size(); ++i) (i < half ? first : second).push_back(cells[i]);
    auto a = amr::volumeHistogramOf(first, std::span(values).first(half), lo, hi, 0, 1e6);
    const auto b = amr::volumeHistogramOf(second, std::span(values).subspan(half), lo, hi, 0, 1e6);
    for (size_t k = 0; k < a.volume.size(); ++k) a.volume[k] += b.volume[k];
    EXPECT_EQ(a, whole);  // volumes are integers in finest cells: the sums are exact
}

TEST(VolumeHistogram, PooledOverASeriesAveragesEachOutputsShares) {
    // Output A: half of its box at value 1, half at 3 (range [1, 3]); output B: the same cells at
    // 3 and 5 (range [3, 5]) in a box twice as large, so a quarter of it each. Each output counts
    // once: on [1, 5] the shares are (1/2 + 0)/2 at 1, (1/2 + 1/4)/2 at 3 and (0 + 1/4)/2 at 5, in
    // A's units.
    const amr::Model m = twoLevelBox();
    const amr::VolumeHistogram a = amr::volumeHistogramOf(m.cells, m.fields[0].values, 1.0f, 3.0f, 1, 512.0);
    std::vector<float> shifted = m.fields[0].values;
    for (float& v : shifted) v += 2.0f;
    amr::VolumeHistogram b = amr::volumeHistogramOf(m.cells, shifted, 3.0f, 5.0f, 1, 512.0);
    b.boundsVolume *= 2;  // B's cells fill half of its bounds
    const std::vector<amr::VolumeHistogram> parts = {amr::VolumeHistogram{}, a, b};
    const amr::VolumeHistogram pooled = amr::pooledVolumeHistograms(parts);
    EXPECT_EQ(pooled.lo, 1.0f);
    EXPECT_EQ(pooled.hi, 5.0f);
    EXPECT_EQ(pooled.boundsVolume, a.boundsVolume) << "the first output's units";
    auto shareIn = [&](double from, double to) {
        double v = 0;
        for (int k = 0; k < amr::VolumeHistogram::kBins; ++k)
            if (pooled.binCentre(k) >= from && pooled.binCentre(k) < to) v += pooled.volume[size_t(k)];
        return v / pooled.boundsVolume;
    };
    EXPECT_NEAR(shareIn(1, 2), 0.25, 1e-12);
    EXPECT_NEAR(shareIn(2, 4), 0.5 * 0.5 + 0.5 * 0.25, 1e-12) << "A's upper half and B's lower quarter";
    EXPECT_NEAR(shareIn(4, 5.01), 0.5 * 0.25, 1e-12);
    // The union's bins are twice as wide as A's and B's: every part's volume lands, none lost.
    EXPECT_NEAR(shareIn(0, 6), 0.5 + 0.25, 1e-12);
    // One output (the empty ones skipped) is itself; the same output twice, itself again.
    EXPECT_EQ(amr::pooledVolumeHistograms(std::span(parts).first(2)), a);
    const amr::VolumeHistogram twice = amr::pooledVolumeHistograms(std::vector<amr::VolumeHistogram>{a, a});
    for (size_t k = 0; k < a.volume.size(); ++k) EXPECT_NEAR(twice.volume[k], a.volume[k], 1e-12) << k;
    EXPECT_TRUE(amr::pooledVolumeHistograms(std::span(parts).first(1)).empty());
}

TEST(VolumeHistogram, LayersGiveEachLayerItsOpticalDepthAlongAChord) {
    // One value fills nearly all of a 16^3 box: layer 0's apex (range [0, 8], apexes at 0.5, 1.5, ...).
    amr::Model m;
    m.source = "slab";
    m.fields.push_back({"v", {}});
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                m.cells.push_back({{x, y, z}, 0});
                m.fields[0].values.push_back(0.5f);
            }
    m.fields[0].values[0] = 0.0f;   // the range's ends, one cell each
    m.fields[0].values[1] = 8.0f;
    m.fields[0].values[2] = 6.5f;   // one cell at layer 6's apex: it fills 1/4096 of space
    const auto v = scene::makeVolume(m);
    const scene::TransferFunction tf = scene::makePreset("layers", v->percentiles, v->volumeHistogram);
    const amr::VolumeHistogram& h = v->volumeHistogram;
    // The share under layer 0's triangle, from the bin that holds 0.5 (its centre a little off the apex).
    const int bin = h.binOf(0.5f);
    const double weight = 1.0 - std::abs(h.binCentre(bin) - 0.5) / 0.25;
    const double share = 4093.0 / 4096.0 * weight;
    const double alpha0 = 0.15 / (share * 16.0);
    EXPECT_NEAR(tf.evaluate(0.5f).a, alpha0, 1e-6 * alpha0);
    // Optical depth along an axis through the box (16 finest cells of that value): the layer's 0.15.
    EXPECT_NEAR(tf.evaluate(0.5f).a * 16.0 * weight, 0.15, 2e-3);
    // A layer whose values fill 1/4096 of space is capped at alpha 1; layers without values too.
    EXPECT_EQ(tf.evaluate(6.5f).a, 1.0f);
    EXPECT_EQ(tf.evaluate(3.5f).a, 1.0f);
    // Between layers, and at the ends, nothing.
    EXPECT_EQ(tf.evaluate(1.0f).a, 0.0f);
    EXPECT_EQ(tf.evaluate(0.0f).a, 0.0f);
    EXPECT_EQ(tf.evaluate(8.0f).a, 0.0f);
    // Range-fixed (no histogram): alpha halves layer by layer down from 0.5 at the top.
    const scene::TransferFunction fixed = scene::makePreset("layers", 0.0f, 8.0f);
    EXPECT_FLOAT_EQ(fixed.evaluate(7.5f).a, 0.5f);
    EXPECT_FLOAT_EQ(fixed.evaluate(0.5f).a, 0.5f / 128.0f);
}
