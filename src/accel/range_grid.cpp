#include "accel/range_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include "accel/abrs.h"
#include "accel/brick_grid.h"
#include "accel/brick_sampler.h"
#include "accel/majorant_bounds.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stats.h"
#include "core/strings.h"

namespace amrvk::accel {

glm::ivec3 MacrocellLayout::cellOf(glm::dvec3 p) const {
    glm::dvec3 c = glm::floor((p - origin) / cellSize);
    return glm::clamp(glm::ivec3(glm::clamp(c, glm::dvec3(-1.0), glm::dvec3(dims))), glm::ivec3(0),
                      dims - 1);
}

glm::ivec3 autoGridDims(const amr::Box3l& bounds, int longest, uint64_t maxMacrocells) {
    glm::dvec3 size(bounds.size());
    double maxSize = std::max({size.x, size.y, size.z});
    // Never more macrocells than voxel units along the longest axis.
    longest = int(std::min<double>(longest, std::max(1.0, maxSize)));
    auto dimsOf = [&](int n) {
        glm::ivec3 dims;
        for (int a = 0; a < 3; ++a) dims[a] = std::clamp(int(std::ceil(size[a] * n / maxSize - 1e-9)), 1, n);
        return dims;
    };
    glm::ivec3 dims = dimsOf(longest);
    auto count = [](glm::ivec3 d) { return uint64_t(d.x) * uint64_t(d.y) * uint64_t(d.z); };
    while (maxMacrocells > 0 && longest > 1 && count(dims) > maxMacrocells) dims = dimsOf(--longest);
    return dims;
}

namespace {

// "auto" -> nullopt dims and n = 0; "N" -> n; "NxMxK" -> dims; else `why`.
struct GridText {
    int n = 0;
    glm::ivec3 dims{0};
    std::string why;
};

GridText readGridText(const std::string& text) {
    GridText g;
    if (text == "auto") return g;
    int x = 0, y = 0, z = 0;
    char c1 = 0, c2 = 0, tail = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c%d%c", &x, &c1, &y, &c2, &z, &tail) == 5 && c1 == 'x' && c2 == 'x') {
        g.dims = {x, y, z};
        for (int a = 0; a < 3; ++a)
            if (g.dims[a] < 1 || g.dims[a] > 4096)
                g.why = strCat("macrocells per axis must be in [1, 4096] (got ", text, ")");
    } else if (std::sscanf(text.c_str(), "%d%c", &x, &tail) == 1) {
        g.n = x;
        if (x < 1 || x > 4096) g.why = strCat("macrocells must be in [1, 4096] (got ", text, ")");
    } else {
        g.why = strCat("expected auto, N or NxMxK (got '", text, "')");
    }
    return g;
}

}  // namespace

std::string gridTextError(const std::string& text) { return readGridText(text).why; }

glm::ivec3 parseGridDims(const std::string& text, const amr::Box3l& bounds, uint64_t leafCells) {
    const GridText g = readGridText(text);
    AMRVK_CHECK(g.why.empty(), "--grid: ", g.why);
    if (text == "auto") return autoGridDims(bounds, 128, leafCells * kAutoMacrocellsPerCell);
    return g.n > 0 ? autoGridDims(bounds, g.n) : g.dims;
}

MacrocellLayout macrocellLayout(const amr::Box3l& bounds, glm::ivec3 dims) {
    AMRVK_CHECK(dims.x >= 1 && dims.y >= 1 && dims.z >= 1, "range grid needs at least one macrocell");
    return {.dims = dims, .origin = glm::dvec3(bounds.lower), .cellSize = glm::dvec3(bounds.size()) / glm::dvec3(dims)};
}

