#include "amr/model.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>

#include "amr/cell_hash.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/strings.h"

namespace amrvk::amr {

std::string describeCell(const Cell& c) {
    return strCat("(lower ", c.lower.x, ",", c.lower.y, ",", c.lower.z, " level ", c.level, ")");
}

const Field& Model::field(std::string_view name) const {
    for (const Field& f : fields)
        if (f.name == name) return f;
    const std::string names = join(availableFields, ", ");
    AMRVK_CHECK(false, "unknown field '", name, "' in ", source, " (available: ", names.empty() ? "none" : names, ")");
    return fields.front();
}

const Field& Model::defaultField() const {
    AMRVK_CHECK(!fields.empty(), source, ": no field loaded");
    std::vector<std::string> names;
    for (const Field& f : fields) names.push_back(f.name);
    return fields[defaultFieldIndex(names)];
}

size_t defaultFieldIndex(const std::vector<std::string>& names) {
    for (size_t i = 0; i < names.size(); ++i) {
        std::string lower = names[i];
        for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (lower == "density" || lower == "dens" || lower == "rho" || lower == "gas_density") return i;
    }
    return 0;
}

namespace {
constexpr size_t kReduceChunks = 64;  // fixed, so sums are the same on every machine
}  // namespace

ModelSummary summarize(const Model& model) {
    ModelSummary s;
    if (model.cells.empty()) return s;
    struct Part {
        glm::i64vec3 lo{std::numeric_limits<int64_t>::max()}, hi{std::numeric_limits<int64_t>::min()};
        std::array<uint64_t, kMaxLevel + 1> perLevel{};
        double volume = 0;
    };
    const Part all = parallelReduce<Part>(
        0, model.cells.size(), kReduceChunks,
        [&](size_t from, size_t to) {
            Part p;
            for (size_t i = from; i < to; ++i) {
                const Cell& c = model.cells[i];
                const glm::i64vec3 l(c.lower);
                p.lo = glm::min(p.lo, l);
                p.hi = glm::max(p.hi, l + cellWidth(c.level));
                p.perLevel[size_t(c.level)]++;
                p.volume += cellVolume(c.level);
            }
            return p;
        },
        [](Part& a, Part&& b) {
            a.lo = glm::min(a.lo, b.lo);
            a.hi = glm::max(a.hi, b.hi);
            for (size_t l = 0; l < a.perLevel.size(); ++l) a.perLevel[l] += b.perLevel[l];
            a.volume += b.volume;
        });
    s.bounds = {all.lo, all.hi};
    s.leafVolume = all.volume;
    levelRange(all.perLevel, s.minLevel, s.maxLevel, s.cellsPerLevel);
    return s;
}

void levelRange(const std::array<uint64_t, kMaxLevel + 1>& perLevel, int& minLevel, int& maxLevel,
                std::vector<uint64_t>& cellsPerLevel) {
    minLevel = maxLevel = 0;
    bool any = false;
    for (int l = 0; l <= kMaxLevel; ++l) {
        if (perLevel[size_t(l)] == 0) continue;
        if (!any) minLevel = l;
        maxLevel = l;
        any = true;
    }
    cellsPerLevel.assign(perLevel.begin(), perLevel.begin() + maxLevel + 1);
}

FieldStats computeFieldStats(const Model& model, const Field& field) {
    FieldStats st;
    if (field.values.empty()) return st;
    struct Part {
        float lo = std::numeric_limits<float>::infinity(), hi = -std::numeric_limits<float>::infinity();
        double sum = 0, volume = 0;
    };
    const Part all = parallelReduce<Part>(
        0, field.values.size(), kReduceChunks,
        [&](size_t from, size_t to) {
            Part p;
            for (size_t i = from; i < to; ++i) {
                const float v = field.values[i];
                p.lo = std::min(p.lo, v);
                p.hi = std::max(p.hi, v);
                const double w = cellVolume(model.cells[i].level);
                p.sum += w * v;
                p.volume += w;
            }
            return p;
        },
        [](Part& a, Part&& b) {
            a.lo = std::min(a.lo, b.lo);
            a.hi = std::max(a.hi, b.hi);
            a.sum += b.sum;
            a.volume += b.volume;
        });
    st.minValue = all.lo;
    st.maxValue = all.hi;
    st.volumeWeightedMean = all.volume > 0 ? all.sum / all.volume : 0.0;
    return st;
}

NanPolicy parseNanPolicy(std::string_view text) {
    if (text == "reject") return NanPolicy::Reject;
    if (text == "drop") return NanPolicy::Drop;
    AMRVK_CHECK(false, "unknown NaN policy '", text, "' (expected reject or drop)");
    return NanPolicy::Reject;
}

const char* nanPolicyName(NanPolicy policy) { return policy == NanPolicy::Drop ? "drop" : "reject"; }

void applyNanPolicy(Model& model, NanPolicy policy) {
    // The common case, every value finite, found on every core; the rest is serial.
    constexpr size_t kChunks = 64;
    const bool allFinite = std::all_of(model.fields.begin(), model.fields.end(), [](const Field& f) {
        return parallelReduce<bool>(
            0, f.values.size(), kChunks,
            [&](size_t lo, size_t hi) {
                return std::all_of(f.values.begin() + std::ptrdiff_t(lo), f.values.begin() + std::ptrdiff_t(hi),
                                   [](float v) { return std::isfinite(v); });
            },
            [](bool& a, bool b) { a = a && b; });
    });
    if (allFinite) return;
    std::vector<uint8_t> bad;
    uint64_t badCount = 0;
    for (const Field& f : model.fields) {
        for (size_t i = 0; i < f.values.size(); ++i) {
            if (std::isfinite(f.values[i])) continue;
            AMRVK_CHECK(policy != NanPolicy::Reject, model.source, ": field '", f.name,
                        "' has a non-finite value (", f.values[i], ") at cell ", i,
                        " (use --nan drop to treat such cells as empty)");
            if (bad.empty()) bad.assign(model.cells.size(), 0);
            badCount += bad[i] == 0;
            bad[i] = 1;
        }
    }
    if (badCount == 0) return;
    size_t out = 0;
    for (size_t i = 0; i < model.cells.size(); ++i) {
        if (bad[i]) continue;
        model.cells.set(out, model.cells[i]);
        for (Field& f : model.fields) f.values[out] = f.values[i];
        ++out;
    }
    model.cells.resize(out);
    for (Field& f : model.fields) f.values.resize(out);
    model.attributes.emplace_back("droppedNonFiniteCells", std::to_string(badCount));
}

FieldScale parseFieldScale(std::string_view text) {
    if (text == "linear") return FieldScale::Linear;
    if (text == "log") return FieldScale::Log;
    if (text == "auto") return FieldScale::Auto;
    AMRVK_CHECK(false, "--scale: '", text, "' is not auto, linear or log");
    return FieldScale::Linear;
}

const char* fieldScaleName(FieldScale scale) {
    return scale == FieldScale::Log ? "log" : scale == FieldScale::Auto ? "auto" : "linear";
}

FieldScale autoScaleOf(float smallest, float largest) {
    return smallest > 0 && double(largest) >= kAutoLogSpan * double(smallest) ? FieldScale::Log : FieldScale::Linear;
}

namespace {
// Chunks for the per-value passes over a field (min, max, log): fixed, so results do not depend on
// the thread count; fields below kParallelValues are done in one.
constexpr size_t kValueChunks = 64;
constexpr size_t kParallelValues = size_t{1} << 16;
size_t valueChunks(size_t n) { return n < kParallelValues ? 1 : kValueChunks; }
}  // namespace

void FiniteExtremes::add(std::span<const float> values) {
    // Order-independent (min and max), so any chunking gives the same extremes.
    const FiniteExtremes part = parallelReduce<FiniteExtremes>(
        0, values.size(), valueChunks(values.size()),
        [&](size_t b, size_t e) {
            FiniteExtremes x;
            for (size_t i = b; i < e; ++i)
                if (const float v = values[i]; std::isfinite(v)) {
                    x.lo = std::min(x.lo, v);
                    x.hi = std::max(x.hi, v);
                }
            return x;
        },
        [](FiniteExtremes& a, FiniteExtremes&& o) {
            a.lo = std::min(a.lo, o.lo);
            a.hi = std::max(a.hi, o.hi);
        });
    lo = std::min(lo, part.lo);
    hi = std::max(hi, part.hi);
}

FieldScale FiniteExtremes::autoScale() const { return lo <= hi ? autoScaleOf(lo, hi) : FieldScale::Linear; }

FieldScale autoScaleOf(std::span<const float> values) {
    FiniteExtremes e;
    e.add(values);
    return e.autoScale();
}

FieldScale scaleOf(const Model& model) {
    for (const auto& [key, value] : model.attributes)
        if (key == "scale" && value == "log10") return FieldScale::Log;
    return FieldScale::Linear;
}

float smallestPositive(std::span<const float> values) {
    auto smaller = [](float best, float v) { return v > 0 && std::isfinite(v) && (best == 0 || v < best) ? v : best; };
    return parallelReduce<float>(
        0, values.size(), valueChunks(values.size()),
        [&](size_t b, size_t e) {
            float best = 0;
            for (size_t i = b; i < e; ++i) best = smaller(best, values[i]);
            return best;
        },
        [&](float& a, float&& o) { a = smaller(a, o); });
}

ScaleReport applyFieldScale(Model& model, FieldScale scale, double floor) {
    constexpr double kLog10Of2 = 0.30102999566398119521;
    ScaleReport first;
    AMRVK_CHECK(scale != FieldScale::Auto, "internal: the auto scale is resolved before it is applied");
    if (scale == FieldScale::Linear) return first;
    AMRVK_CHECK(floor >= 0 && std::isfinite(floor), "--log-floor: ", floor, " must be positive");
    for (size_t f = 0; f < model.fields.size(); ++f) {
        Field& field = model.fields[f];
        const double lo = floor > 0 ? floor : double(smallestPositive(field.values));
        AMRVK_CHECK(lo > 0, model.source, ": field '", field.name,
                    "' has no positive value: log scale needs one (or --log-floor)");
        std::span<float> values(field.values);
        const uint64_t floored = parallelReduce<uint64_t>(
            0, values.size(), valueChunks(values.size()),
            [&](size_t b, size_t e) {
                uint64_t n = 0;
                for (size_t i = b; i < e; ++i) {
                    float& v = values[i];
                    if (std::isnan(v)) continue;
                    if (!(double(v) >= lo)) ++n;  // <= 0, or below an explicit floor
                    // log10 as log2 times log10(2): glibc's log2 is about 3x faster than its
                    // log10 (10^8 cells: 0.3 s of both cores), and within 2 double ulps of it,
                    // so the float differs from float(log10) about once in 10^8 values, by 1 ulp.
                    v = float(std::log2(std::max(double(v), lo)) * kLog10Of2);
                }
                return n;
            },
            [](uint64_t& a, uint64_t&& o) { a += o; });
        if (f == 0) first = {floored, lo};
    }
    model.attributes.emplace_back("scale", "log10");
    if (first.floored > 0)
        model.attributes.emplace_back("logFloored", strCat(first.floored, " cells at ", first.floor));
    return first;
}

namespace {
// What can be wrong with a cell on its own (level, alignment, the int32 voxel range): found without
// building a string, so that the check of 10^8 cells costs a few ns each.
enum class CellFault { None, Level, Alignment, Range };
CellFault cellFault(const Cell& c) {
    if (c.level < 0 || c.level > kMaxLevel) return CellFault::Level;
    const int64_t w = cellWidth(c.level);
    if (((c.lower.x | c.lower.y | c.lower.z) & static_cast<int32_t>(w - 1)) != 0) return CellFault::Alignment;
    if (int64_t{c.lower.x} + w > INT32_MAX || int64_t{c.lower.y} + w > INT32_MAX || int64_t{c.lower.z} + w > INT32_MAX)
        return CellFault::Range;
    return CellFault::None;
}
// The fault in words, or "".
std::string cellProblem(const Cell& c) {
    switch (cellFault(c)) {
        case CellFault::Level: return strCat("has a level outside [0, ", kMaxLevel, "]");
        case CellFault::Alignment: return strCat("is not aligned to its width ", cellWidth(c.level));
        case CellFault::Range: return "reaches past 2^31-1";
        case CellFault::None: break;
    }
    return {};
}
}  // namespace

void validateCells(const Model& model) {
    const std::string& src = model.source;
    if (model.cells.empty())
        for (const auto& [key, value] : model.attributes)
            AMRVK_CHECK(key != "droppedNonFiniteCells", src, ": every one of its ", value,
                        " cells has a non-finite value, and --nan drop dropped them all");
    AMRVK_CHECK(!model.cells.empty(), src, ": no cells");
    for (int a = 0; a < 3; ++a) {
        const double size = model.voxelToWorld.scale[a], origin = model.voxelToWorld.origin[a];
        AMRVK_CHECK(size >= kMinCellSize && size <= kMaxWorldCoordinate, src, ": a finest cell is ", formatDouble(size),
                    " wide on axis ", a, " (amrvk's world coordinates hold cell sizes in [", formatDouble(kMinCellSize),
                    ", ", formatDouble(kMaxWorldCoordinate), "])");
        AMRVK_CHECK(std::abs(origin) <= kMaxWorldCoordinate, src, ": the origin is ", formatDouble(origin), " on axis ",
                    a, " (amrvk's world coordinates hold at most ", formatDouble(kMaxWorldCoordinate),
                    " in magnitude)");
    }
    for (const Field& f : model.fields)
        AMRVK_CHECK(f.values.size() == model.cells.size(), src, ": field '", f.name, "' has ",
                    f.values.size(), " values but there are ", model.cells.size(), " cells");
    // Each chunk finds its first bad cell; the lowest is reported, whatever the schedule.
    constexpr size_t kChunks = 64;
    const size_t n = model.cells.size();
    std::vector<size_t> firstBad(kChunks, SIZE_MAX);
    parallelFor(0, kChunks, [&](size_t k) {
        for (size_t i = k * n / kChunks; i < (k + 1) * n / kChunks; ++i)
            if (cellFault(model.cells[i]) != CellFault::None) {
                firstBad[k] = i;
                return;
            }
    });
    for (size_t i : firstBad)
        AMRVK_CHECK(i == SIZE_MAX, src, ": cell ", i, " ", describeCell(model.cells[i]), " ",
                    cellProblem(model.cells[i]));
}

void validate(const Model& model) {
    validateCells(model);
    const std::string& src = model.source;
    CellHash hash(model.cells);
    if (hash.firstDuplicate() != CellHash::kNone)
        AMRVK_CHECK(false, src, ": overlapping cells: cell ", hash.firstDuplicate(), " ",
                    describeCell(model.cells[hash.firstDuplicate()]), " duplicates cell ",
                    hash.duplicateOf());
    const auto& levels = hash.levels();
    for (size_t i = 0; i < model.cells.size(); ++i) {
        const Cell& c = model.cells[i];
        for (int32_t L : levels) {
            if (L <= c.level) continue;
            glm::ivec3 parent = c.lower & glm::ivec3(~static_cast<int32_t>(cellWidth(L) - 1));
            uint32_t j = hash.find(parent, L);
            AMRVK_CHECK(j == CellHash::kNone, src, ": overlapping cells: cell ", i, " ",
                        describeCell(c), " lies inside cell ", j, " ",
                        describeCell(model.cells[j]));
        }
    }
}

}  // namespace amrvk::amr
