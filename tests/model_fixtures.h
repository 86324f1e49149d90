#pragma once
// Small hand-built AMR models for tests: random octree refinement of a block of coarse cells, so
// level boundaries with jumps of one, two and more levels occur, and simple fields on them.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <random>

#include "accel/abrs.h"
#include "accel/brick_build.h"
#include "accel/bricks.h"
#include "amr/model.h"
#include "amr/readers.h"
#include "amr/synthetic.h"
#include "test_data.h"

namespace amrvk::test {

// The Enzo cosmology sample, relative to dataDir() (tests skip without it: AMRVK_REQUIRE_DATA).
inline constexpr const char* kEnzoDataSet = "enzo_tiny_cosmology/DD0018/DD0018";
// Its Density field, the one every Enzo test uses.
inline amr::Model readEnzoDensity() {
    amr::ReadOptions o;
    o.fields = {"Density"};
    return amr::readModel(dataDir() / kEnzoDataSet, o);
}

// A synthetic cloud on exactly three levels: 7960 cells, 79 bricks, 4214 ABRs (cloud, 8000
// cells, seed 5, 5 allowed levels, 2^3-cell blocks).
inline amr::Model makeThreeLevelCloud() {
    amr::SyntheticParams p;
    p.kind = amr::SyntheticKind::Cloud;
    p.cells = 8000;
    p.seed = 5;
    p.levels = 5;
    p.blockCells = 2;
    return amr::makeSyntheticModel(p);
}

// Root cells of level `rootLevel` over rootDims, each refined recursively with probability
// `refineProbability` per cell down to level 0. Deterministic for a seed.
inline amr::Model makeRefinedModel(uint32_t seed, glm::ivec3 rootDims, int rootLevel,
                                   double refineProbability,
                                   glm::ivec3 originCells = glm::ivec3(0)) {
    amr::Model m;
    m.source = "fixture";
    m.format = "fixture";
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::function<void(glm::ivec3, int)> refine = [&](glm::ivec3 lower, int level) {
        if (level > 0 && u(rng) < refineProbability) {
            int half = 1 << (level - 1);
            for (int c = 0; c < 8; ++c)
                refine(lower + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1) * half, level - 1);
        } else {
            m.cells.push_back({lower, level});
        }
    };
    const int w = 1 << rootLevel;
    for (int z = 0; z < rootDims.z; ++z)
        for (int y = 0; y < rootDims.y; ++y)
            for (int x = 0; x < rootDims.x; ++x)
                refine((originCells + glm::ivec3(x, y, z)) * w, rootLevel);
    return m;
}

inline glm::dvec3 cellCentre(const amr::Cell& c) {
    return glm::dvec3(c.lower) + 0.5 * double(amr::cellWidth(c.level));
}

// Adds a field with value f(cell centre) for every cell.
inline void addField(amr::Model& m, const std::string& name,
                     const std::function<double(glm::dvec3)>& f) {
    amr::Field field{name, {}};
    field.values.reserve(m.cells.size());
    for (const amr::Cell& c : m.cells) field.values.push_back(static_cast<float>(f(cellCentre(c))));
    m.fields.push_back(std::move(field));
    m.availableFields.push_back(name);
}

inline void addRandomField(amr::Model& m, const std::string& name, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-3.0f, 7.0f);
    amr::Field field{name, {}};
    for (size_t i = 0; i < m.cells.size(); ++i) field.values.push_back(u(rng));
    m.fields.push_back(std::move(field));
    m.availableFields.push_back(name);
}

// Writes `m` as ExaBrick .cells/.scalars into the test's scratch directory, reads it back and
// expects identical cells and field values (names and order included).
inline void expectExaBrickRoundTrip(const amr::Model& m) {
    const std::filesystem::path base = scratchDir() / "roundtrip";
    amr::writeExaBrick(m, base);
    amr::ReadOptions back;
    back.format = "exabrick";
    for (const amr::Field& f : m.fields) back.fields.push_back(f.name);
    const amr::Model r = amr::readModel(base, back);
    ASSERT_EQ(r.cells.size(), m.cells.size());
    EXPECT_TRUE(r.cells == m.cells);
    ASSERT_EQ(r.fields.size(), m.fields.size());
    for (size_t f = 0; f < m.fields.size(); ++f) {
        EXPECT_EQ(r.fields[f].name, m.fields[f].name);
        EXPECT_EQ(r.fields[f].values, m.fields[f].values);
    }
    for (const auto& e : std::filesystem::directory_iterator(base.parent_path()))
        EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << "temporary file left: " << e.path();
}

// A validated model with its bricks, optionally its ABRs, and its first field in brick order: what
// the CPU structure tests build before the structure under test.
struct Built {
    amr::Model model;
    accel::BrickSet bricks;
    accel::AbrSet abrs;         // empty unless asked for
    std::vector<float> values;  // the first field, brick order
};

inline Built buildBricks(amr::Model m, bool withAbrs = false) {
    Built b{std::move(m), {}, {}, {}};
    amr::validate(b.model);
    b.bricks = accel::buildBricks(b.model);
    if (withAbrs) b.abrs = accel::buildAbrs(b.bricks);
    b.values = accel::brickOrderValues(b.bricks, b.model.fields[0]);
    return b;
}

}  // namespace amrvk::test