namespace {

// Positions along one axis of a brick where the extremes of its clamped trilinear t_b over the
// interval [lo, hi] (cell-centre index space) can lie: both ends and the centres between them.
// Each is (cell i0, fraction f): value (1 - f) v[i0] + f v[i0 + 1].
struct AxisPositions {
    int first = 0, last = 0;  // cells read: [first, last]
    std::vector<std::pair<int, double>> pos;
};

void axisPositions(double lo, double hi, int size, AxisPositions& out) {
    lo = std::clamp(lo, 0.0, double(size - 1));
    hi = std::clamp(hi, lo, double(size - 1));
    out.pos.clear();
    auto add = [&](double u) {
        int i0 = std::min(int(std::floor(u)), size - 1);
        out.pos.emplace_back(i0, u - double(i0));
    };
    add(lo);
    for (double c = std::floor(lo) + 1.0; c < hi; c += 1.0) add(c);
    if (hi > lo) add(hi);
    out.first = out.pos.front().first;
    out.last = std::min(out.pos.back().first + (out.pos.back().second > 0.0 ? 1 : 0), size - 1);
}

struct Scratch {
    AxisPositions axis[3];
    std::vector<double> ax, ay;  // t_b interpolated along x, then along y
};

// The range [clo, chi] of brick b's non-empty cells read by t_b over the closed voxel-space box
// [lo, hi] (cut to the brick's domain), with s.axis set to the box's positions; returns whether an
// empty slot is among them (clo > chi: nothing but empty slots).
bool cellsRead(const Brick& b, std::span<const float> values, glm::dvec3 lo, glm::dvec3 hi, Scratch& s, double& clo,
               double& chi) {
    const double w = double(b.cellWidth());
    for (int d = 0; d < 3; ++d)
        axisPositions((lo[d] - b.lower[d]) / w - 0.5, (hi[d] - b.lower[d]) / w - 0.5, b.size[d], s.axis[d]);
    // Without branches, so that it vectorises: std::min(r, NaN) and std::max(r, NaN) keep r.
    bool hole = false;
    float vlo = INFINITY, vhi = -INFINITY;
    for (int z = s.axis[2].first; z <= s.axis[2].last; ++z)
        for (int y = s.axis[1].first; y <= s.axis[1].last; ++y) {
            const float* row = values.data() + b.begin + size_t((z * b.size.y + y) * b.size.x);
            for (int x = s.axis[0].first; x <= s.axis[0].last; ++x) {
                vlo = std::min(vlo, row[x]);
                vhi = std::max(vhi, row[x]);
                hole |= row[x] != row[x];
            }
        }
    clo = double(vlo);
    chi = double(vhi);
    return hole;
}

// Extends `range` by the range of brick b's t_b over the closed voxel-space box [lo, hi] (already
// cut to the brick's domain); tracks the range of the values read in [readLo, readHi].
void extendByBrick(const Brick& b, std::span<const float> values, glm::dvec3 lo, glm::dvec3 hi, Scratch& s,
                   double& rlo, double& rhi, double& readLo, double& readHi) {
    auto at = [&](int x, int y, int z) { return values[b.begin + size_t((z * b.size.y + y) * b.size.x + x)]; };
    double clo = 0, chi = 0;
    // With an empty slot among the cells read, t_b is a convex combination of the others.
    const bool hole = cellsRead(b, values, lo, hi, s, clo, chi);
    if (clo > chi) return;  // nothing but empty slots
    readLo = std::min(readLo, clo);
    readHi = std::max(readHi, chi);
    if (hole) {
        rlo = std::min(rlo, clo);
        rhi = std::max(rhi, chi);
        return;
    }
    const AxisPositions &X = s.axis[0], &Y = s.axis[1], &Z = s.axis[2];
    // Separable evaluation on the lattice X x Y x Z: along x for every cell row read, then along y,
    // then along z.
    const int ny = Y.last - Y.first + 1, nz = Z.last - Z.first + 1;
    const size_t px = X.pos.size(), py = Y.pos.size();
    auto next = [](int i, int last) { return std::min(i + 1, last); };
    s.ax.resize(px * size_t(ny) * size_t(nz));
    for (int z = 0; z < nz; ++z)
        for (int y = 0; y < ny; ++y)
            for (size_t i = 0; i < px; ++i) {
                const auto [x0, f] = X.pos[i];
                const double v0 = at(x0, Y.first + y, Z.first + z), v1 = at(next(x0, X.last), Y.first + y, Z.first + z);
                s.ax[(size_t(z) * size_t(ny) + size_t(y)) * px + i] = v0 + f * (v1 - v0);
            }
    s.ay.resize(px * py * size_t(nz));
    for (int z = 0; z < nz; ++z)
        for (size_t j = 0; j < py; ++j) {
            const auto [y0, f] = Y.pos[j];
            const size_t r0 = (size_t(z) * size_t(ny) + size_t(y0 - Y.first)) * px;
            const size_t r1 = (size_t(z) * size_t(ny) + size_t(next(y0, Y.last) - Y.first)) * px;
            for (size_t i = 0; i < px; ++i)
                s.ay[(size_t(z) * py + j) * px + i] = s.ax[r0 + i] + f * (s.ax[r1 + i] - s.ax[r0 + i]);
        }
    for (const auto& [z0, f] : Z.pos) {
        const size_t p0 = size_t(z0 - Z.first) * py * px, p1 = size_t(next(z0, Z.last) - Z.first) * py * px;
        for (size_t k = 0; k < py * px; ++k) {
            const double v = s.ay[p0 + k] + f * (s.ay[p1 + k] - s.ay[p0 + k]);
            rlo = std::min(rlo, v);
            rhi = std::max(rhi, v);
        }
    }
}

// The exact range of the reconstruction f = N / D over a macrocell's box (N = sum phi v, D = sum
// phi over every brick cell, empty slots skipped): between consecutive breakpoints of the tent
// weights along each axis (cell centres and domain ends of the bricks) every phi is a product of
// linear factors, so N and D are multilinear on each sub-box, and so is N - M D for any M. With M
// the largest f over the sub-box's vertices where D > 0, N - M D <= 0 at every vertex (where D = 0
// also N = 0), hence everywhere in the sub-box: f <= M wherever D > 0; the same holds for the
// minimum. So f's range over a box is its range over the vertices of the lattice of breakpoints
// and the box's faces inside the box. Neighbouring macrocells share a lattice: a tile of
// macrocells gets one (every macrocell's grown faces, and every breakpoint of the bricks that meet
// the tile), split in two while it has more than kSharedVertices per macrocell (a fine brick's
// planes cross its coarse neighbours' macrocells too) or a macrocell over kMaxExactVertices in it,
// down to one macrocell. N and D are summed brick by brick, separably (along x for every cell row,
// then along y, then z), in chunks of at most kChunkPlanes^3 vertices, and each macrocell's range
// is reduced separably over its vertices. A macrocell whose own lattice has more than
// kMaxExactVertices vertices (a few cells of its finest brick across it) takes the union of the
// exact per-brick ranges (extendByBrick), as before the lattice: looser only where bricks blend,
// O(cells) to make. The ranges are those of one lattice per macrocell, up to rounding, made with
// less work per macrocell (docs/benchmarks.md section 24).
constexpr size_t kMaxExactVertices = 512;
constexpr size_t kChunkPlanes = 64;
constexpr size_t kSharedVertices = 512;
// Tiles of kTile^3 macrocells, whose bricks' values stay in the cache; halving one axis at a time,
// a tile's split is at most 3 log2(kTile) deep below it.
constexpr int kTile = 8;
constexpr int kMaxSplitDepth = 1 + 3 * 3;
static_assert(kTile == 1 << 3, "kMaxSplitDepth assumes tiles of 8^3");

// Where brick b's tent weights change form along axis a (voxel space): its domain ends, and the
// centres of its cells k0..k1, those that may lie in [lo, hi] (k1 < k0: none).
struct AxisBreakpoints {
    double ends[2];
    double k0, k1;
    double base, width;
    double centre(double k) const { return base + (k + 0.5) * width; }
};
AxisBreakpoints breakpoints(const Brick& b, int a, double lo, double hi) {
    const double w = double(b.cellWidth()), base = double(b.lower[a]);
    return {.ends = {base - 0.5 * w, base + (double(b.size[a]) + 0.5) * w},
            .k0 = std::max(0.0, std::ceil((lo - base) / w - 0.5)),
            .k1 = std::min(double(b.size[a] - 1), std::floor((hi - base) / w - 0.5)),
            .base = base,
            .width = w};
}

// What the padding needs of a brick without reading its cells again: the range of its non-empty
// values.
struct BrickSigns {
    float lo = INFINITY, hi = -INFINITY;
    bool hole = false;  // an empty slot among its cells
};

struct TileScratch {
    std::vector<uint32_t> bricks[kMaxSplitDepth + 1];  // per depth of the split: whose domains meet the box, ascending
    std::vector<double> planes[3];                 // the box's lattice, per axis, ascending
    std::vector<std::pair<size_t, size_t>> span[3];  // per macrocell of the box and axis: planes [first, end)
    std::vector<double> num, den;                  // per vertex of the current chunk (num becomes f)
    std::vector<double> ax, axw, ay, ayw;          // partial sums of N (and of D, with empty slots)
    std::vector<TentAxis> factor[3];               // per plane of the current brick and chunk
    std::vector<double> weightSum[3];              // sum of each factor's weights
    std::vector<double> rx, ry, rz;                // a chunk's ranges per macrocell along x, then y, then z
    std::vector<double> lo, hi;                    // per macrocell of the tile: the range so far
    std::vector<uint8_t> exact;                    // per macrocell of the tile: made on the lattice
    bool nonNegative = false, nonPositive = false;  // every value the tile's bricks hold
    Scratch perBrick;
};

// Adds brick b's N and D at the chunk's vertices (plane indices [q0, q1) per axis) that lie in its
// closed domain [dlo, dhi]; the chunk's arrays are x fastest.
void addBrickAtVertices(const Brick& b, std::span<const float> values, bool hole, glm::dvec3 dlo, glm::dvec3 dhi,
                        const size_t (&q0)[3], const size_t (&q1)[3], TileScratch& s) {
    size_t first[3], count[3];
    int cmin[3], cmax[3];
    const double w = double(b.cellWidth());
    for (int a = 0; a < 3; ++a) {
        const std::vector<double>& pl = s.planes[a];
        first[a] = std::max(q0[a], size_t(std::lower_bound(pl.begin(), pl.end(), dlo[a]) - pl.begin()));
        const size_t end = std::min(q1[a], size_t(std::upper_bound(pl.begin(), pl.end(), dhi[a]) - pl.begin()));
        if (first[a] >= end) return;
        count[a] = end - first[a];
        s.factor[a].resize(count[a]);
        s.weightSum[a].resize(count[a]);
        cmin[a] = INT32_MAX;
        cmax[a] = -1;
        for (size_t q = 0; q < count[a]; ++q) {
            const TentAxis t = tentAxis((pl[first[a] + q] - double(b.lower[a])) / w - 0.5, b.size[a]);
            s.factor[a][q] = t;
            s.weightSum[a][q] = 0;
            for (int k = 0; k < t.count; ++k) {
                s.weightSum[a][q] += t.weight[k];
                cmin[a] = std::min(cmin[a], t.cell[k]);
                cmax[a] = std::max(cmax[a], t.cell[k]);
            }
        }
        if (cmin[a] > cmax[a]) return;  // only the far domain end: no weight
    }
    const size_t nx = count[0], ny = count[1], nz = count[2];
    const size_t rows = size_t(cmax[1] - cmin[1] + 1), layers = size_t(cmax[2] - cmin[2] + 1);
    const std::vector<TentAxis>&fx = s.factor[0], &fy = s.factor[1], &fz = s.factor[2];
    // Along x, for every cell row the chunk's planes read.
    s.ax.resize(nx * rows * layers);
    if (hole) s.axw.resize(nx * rows * layers);
    for (size_t z = 0; z < layers; ++z)
        for (size_t y = 0; y < rows; ++y) {
            const size_t row = b.begin + size_t((int64_t(cmin[2]) + int64_t(z)) * b.size.y + cmin[1] + int64_t(y)) * size_t(b.size.x);
            double* out = &s.ax[(z * rows + y) * nx];
            double* outW = hole ? &s.axw[(z * rows + y) * nx] : nullptr;
            for (size_t i = 0; i < nx; ++i) {
                double sum = 0, sumW = 0;
                for (int k = 0; k < fx[i].count; ++k) {
                    const float v = values[row + size_t(fx[i].cell[k])];
                    if (std::isnan(v)) continue;
                    sum += fx[i].weight[k] * double(v);
                    sumW += fx[i].weight[k];
                }
                out[i] = sum;
                if (hole) outW[i] = sumW;
            }
        }
    // Along y.
    s.ay.resize(nx * ny * layers);
    if (hole) s.ayw.resize(nx * ny * layers);
    for (size_t z = 0; z < layers; ++z)
        for (size_t j = 0; j < ny; ++j) {
            double* out = &s.ay[(z * ny + j) * nx];
            std::fill_n(out, nx, 0.0);
            double* outW = hole ? &s.ayw[(z * ny + j) * nx] : nullptr;
            if (hole) std::fill_n(outW, nx, 0.0);
            for (int k = 0; k < fy[j].count; ++k) {
                const double wy = fy[j].weight[k];
                const size_t in = (z * rows + size_t(fy[j].cell[k] - cmin[1])) * nx;
                for (size_t i = 0; i < nx; ++i) out[i] += wy * s.ax[in + i];
                if (hole)
                    for (size_t i = 0; i < nx; ++i) outW[i] += wy * s.axw[in + i];
            }
        }
    // Along z, into the chunk's vertices.
    const size_t cx = q1[0] - q0[0], cy = q1[1] - q0[1];
    for (size_t k = 0; k < nz; ++k)
        for (size_t j = 0; j < ny; ++j) {
            const size_t v0 = ((first[2] + k - q0[2]) * cy + (first[1] + j - q0[1])) * cx + (first[0] - q0[0]);
            double* num = &s.num[v0];
            double* den = &s.den[v0];
            for (int c = 0; c < fz[k].count; ++c) {
                const double wz = fz[k].weight[c];
                const size_t in = (size_t(fz[k].cell[c] - cmin[2]) * ny + j) * nx;
                for (size_t i = 0; i < nx; ++i) num[i] += wz * s.ay[in + i];
                if (hole)
                    for (size_t i = 0; i < nx; ++i) den[i] += wz * s.ayw[in + i];
            }
            if (!hole) {
                const double wyz = s.weightSum[1][j] * s.weightSum[2][k];
                for (size_t i = 0; i < nx; ++i) den[i] += s.weightSum[0][i] * wyz;
            }
        }
}


// The ranges of one tile of macrocells on shared lattices (see kMaxExactVertices). The layout `g`
// is the lists' own, or the sub-boxes of one macrocell of theirs (SubRangeMaker): then every
// sub-box takes that macrocell's list (`everyList`), and reaches outwards only on the faces where
// the macrocell is at the grid's edge (`openLo`, `openHi`).
struct TileLattice {
    const MacrocellLayout& g;
    glm::dvec3 margin;
    const BrickGrid& lists;
    const BrickSet& bricks;
    std::span<const float> values;
    const std::vector<BrickSigns>& signs;
    std::optional<std::span<const uint32_t>> everyList = std::nullopt;
    glm::bvec3 openLo{true}, openHi{true};

