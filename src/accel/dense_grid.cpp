#include "accel/dense_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "accel/brick_sampler.h"
#include "accel/majorant_bounds.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stats.h"

namespace amrvk::accel {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Samples per axis (64-bit: may exceed int32 before the check).
glm::i64vec3 denseDims64(const amr::Box3l& bounds, int32_t level) {
    const int64_t w = amr::cellWidth(level);
    glm::i64vec3 size = bounds.size();
    glm::i64vec3 d;
    for (int a = 0; a < 3; ++a) d[a] = (size[a] + w - 1) / w;
    return d;
}

// Product of the dims times sizeof(float), saturating at UINT64_MAX.
uint64_t bytesOf(glm::i64vec3 d) {
    uint64_t bytes = sizeof(float);
    for (int a = 0; a < 3; ++a) {
        const uint64_t n = uint64_t(d[a]);
        if (n != 0 && bytes > std::numeric_limits<uint64_t>::max() / n) return std::numeric_limits<uint64_t>::max();
        bytes *= n;
    }
    return bytes;
}

std::string formatDims(glm::i64vec3 d) {
    if (d.x == d.y && d.y == d.z) return strCat(d.x, "^3");
    return strCat(d.x, "x", d.y, "x", d.z);
}

}  // namespace

uint64_t denseGridBytes(const amr::Box3l& bounds, int32_t level) {
    if (bounds.empty() || level < 0 || level > amr::kMaxLevel) return 0;
    return bytesOf(denseDims64(bounds, level));
}

DenseGrid buildDenseGrid(const amr::Model& model, const BrickSet& bricks, std::span<const float> brickValues,
                         const amr::Box3l& bounds, int32_t level, uint64_t maxBytes) {
    Timer timer;
    AMRVK_CHECK(!bounds.empty(), "dense sampler: empty data bounds");
    AMRVK_CHECK(level >= 0 && level <= amr::kMaxLevel, "dense sampler: level ", level, " outside [0, ",
                amr::kMaxLevel, "]");
    const glm::i64vec3 d64 = denseDims64(bounds, level);
    const uint64_t bytes = bytesOf(d64);
    const int64_t maxDim = std::max({d64.x, d64.y, d64.z});
    const bool overflow = bytes == std::numeric_limits<uint64_t>::max();
    AMRVK_CHECK(!overflow && maxDim <= int64_t(INT32_MAX) && bytes <= maxBytes, "dense sampler: ",
                formatDims(d64), " samples need ", overflow ? std::string("more than 16 EiB") : formatBytes(bytes),
                maxDim > int64_t(INT32_MAX) ? " (over 2^31-1 per axis)" : "", ", more than the limit ",
                formatBytes(maxBytes), " (--dense-max-mib)");

    DenseGrid g{.origin = bounds.lower, .level = level, .dims = glm::ivec3(d64)};
    const size_t total = size_t(bytes / sizeof(float));
    // A long build says what it is about to take, then shows its progress over z slices.
    std::optional<ProgressStage> progress;
    if (total > (size_t(1) << 22))
        progress.emplace(strCat("dense grid of ", formatDims(d64), " samples: ", formatBytes(bytes), " of memory"));

    // Inside mask: rasterise the closed leaf-cell boxes; a sample is inside when its centre
    // origin + (i + 0.5) W lies in [lo, hi], i.e. 2(lo - o) - W <= 2 i W <= 2(hi - o) - W.
    // Inside samples hold 0 until evaluated, the others NaN.
    AMRVK_CHECK(!model.cells.empty(), "dense sampler: the cells were released after the brick build (internal)");
    g.values.assign(total, kNaN);
    const int64_t w = amr::cellWidth(level);
    for (const amr::Cell& c : model.cells) {
        const int64_t cw = amr::cellWidth(c.level);
        glm::ivec3 lo, hi;
        bool any = true;
        for (int a = 0; a < 3; ++a) {
            const int64_t l = int64_t(c.lower[a]) - g.origin[a];
            const int64_t first = ceilDiv(2 * l - w, 2 * w);
            const int64_t last = floorDiv(2 * (l + cw) - w, 2 * w);
            const int64_t f = std::max<int64_t>(first, 0), e = std::min<int64_t>(last, g.dims[a] - 1);
            if (f > e) any = false;
            lo[a] = int(f);
            hi[a] = int(e);
        }
        if (!any) continue;
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y) {
                float* row = g.values.data() + g.index({0, y, z});
                std::fill(row + lo.x, row + hi.x + 1, 0.0f);
            }
    }

    // Values: the brick reconstruction at each inside centre, z slices in parallel, in about a
    // hundred batches so that the bar moves.
    ExtBrickSampler sampler(bricks, brickValues);
    ProgressBar bar("dense grid", "slices");
    const size_t slices = size_t(g.dims.z), batch = std::max<size_t>(1, slices / 100);
    for (size_t z0 = 0; z0 < slices; z0 += batch) {
        const size_t z1 = std::min(slices, z0 + batch);
        parallelFor(z0, z1, [&](size_t zi) {
            const int z = int(zi);
            for (int y = 0; y < g.dims.y; ++y)
                for (int x = 0; x < g.dims.x; ++x) {
                    float& v = g.values[g.index({x, y, z})];
                    if (std::isnan(v)) continue;
                    const amr::Sample s = sampler.sample(g.centre({x, y, z}));
                    v = s.valid() ? static_cast<float>(s.value) : kNaN;
                }
        });
        if (progress) bar.update(z1, slices);
    }
    bar.finish();
    g.buildSeconds = timer.seconds();
    return g;
}

