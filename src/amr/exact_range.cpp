#include "amr/exact_range.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/error.h"

namespace amrvk::amr {

namespace {

constexpr uint64_t kEmpty = ~uint64_t{0};
constexpr int kKeyBits = 21;  // per axis in a packed block key
constexpr int64_t kKeyMax = (int64_t{1} << kKeyBits) - 1;
constexpr uint64_t kMaxVertices = 4096;  // per evaluated part; more are split at a breakpoint

uint64_t packKey(glm::i64vec3 b) {
    return uint64_t(b.x) | (uint64_t(b.y) << kKeyBits) | (uint64_t(b.z) << (2 * kKeyBits));
}

glm::i64vec3 unpackKey(uint64_t k) {
    return {int64_t(k & uint64_t(kKeyMax)), int64_t((k >> kKeyBits) & uint64_t(kKeyMax)),
            int64_t((k >> (2 * kKeyBits)) & uint64_t(kKeyMax))};
}

uint64_t mix(uint64_t k) {
    k ^= k >> 31;
    k *= 0x7fb5d329728ea185ull;
    k ^= k >> 27;
    k *= 0x81dadef4bc2dd44dull;
    return k ^ (k >> 33);
}

// The cells of one level near a part, by slot (lower corner = k w) over [k0, k0 + n).
struct LevelSlots {
    int32_t level = 0;
    double w = 1;
    glm::i64vec3 k0{0}, n{0};
    std::vector<double> values;  // NaN: no cell (or a NaN value, skipped as the samplers do)
    double at(glm::i64vec3 k) const {
        const glm::i64vec3 r = k - k0;
        if (r.x < 0 || r.y < 0 || r.z < 0 || r.x >= n.x || r.y >= n.y || r.z >= n.z) return NAN;
        return values[size_t((r.z * n.y + r.y) * n.x + r.x)];
    }
};

// The breakpoints of the reconstruction along axis a inside [lo, hi]: both ends and c - w, c,
// c + w of every slab of slots that holds a cell, sorted and unique.
std::vector<double> latticePlanes(const std::vector<LevelSlots>& slots, int a, double lo, double hi) {
    std::vector<double> out = {lo, hi};
    for (const LevelSlots& s : slots) {
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        for (int64_t i = 0; i < s.n[a]; ++i) {
            bool occupied = false;  // any cell in this slab of slots
            for (int64_t j = 0; j < s.n[b] && !occupied; ++j)
                for (int64_t k = 0; k < s.n[c] && !occupied; ++k) {
                    glm::i64vec3 r3;
                    r3[a] = i;
                    r3[b] = j;
                    r3[c] = k;
                    occupied = !std::isnan(s.values[size_t((r3.z * s.n.y + r3.y) * s.n.x + r3.x)]);
                }
            if (!occupied) continue;
            const double centre = (double(s.k0[a] + i) + 0.5) * s.w;
            for (double p : {centre - s.w, centre, centre + s.w})
                if (p > lo && p < hi) out.push_back(p);
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// f = sum(phi v) / sum(phi) (and its room) at every vertex of the lattice, folded into r; a
// lattice of more than kMaxVertices vertices is split along the axis with most planes.
void evaluateLattice(const std::vector<LevelSlots>& slots, std::vector<double> (&planes)[3], double relativeRoom,
                     ExactRange::Result& r) {
    struct Piece {
        std::vector<double> planes[3];
    };
    std::vector<Piece> pieces(1);
    for (int a = 0; a < 3; ++a) pieces[0].planes[a] = std::move(planes[a]);
    while (!pieces.empty()) {
        Piece piece = std::move(pieces.back());
        pieces.pop_back();
        const uint64_t count = uint64_t(piece.planes[0].size()) * piece.planes[1].size() * piece.planes[2].size();
        if (count > kMaxVertices) {
            int a = 0;
            for (int k = 1; k < 3; ++k)
                if (piece.planes[k].size() > piece.planes[a].size()) a = k;
            const size_t m = piece.planes[a].size() / 2;  // shared by both halves
            Piece left = piece, right = piece;
            left.planes[a].assign(piece.planes[a].begin(), piece.planes[a].begin() + ptrdiff_t(m) + 1);
            right.planes[a].assign(piece.planes[a].begin() + ptrdiff_t(m), piece.planes[a].end());
            pieces.push_back(std::move(left));
            pieces.push_back(std::move(right));
            continue;
        }
        for (double z : piece.planes[2])
            for (double y : piece.planes[1])
                for (double x : piece.planes[0]) {
                    const glm::dvec3 p(x, y, z);
                    double sumW = 0, sumWV = 0, sumWA = 0;  // sumWA: the same sum over |v|
                    for (const LevelSlots& s : slots) {
                        const glm::i64vec3 k0(glm::floor(p / s.w - 0.5));
                        for (int corner = 0; corner < 8; ++corner) {
                            const glm::i64vec3 k = k0 + glm::i64vec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
                            const double v = s.at(k);
                            if (std::isnan(v)) continue;
                            const glm::dvec3 c = (glm::dvec3(k) + 0.5) * s.w;
                            double phi = 1.0;
                            for (int a = 0; a < 3; ++a) phi *= std::max(0.0, 1.0 - std::abs(p[a] - c[a]) / s.w);
                            if (phi <= 0) continue;
                            sumW += phi;
                            sumWV += phi * v;
                            sumWA += phi * std::abs(v);
                        }
                    }
                    ++r.vertices;
                    if (!(sumW > 0)) continue;
                    const double f = sumWV / sumW, magnitude = sumWA / sumW;
                    r.roomLo = std::min(r.roomLo, f - relativeRoom * magnitude);
                    r.roomHi = std::max(r.roomHi, f + relativeRoom * magnitude);
                    if (f < r.lo) {
                        r.lo = f;
                        r.argLo = p;
                    }
                    if (f > r.hi) {
                        r.hi = f;
                        r.argHi = p;
                    }
                }
    }
}

}  // namespace

bool ExactRange::Blocks::contains(uint64_t key) const {
    for (uint64_t s = mix(key) & mask;; s = (s + 1) & mask) {
        if (slots[s] == key) return true;
        if (slots[s] == kEmpty) return false;
    }
}

ExactRange::ExactRange(const Model& model, const Field& field)
    : mModel(model), mField(field), mHash(model.cells), mCellOrder(model.cellOrder) {
    AMRVK_CHECK(field.values.size() == model.cells.size(), "exact range: ", field.values.size(), " values for ",
                model.cells.size(), " cells");
    mLevels = mHash.levels();
    AMRVK_CHECK(mLevels.size() <= 32, "exact range: more than 32 levels");
    if (model.cells.empty()) return;
    const ModelSummary s = summarize(model);
    mOrigin = s.bounds.lower;
    const glm::i64vec3 e = s.bounds.upper - s.bounds.lower;
    const int extentBits = int(std::bit_width(uint64_t(std::max({e.x, e.y, e.z, int64_t{1}}))));
    mBlocks.resize(mLevels.size());
    for (size_t li = 0; li < mLevels.size(); ++li) {
        const int32_t level = mLevels[li];
        const int32_t gFirst = std::max(level + 3, extentBits - kKeyBits);
        std::vector<uint64_t> keys;
        for (const Cell& c : model.cells)
            if (c.level == level) keys.push_back(packKey((glm::i64vec3(c.lower) - mOrigin) >> int64_t(gFirst)));
        for (int32_t g = gFirst;; ++g) {
            if (g > gFirst)
                for (uint64_t& k : keys) k = packKey(unpackKey(k) >> int64_t{1});
            std::sort(keys.begin(), keys.end());
            keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
            Blocks b;
            b.g = g;
            const uint64_t capacity = std::bit_ceil(std::max<uint64_t>(16, keys.size() * 2));
            b.slots.assign(capacity, kEmpty);
            b.mask = capacity - 1;
            for (uint64_t k : keys) {
                uint64_t slot = mix(k) & b.mask;
                while (b.slots[slot] != kEmpty) slot = (slot + 1) & b.mask;
                b.slots[slot] = k;
            }
            mBlocks[li].push_back(std::move(b));
            if (g >= extentBits) break;  // every block coordinate is 0 or 1 from here on
        }
    }
}

uint32_t ExactRange::levelsNear(glm::dvec3 lo, glm::dvec3 hi) const {
    uint32_t mask = 0;
    for (size_t li = 0; li < mLevels.size(); ++li) {
        const double w = double(cellWidth(mLevels[li]));
        // Lower corners of this level's cells whose support [lower - w/2, lower + 3w/2] meets the box.
        const glm::dvec3 a = glm::ceil(lo - 1.5 * w), b = glm::floor(hi + 0.5 * w);
        if (a.x > b.x || a.y > b.y || a.z > b.z) continue;
        const double span = std::max({b.x - a.x, b.y - a.y, b.z - a.z});
        const std::vector<Blocks>& tables = mBlocks[li];
        size_t t = 0;  // the finest table whose blocks make at most 3 per axis
        while (t + 1 < tables.size() && std::ldexp(1.0, tables[t].g) < span) ++t;
        const Blocks& table = tables[t];
        const double size = std::ldexp(1.0, table.g);
        glm::i64vec3 b0, b1;
        bool any = true;
        for (int k = 0; k < 3; ++k) {
            const double from = std::floor((a[k] - double(mOrigin[k])) / size);
            const double to = std::floor((b[k] - double(mOrigin[k])) / size);
            b0[k] = int64_t(std::clamp(from, 0.0, double(kKeyMax)));
            b1[k] = int64_t(std::clamp(to, 0.0, double(kKeyMax)));
            any = any && to >= 0 && from <= double(kKeyMax);
        }
        if (!any) continue;
        for (int64_t z = b0.z; z <= b1.z && !(mask >> li & 1u); ++z)
            for (int64_t y = b0.y; y <= b1.y && !(mask >> li & 1u); ++y)
                for (int64_t x = b0.x; x <= b1.x; ++x)
                    if (table.contains(packKey({x, y, z}))) {
                        mask |= 1u << li;
                        break;
                    }
    }
    return mask;
}

ExactRange::Result ExactRange::over(glm::dvec3 lo, glm::dvec3 hi, double relativeRoom) const {
    AMRVK_CHECK(mModel.cellOrder == mCellOrder, "internal: ", mModel.source,
                " was reordered after its exact range indexed it; build bricks first");
    Result r;
    if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z)) return r;
    part(lo, hi, relativeRoom, r);
    return r;
}

void ExactRange::part(glm::dvec3 lo, glm::dvec3 hi, double relativeRoom, Result& r) const {
    const uint32_t levels = levelsNear(lo, hi);
    if (levels == 0) return;
    const double finest = double(cellWidth(mLevels[size_t(std::countr_zero(levels))]));
    const glm::dvec3 ext = hi - lo;
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    if (ext[axis] > double(kMaxCellsPerAxis) * finest) {
        const double mid = 0.5 * (lo[axis] + hi[axis]);
        glm::dvec3 leftHi = hi, rightLo = lo;
        leftHi[axis] = mid;
        rightLo[axis] = mid;
        part(lo, leftHi, relativeRoom, r);
        part(rightLo, hi, relativeRoom, r);
        return;
    }
    // Gather every cell whose support reaches the part, per level, into dense slot arrays.
    std::vector<LevelSlots> slots;
    for (size_t li = 0; li < mLevels.size(); ++li) {
        if (!(levels >> li & 1u)) continue;
        LevelSlots s;
        s.level = mLevels[li];
        s.w = double(cellWidth(s.level));
        const glm::dvec3 k0 = glm::ceil((lo - 1.5 * s.w) / s.w), k1 = glm::floor((hi + 0.5 * s.w) / s.w);
        s.k0 = glm::i64vec3(k0);
        s.n = glm::max(glm::i64vec3(k1) - s.k0 + int64_t{1}, glm::i64vec3(0));
        s.values.assign(size_t(s.n.x * s.n.y * s.n.z), NAN);
        bool anyCell = false;
        for (int64_t z = 0; z < s.n.z; ++z)
            for (int64_t y = 0; y < s.n.y; ++y)
                for (int64_t x = 0; x < s.n.x; ++x) {
                    const glm::i64vec3 lower = (s.k0 + glm::i64vec3(x, y, z)) * int64_t(cellWidth(s.level));
                    if (glm::any(glm::lessThan(lower, glm::i64vec3(INT32_MIN))) ||
                        glm::any(glm::greaterThan(lower, glm::i64vec3(INT32_MAX))))
                        continue;
                    const uint32_t idx = mHash.find(glm::ivec3(lower), s.level);
                    if (idx == CellHash::kNone) continue;
                    const double v = double(mField.values[idx]);
                    if (std::isnan(v)) continue;
                    s.values[size_t((z * s.n.y + y) * s.n.x + x)] = v;
                    r.maxAbs = std::max(r.maxAbs, std::abs(v));
                    anyCell = true;
                }
        if (anyCell) slots.push_back(std::move(s));
    }
    if (slots.empty()) return;

    // The lattice: the part's faces and every breakpoint c - w, c, c + w strictly inside.
    std::vector<double> planes[3];
    for (int a = 0; a < 3; ++a) planes[a] = latticePlanes(slots, a, lo[a], hi[a]);
    evaluateLattice(slots, planes, relativeRoom, r);
}

}  // namespace amrvk::amr