    std::span<const uint32_t> bricksOf(glm::ivec3 c) const { return everyList ? *everyList : lists.bricksOf(g.index(c)); }
    // A macrocell's box grown by the margin (the lists' box), per axis; edge macrocells reach outwards.
    double boxLo(int a, int i) const {
        return i == 0 && openLo[a] ? -INFINITY : g.origin[a] + g.cellSize[a] * double(i) - margin[a];
    }
    double boxHi(int a, int i) const {
        return i == g.dims[a] - 1 && openHi[a] ? INFINITY : g.origin[a] + g.cellSize[a] * double(i + 1) + margin[a];
    }
    static bool meets(const HalfBox& d, glm::dvec3 lo, glm::dvec3 hi) {
        const glm::dvec3 blo = glm::max(lo, d.lower()), bhi = glm::min(hi, d.upper());
        return blo.x <= bhi.x && blo.y <= bhi.y && blo.z <= bhi.z;
    }

    // Writes the ranges of the macrocells [c0, c1) into `ranges`.
    void tile(glm::ivec3 c0, glm::ivec3 c1, std::vector<ValueRange>& ranges, TileScratch& s) const {
        const glm::ivec3 n = c1 - c0;
        const size_t count = size_t(n.x) * size_t(n.y) * size_t(n.z);
        s.lo.assign(count, INFINITY);
        s.hi.assign(count, -INFINITY);
        s.exact.assign(count, 0);
        std::vector<uint32_t>& listed = s.bricks[0];
        listed.clear();
        if (everyList) {  // one list, ascending already
            listed.assign(everyList->begin(), everyList->end());
        } else {
            for (int z = c0.z; z < c1.z; ++z)
                for (int y = c0.y; y < c1.y; ++y)
                    for (int x = c0.x; x < c1.x; ++x)
                        for (uint32_t id : bricksOf({x, y, z})) listed.push_back(id);
            std::sort(listed.begin(), listed.end());
            listed.erase(std::unique(listed.begin(), listed.end()), listed.end());
        }
        // Where every listed brick's values have one sign, so do the values any macrocell reads
        // (finish then skips its per-macrocell look at the bricks' signs: 4-5% of the build at 256).
        s.nonNegative = s.nonPositive = true;
        for (uint32_t id : listed) {
            s.nonNegative &= signs[id].lo >= 0;
            s.nonPositive &= signs[id].hi <= 0;
        }
        box(c0, c1, c0, n, 1, s);
        for (int z = 0; z < n.z; ++z)
            for (int y = 0; y < n.y; ++y)
                for (int x = 0; x < n.x; ++x) {
                    const glm::ivec3 c = c0 + glm::ivec3(x, y, z);
                    const size_t local = (size_t(z) * size_t(n.y) + size_t(y)) * size_t(n.x) + size_t(x);
                    ranges[g.index(c)] = finish(c, s.exact[local] != 0, s.lo[local], s.hi[local], s);
                }
    }