void assignDenseRanges(const DenseGrid& dense, RangeGrid& grid) {
    const glm::ivec3 M = grid.dims, N = dense.dims;
    grid.ranges.assign(size_t(M.x) * size_t(M.y) * size_t(M.z), ValueRange{});
    if (dense.values.empty() || M.x <= 0 || M.y <= 0 || M.z <= 0) return;
    const double W = dense.width();

    // Per axis and macrocell: the sample indices [first, last] read inside it, grown by the
    // position margin (accel/majorant_bounds.h).
    const glm::dvec3 extent = grid.cellSize * glm::dvec3(M);
    const double position = positionMargin(std::max({extent.x, extent.y, extent.z}));
    std::vector<glm::ivec2> span[3];
    for (int a = 0; a < 3; ++a) {
        const double eps = std::max(1e-5 * grid.cellSize[a], position);
        span[a].resize(size_t(M[a]));
        for (int c = 0; c < M[a]; ++c) {
            const double pa = grid.origin[a] + c * grid.cellSize[a] - eps;
            const double pb = grid.origin[a] + (c + 1) * grid.cellSize[a] + eps;
            const double qa = (pa - double(dense.origin[a])) / W - 0.5;
            const double qb = (pb - double(dense.origin[a])) / W - 0.5;
            const double hiLimit = double(N[a] - 1);
            const double first = std::clamp(std::floor(qa), 0.0, hiLimit);
            const double last = std::clamp(std::floor(qb) + 1.0, 0.0, hiLimit);
            span[a][size_t(c)] = glm::ivec2(int(first), int(last));
        }
    }

    // Separable min/max per macrocell layer cz: rows reduced over x, then over y, then over z.
    // Layers in parallel; each run of layers has its own scratch.
    parallelForRanges(0, size_t(M.z), 1, [&](size_t czBegin, size_t czEnd) {
        std::vector<ValueRange> rows(size_t(M.x) * size_t(N.y));  // (cx, y)
        std::vector<ValueRange> layer(size_t(M.x) * size_t(M.y));  // (cx, cy)
        for (int cz = int(czBegin); cz < int(czEnd); ++cz) {
            std::fill(layer.begin(), layer.end(), ValueRange{});
            const glm::ivec2 zs = span[2][size_t(cz)];
            for (int z = zs.x; z <= zs.y; ++z) {
                for (int y = 0; y < N.y; ++y) {
                    const float* row = dense.values.data() + dense.index({0, y, z});
                    for (int cx = 0; cx < M.x; ++cx) {
                        const glm::ivec2 xs = span[0][size_t(cx)];
                        ValueRange r;
                        for (int x = xs.x; x <= xs.y; ++x)
                            if (!std::isnan(row[x])) r.extend(row[x]);
                        rows[size_t(cx) + size_t(M.x) * size_t(y)] = r;
                    }
                }
                for (int cy = 0; cy < M.y; ++cy) {
                    const glm::ivec2 ys = span[1][size_t(cy)];
                    for (int cx = 0; cx < M.x; ++cx) {
                        ValueRange& acc = layer[size_t(cx) + size_t(M.x) * size_t(cy)];
                        for (int y = ys.x; y <= ys.y; ++y) acc.extend(rows[size_t(cx) + size_t(M.x) * size_t(y)]);
                    }
                }
            }
            // Room for the GPU's float trilinear sums.
            std::transform(layer.begin(), layer.end(), grid.ranges.begin() + ptrdiff_t(grid.index({0, 0, cz})),
                           [](const ValueRange& r) { return padForGpu(r); });
        }
    });
}

DenseSample sampleDense(const DenseGrid& dense, glm::dvec3 p) {
    if (dense.values.empty()) return {kNaN, false};
    const glm::dvec3 u = (p - glm::dvec3(dense.origin)) / dense.width();
    const glm::dvec3 q = u - 0.5;
    const glm::dvec3 i0 = glm::floor(q);
    const glm::dvec3 f = q - i0;
    const glm::dvec3 hiIdx = glm::dvec3(dense.dims - 1);
    double sumW = 0, sumWV = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 bit(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        const glm::ivec3 idx(glm::clamp(i0 + bit, glm::dvec3(0.0), hiIdx));
        const float v = dense.values[dense.index(idx)];
        double phi = 1.0;
        for (int a = 0; a < 3; ++a) phi *= bit[a] != 0.0 ? f[a] : 1.0 - f[a];
        if (std::isnan(v) || phi <= 0) continue;
        sumW += phi;
        sumWV += phi * double(v);
    }
    const glm::ivec3 cell(glm::clamp(glm::floor(u), glm::dvec3(0.0), hiIdx));
    DenseSample s;
    s.inside = !std::isnan(dense.values[dense.index(cell)]);
    s.value = sumW > 0 ? static_cast<float>(sumWV / sumW) : kNaN;
    return s;
}

}  // namespace amrvk::accel