    // The lattice of the macrocells [c0, c1) (of the tile at t0, n per axis) over the bricks of
    // s.bricks[depth - 1] that meet them; split in two while it has more than kSharedVertices per
    // macrocell (a fine brick's planes cross its coarse neighbours' macrocells too).
    void box(glm::ivec3 c0, glm::ivec3 c1, glm::ivec3 t0, glm::ivec3 n, int depth, TileScratch& s) const {
        const glm::ivec3 m = c1 - c0;
        glm::dvec3 lo, hi;
        for (int a = 0; a < 3; ++a) {
            lo[a] = boxLo(a, c0[a]);
            hi[a] = boxHi(a, c1[a] - 1);
        }
        std::vector<uint32_t>& own = s.bricks[depth];
        own.clear();
        for (uint32_t id : s.bricks[depth - 1])
            if (meets(brickDomain(bricks.bricks[id]), lo, hi)) own.push_back(id);
        if (own.empty()) return;  // no brick has weight here: empty, majorant 0
        // Planes per axis, counted without gathering them (duplicates counted twice, so at least
        // the lattice's): split, or give a macrocell across many cells up, before any sorting.
        // Faces outside the bricks' domains add no vertex with weight: only those inside count.
        glm::dvec3 hullLo(INFINITY), hullHi(-INFINITY);
        for (uint32_t id : own) {
            const HalfBox d = brickDomain(bricks.bricks[id]);
            hullLo = glm::min(hullLo, d.lower());
            hullHi = glm::max(hullHi, d.upper());
        }
        auto faceInside = [&](int a, double f) { return std::isfinite(f) && f >= hullLo[a] && f <= hullHi[a]; };
        double counted = 1;
        for (int a = 0; a < 3; ++a) {
            double planes = 0;
            for (int i = c0[a]; i < c1[a]; ++i) planes += faceInside(a, boxLo(a, i)) + faceInside(a, boxHi(a, i));
            for (uint32_t id : own) {
                const AxisBreakpoints p = breakpoints(bricks.bricks[id], a, lo[a], hi[a]);
                for (double e : p.ends) planes += e >= lo[a] && e <= hi[a];
                planes += std::max(0.0, p.k1 - p.k0 + 1);
            }
            counted *= planes;
        }
        const size_t macrocells = size_t(m.x) * size_t(m.y) * size_t(m.z);
        auto split = [&] {
            const int a = m.x >= m.y && m.x >= m.z ? 0 : m.y >= m.z ? 1 : 2;
            glm::ivec3 mid = c1;
            mid[a] = c0[a] + m[a] / 2;
            glm::ivec3 second = c0;
            second[a] = mid[a];
            box(c0, mid, t0, n, depth + 1, s);
            box(second, c1, t0, n, depth + 1, s);
        };
        if (macrocells > 1 && counted > double(kSharedVertices * macrocells)) return split();
        // One macrocell across many cells: the per-brick ranges (finish); up to 4 counted per plane.
        if (macrocells == 1 && counted > 64.0 * double(kMaxExactVertices)) return;
        gatherPlanes(c0, c1, lo, hi, own, faceInside, s);
        if (macrocells == 1 && s.planes[0].size() * s.planes[1].size() * s.planes[2].size() > kMaxExactVertices) return;
        for (int a = 0; a < 3; ++a) {
            const std::vector<double>& pl = s.planes[a];
            s.span[a].resize(size_t(m[a]));
            for (int i = 0; i < m[a]; ++i)
                s.span[a][size_t(i)] = {size_t(std::lower_bound(pl.begin(), pl.end(), boxLo(a, c0[a] + i)) - pl.begin()),
                                        size_t(std::upper_bound(pl.begin(), pl.end(), boxHi(a, c0[a] + i)) - pl.begin())};
        }
        auto spanOf = [&](int a, int i) { return s.span[a][size_t(i)]; };
        auto exactAt = [&](int x, int y, int z) {
            return (spanOf(0, x).second - spanOf(0, x).first) * (spanOf(1, y).second - spanOf(1, y).first) *
                       (spanOf(2, z).second - spanOf(2, z).first) <=
                   kMaxExactVertices;
        };
        auto local = [&](int x, int y, int z) {  // in the tile
            const glm::ivec3 t = c0 - t0 + glm::ivec3(x, y, z);
            return (size_t(t.z) * size_t(n.y) + size_t(t.y)) * size_t(n.x) + size_t(t.x);
        };
        if (macrocells > 1)  // a macrocell that its neighbours' planes would put over the limit
            for (int z = 0; z < m.z; ++z)
                for (int y = 0; y < m.y; ++y)
                    for (int x = 0; x < m.x; ++x)
                        if (!exactAt(x, y, z)) return split();
        bool any = false;
        for (int z = 0; z < m.z; ++z)
            for (int y = 0; y < m.y; ++y)
                for (int x = 0; x < m.x; ++x)
                    if (exactAt(x, y, z)) s.exact[local(x, y, z)] = any = true;
        if (!any) return;  // one macrocell across many cells: the per-brick ranges (finish)
        rangesAtVertices(m, own, exactAt, local, s);
    }

    // The sorted, distinct planes of box()'s lattice on each axis into s.planes: the macrocells'
    // faces inside the bricks' hull (faceInside), and each brick's breakpoints within [lo, hi].
    template <typename FaceInside>
    void gatherPlanes(glm::ivec3 c0, glm::ivec3 c1, glm::dvec3 lo, glm::dvec3 hi, const std::vector<uint32_t>& own,
                      const FaceInside& faceInside, TileScratch& s) const {
        for (int a = 0; a < 3; ++a) {
            std::vector<double>& pl = s.planes[a];
            pl.clear();
            for (int i = c0[a]; i < c1[a]; ++i)
                for (double f : {boxLo(a, i), boxHi(a, i)})
                    if (faceInside(a, f)) pl.push_back(f);
            for (uint32_t id : own) {
                const AxisBreakpoints p = breakpoints(bricks.bricks[id], a, lo[a], hi[a]);
                for (double e : p.ends)
                    if (e >= lo[a] && e <= hi[a]) pl.push_back(e);
                for (double k = p.k0; k <= p.k1; k += 1.0) {
                    const double c = p.centre(k);
                    if (c >= lo[a] && c <= hi[a]) pl.push_back(c);
                }
            }
            std::sort(pl.begin(), pl.end());
            pl.erase(std::unique(pl.begin(), pl.end()), pl.end());
        }
    }

    // N and D at the lattice's vertices (s.planes), chunk by chunk, and the ranges of f = N / D
    // over them into s.lo and s.hi of each macrocell of the box (m per axis) that is exact
    // (exactAt); local(x, y, z) is the macrocell's index in the tile.
    template <typename ExactAt, typename Local>
    void rangesAtVertices(glm::ivec3 m, const std::vector<uint32_t>& own, const ExactAt& exactAt, const Local& local,
                          TileScratch& s) const {
        const size_t np[3] = {s.planes[0].size(), s.planes[1].size(), s.planes[2].size()};
        for (size_t z0 = 0; z0 < np[2]; z0 += kChunkPlanes)
            for (size_t y0 = 0; y0 < np[1]; y0 += kChunkPlanes)
                for (size_t x0 = 0; x0 < np[0]; x0 += kChunkPlanes) {
                    const size_t q0[3] = {x0, y0, z0};
                    const size_t q1[3] = {std::min(np[0], x0 + kChunkPlanes), std::min(np[1], y0 + kChunkPlanes),
                                          std::min(np[2], z0 + kChunkPlanes)};
                    const size_t cx = q1[0] - q0[0], cy = q1[1] - q0[1], cz = q1[2] - q0[2];
                    s.num.assign(cx * cy * cz, 0.0);
                    s.den.assign(cx * cy * cz, 0.0);
                    for (uint32_t id : own) {
                        const Brick& b = bricks.bricks[id];
                        const HalfBox d = brickDomain(b);
                        addBrickAtVertices(b, values, signs[id].hole, d.lower(), d.upper(), q0, q1, s);
                    }
                    // f where D > 0; else N = 0 too, and 0 / 0 is NaN, which std::min(r, NaN) and
                    // std::max(r, NaN) pass over.
                    for (size_t v = 0; v < s.num.size(); ++v) s.num[v] /= s.den[v];
                    reduceChunk(m, q0, q1, s);
                    for (int z = 0; z < m.z; ++z)
                        for (int y = 0; y < m.y; ++y)
                            for (int x = 0; x < m.x; ++x) {
                                const size_t r = (size_t(z) * size_t(m.y) + size_t(y)) * size_t(m.x) + size_t(x);
                                if (!exactAt(x, y, z) || !(s.rz[2 * r] <= s.rz[2 * r + 1])) continue;
                                s.lo[local(x, y, z)] = std::min(s.lo[local(x, y, z)], s.rz[2 * r]);
                                s.hi[local(x, y, z)] = std::max(s.hi[local(x, y, z)], s.rz[2 * r + 1]);
                            }
                }
    }

    // The range of f (s.num) over each macrocell's vertices in the chunk [q0, q1), separably:
    // along x per vertex row, then along y, then z; into s.rz (lo, hi per macrocell of the box,
    // x fastest; empty where none of its vertices has weight or lies in the chunk).
    static void reduceChunk(glm::ivec3 m, const size_t (&q0)[3], const size_t (&q1)[3], TileScratch& s) {
        const size_t cx = q1[0] - q0[0], cy = q1[1] - q0[1], cz = q1[2] - q0[2];
        const size_t mx = size_t(m.x), my = size_t(m.y), mz = size_t(m.z);
        // The planes of macrocell i along axis a inside the chunk, chunk-relative: [first, end).
        auto inChunk = [&](int a, size_t i) {
            const auto [f, e] = s.span[a][i];
            const size_t lo = std::max(f, q0[a]), hi = std::min(e, q1[a]);
            return lo < hi ? std::pair{lo - q0[a], hi - q0[a]} : std::pair{size_t(0), size_t(0)};
        };
        s.rx.assign(2 * cz * cy * mx, 0.0);
        for (size_t r = 0; r < cz * cy; ++r) {
            const double* f = &s.num[r * cx];
            for (size_t x = 0; x < mx; ++x) {
                const auto [i0, i1] = inChunk(0, x);
                double lo = INFINITY, hi = -INFINITY;
                for (size_t i = i0; i < i1; ++i) {
                    lo = std::min(lo, f[i]);
                    hi = std::max(hi, f[i]);
                }
                s.rx[2 * (r * mx + x)] = lo;
                s.rx[2 * (r * mx + x) + 1] = hi;
            }
        }
        reduceAxis(s.rx, s.ry, cz, cy, my, mx, [&](size_t y) { return inChunk(1, y); });
        reduceAxis(s.ry, s.rz, 1, cz, mz, my * mx, [&](size_t z) { return inChunk(2, z); });
    }

    // (lo, hi) pairs of an (outer, n, inner) array reduced over the middle axis to (outer,
    // spans.size(), inner): out's middle index m takes the input's [span(m).first, span(m).second).
    template <typename Span>
    static void reduceAxis(const std::vector<double>& in, std::vector<double>& out, size_t outer, size_t n,
                           size_t reduced, size_t inner, Span&& span) {
        out.assign(2 * outer * reduced * inner, 0.0);
        for (size_t o = 0; o < outer; ++o)
            for (size_t m = 0; m < reduced; ++m) {
                const auto [j0, j1] = span(m);
                for (size_t x = 0; x < inner; ++x) {
                    double lo = INFINITY, hi = -INFINITY;
                    for (size_t j = j0; j < j1; ++j) {
                        lo = std::min(lo, in[2 * ((o * n + j) * inner + x)]);
                        hi = std::max(hi, in[2 * ((o * n + j) * inner + x) + 1]);
                    }
                    out[2 * ((o * reduced + m) * inner + x)] = lo;
                    out[2 * ((o * reduced + m) * inner + x) + 1] = hi;
                }
            }
    }

    // Macrocell c's range, padded: [rlo, rhi] from its lattice where `exact`, else the union of
    // the per-brick ranges.
    ValueRange finish(glm::ivec3 c, bool exact, double rlo, double rhi, TileScratch& s) const {
        const glm::dvec3 mlo(boxLo(0, c.x), boxLo(1, c.y), boxLo(2, c.z));
        const glm::dvec3 mhi(boxHi(0, c.x), boxHi(1, c.y), boxHi(2, c.z));
        if (exact && rlo > rhi) return {};  // no brick has weight here: empty, majorant 0
        if (exact && (s.nonNegative || s.nonPositive)) return padForGpu(rlo, rhi, s.nonNegative ? rhi : -rlo);
        // The range of the values read near the macrocell (the padding's magnitude where they have
        // both signs). Where the bricks that meet it have one sign, their ranges say so.
        double readLo = INFINITY, readHi = -INFINITY;
        bool nonNegative = true, nonPositive = true;
        auto touching = [&](auto&& visit) {
            for (uint32_t id : bricksOf(c)) {
                const Brick& b = bricks.bricks[id];
                const HalfBox d = brickDomain(b);
                const glm::dvec3 blo = glm::max(mlo, d.lower()), bhi = glm::min(mhi, d.upper());
                if (blo.x <= bhi.x && blo.y <= bhi.y && blo.z <= bhi.z) visit(id, b, blo, bhi);
            }
        };
        if (exact)
            touching([&](uint32_t id, const Brick&, glm::dvec3, glm::dvec3) {
                nonNegative &= signs[id].lo >= 0;
                nonPositive &= signs[id].hi <= 0;
            });
        const bool oneSign = exact && (nonNegative || nonPositive);
        if (!oneSign)
            touching([&](uint32_t, const Brick& b, glm::dvec3 blo, glm::dvec3 bhi) {
                if (!exact) {
                    extendByBrick(b, values, blo, bhi, s.perBrick, rlo, rhi, readLo, readHi);
                    return;
                }
                double clo = 0, chi = 0;
                (void)cellsRead(b, values, blo, bhi, s.perBrick, clo, chi);
                readLo = std::min(readLo, clo);
                readHi = std::max(readHi, chi);
            });
        if (rlo > rhi) return {};  // no brick has weight here: empty, majorant 0
        // Room for the GPU's float sums (accel/majorant_bounds.h): their error scales with the
        // reconstruction of |v|, which is f itself (so at most rhi, or -rlo) where the values read
        // have one sign, else at most the largest magnitude read.
        const double magnitude = oneSign     ? (nonNegative ? rhi : -rlo)
                                 : readLo >= 0 ? rhi
                                 : readHi <= 0 ? -rlo
                                               : std::max(-readLo, readHi);
        return padForGpu(rlo, rhi, magnitude);
    }
};

// Every brick's value range and holes, once (what the padding needs of most macrocells).
std::vector<BrickSigns> brickSigns(const BrickSet& bricks, std::span<const float> brickValues) {
    std::vector<BrickSigns> signs(bricks.bricks.size());
    parallelFor(0, signs.size(), [&](size_t i) {
        const Brick& b = bricks.bricks[i];
        const float* v = brickValues.data() + b.begin;
        // Without branches, so that it vectorises: std::min(r, NaN) and std::max(r, NaN) keep r.
        float lo = INFINITY, hi = -INFINITY;
        bool hole = false;
        for (uint64_t k = 0; k < b.cellCount(); ++k) {
            lo = std::min(lo, v[k]);
            hi = std::max(hi, v[k]);
            hole |= v[k] != v[k];
        }
        signs[i] = {lo, hi, hole};
    }, 64);
    return signs;
}

}  // namespace

RangeGrid buildRangeGrid(const BrickGrid& lists, const BrickSet& bricks, std::span<const float> brickValues) {
    Timer timer;
    RangeGrid g{static_cast<const MacrocellLayout&>(lists)};
    const size_t total = g.cellCount();
    checkAllocation(checkedProduct({total, sizeof(ValueRange)}, "--grid"),
                    strCat("--grid ", g.dims.x, "x", g.dims.y, "x", g.dims.z, ": macrocell value ranges"));
    g.ranges.resize(total);
    const glm::dvec3 margin = brickGridMargin(g.cellSize, g.dims);
    const std::vector<BrickSigns> signs = brickSigns(bricks, brickValues);
    TileLattice lattice{g, margin, lists, bricks, brickValues, signs};
    // In about a hundred batches of tiles, so that the bar moves.
    const glm::ivec3 tiles = (g.dims + kTile - 1) / kTile;
    const size_t tileCount = size_t(tiles.x) * size_t(tiles.y) * size_t(tiles.z);
    ProgressBar bar("macrocell value ranges", "macrocells");
    const size_t batch = std::max<size_t>(1, tileCount / 100);
    for (size_t first = 0; first < tileCount; first += batch) {
        parallelForRanges(first, std::min(tileCount, first + batch), 1, [&](size_t begin, size_t end) {
            TileScratch scratch;
            for (size_t t = begin; t < end; ++t) {
                const glm::ivec3 lo = kTile * glm::ivec3(int(t % size_t(tiles.x)), int(t / size_t(tiles.x) % size_t(tiles.y)),
                                                         int(t / (size_t(tiles.x) * size_t(tiles.y))));
                lattice.tile(lo, glm::min(lo + kTile, g.dims), g.ranges, scratch);
            }
        });
        bar.update(std::min(total, (std::min(tileCount, first + batch)) * total / tileCount), total);
    }
    bar.finish();
    g.buildSeconds = timer.seconds();
    return g;
}

struct SubRangeMaker::Signs {
    std::vector<BrickSigns> v;
};

SubRangeMaker::SubRangeMaker(const BrickGrid& lists, const BrickSet& bricks, std::span<const float> brickValues)
    : mLists(lists), mBricks(bricks), mValues(brickValues),
      mSigns(std::make_shared<const Signs>(Signs{brickSigns(bricks, brickValues)})) {}

void SubRangeMaker::ranges(size_t cell, int n, std::vector<ValueRange>& out) const {
    AMRVK_CHECK(cell < mLists.cellCount() && n >= 1 && n <= kMaxSubdivision, "internal: sub-ranges of macrocell ",
                cell, " at ", n, "^3");
    const glm::ivec3 c = mLists.coordOf(cell);
    const MacrocellLayout sub{.dims = glm::ivec3(n),
                              .origin = mLists.origin + glm::dvec3(c) * mLists.cellSize,
                              .cellSize = mLists.cellSize / double(n)};
    const TileLattice lattice{.g = sub,
                              .margin = brickGridMargin(mLists.cellSize, mLists.dims),
                              .lists = mLists,
                              .bricks = mBricks,
                              .values = mValues,
                              .signs = mSigns->v,
                              .everyList = mLists.bricksOf(cell),
                              .openLo = glm::equal(c, glm::ivec3(0)),
                              .openHi = glm::equal(c, mLists.dims - 1)};
    thread_local TileScratch scratch;
    out.assign(sub.cellCount(), ValueRange{});
    // Where one brick's domain alone meets a grown sub-box, f there is that brick's t_b, whose range
    // the per-brick evaluation makes exactly (finish, not exact: the union over the one brick), at
    // a few lattice points per sub-box. Where several meet one, they blend: the shared lattice for
    // the whole macrocell.
    const std::span<const uint32_t> list = mLists.bricksOf(cell);
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::dvec3 lo(lattice.boxLo(0, x), lattice.boxLo(1, y), lattice.boxLo(2, z));
                const glm::dvec3 hi(lattice.boxHi(0, x), lattice.boxHi(1, y), lattice.boxHi(2, z));
                int meeting = 0;
                for (uint32_t id : list) meeting += TileLattice::meets(brickDomain(mBricks.bricks[id]), lo, hi);
                if (meeting > 1) {  // in tiles of kTile^3 sub-boxes, as buildRangeGrid's (the split depth)
                    for (int tz = 0; tz < n; tz += kTile)
                        for (int ty = 0; ty < n; ty += kTile)
                            for (int tx = 0; tx < n; tx += kTile) {
                                const glm::ivec3 t0(tx, ty, tz);
                                lattice.tile(t0, glm::min(t0 + kTile, sub.dims), out, scratch);
                            }
                    return;
                }
            }
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                out[sub.index({x, y, z})] = lattice.finish({x, y, z}, false, INFINITY, -INFINITY, scratch);
}

}  // namespace amrvk::accel
