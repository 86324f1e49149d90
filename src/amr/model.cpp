#include "amr/model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "amr/cell_hash.h"
#include "core/error.h"

namespace amrvk::amr {

namespace {
std::string describeCell(const Cell& c) {
    return strCat("(lower ", c.lower.x, ",", c.lower.y, ",", c.lower.z, " level ", c.level, ")");
}
std::string listNames(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? "none" : out;
}
}  // namespace

const Field& Model::field(std::string_view name) const {
    for (const Field& f : fields)
        if (f.name == name) return f;
    AMRVK_CHECK(false, "unknown field '", name, "' in ", source, " (available: ",
                listNames(availableFields.empty() ? std::vector<std::string>{} : availableFields),
                ")");
    return fields.front();
}

const Field& Model::defaultField() const {
    AMRVK_CHECK(!fields.empty(), source, ": no field loaded");
    return fields.front();
}

ModelSummary summarize(const Model& model) {
    ModelSummary s;
    if (model.cells.empty()) return s;
    glm::i64vec3 lo(std::numeric_limits<int64_t>::max());
    glm::i64vec3 hi(std::numeric_limits<int64_t>::min());
    int minL = kMaxLevel + 1, maxL = -1;
    std::vector<uint64_t> perLevel(64, 0);
    for (const Cell& c : model.cells) {
        int64_t w = cellWidth(c.level);
        glm::i64vec3 l(c.lower);
        lo = glm::min(lo, l);
        hi = glm::max(hi, l + w);
        minL = std::min(minL, c.level);
        maxL = std::max(maxL, c.level);
        perLevel[static_cast<size_t>(c.level)]++;
        s.leafVolume += std::ldexp(1.0, 3 * c.level);
    }
    s.bounds = {lo, hi};
    s.minLevel = minL;
    s.maxLevel = maxL;
    perLevel.resize(static_cast<size_t>(maxL) + 1);
    s.cellsPerLevel = std::move(perLevel);
    return s;
}

FieldStats computeFieldStats(const Model& model, const Field& field) {
    FieldStats st;
    if (field.values.empty()) return st;
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    double sum = 0, vol = 0;
    for (size_t i = 0; i < field.values.size(); ++i) {
        float v = field.values[i];
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        double w = std::ldexp(1.0, 3 * model.cells[i].level);
        sum += w * v;
        vol += w;
    }
    st.minValue = lo;
    st.maxValue = hi;
    st.volumeWeightedMean = vol > 0 ? sum / vol : 0.0;
    return st;
}

NanPolicy parseNanPolicy(std::string_view text) {
    if (text == "reject") return NanPolicy::Reject;
    if (text == "drop") return NanPolicy::Drop;
    AMRVK_CHECK(false, "unknown NaN policy '", text, "' (expected reject or drop)");
    return NanPolicy::Reject;
}

void applyNanPolicy(Model& model, NanPolicy policy) {
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
        model.cells[out] = model.cells[i];
        for (Field& f : model.fields) f.values[out] = f.values[i];
        ++out;
    }
    model.cells.resize(out);
    for (Field& f : model.fields) f.values.resize(out);
    model.attributes.emplace_back("droppedNonFiniteCells", std::to_string(badCount));
}

void validate(const Model& model) {
    const std::string& src = model.source;
    AMRVK_CHECK(!model.cells.empty(), src, ": no cells");
    for (const Field& f : model.fields)
        AMRVK_CHECK(f.values.size() == model.cells.size(), src, ": field '", f.name, "' has ",
                    f.values.size(), " values but there are ", model.cells.size(), " cells");
    for (size_t i = 0; i < model.cells.size(); ++i) {
        const Cell& c = model.cells[i];
        AMRVK_CHECK(c.level >= 0 && c.level <= kMaxLevel, src, ": cell ", i, " ",
                    describeCell(c), " has a level outside [0, ", kMaxLevel, "]");
        int32_t mask = static_cast<int32_t>(cellWidth(c.level) - 1);
        AMRVK_CHECK(((c.lower.x | c.lower.y | c.lower.z) & mask) == 0, src, ": cell ", i, " ",
                    describeCell(c), " is not aligned to its width ", mask + 1);
        AMRVK_CHECK(int64_t{c.lower.x} + cellWidth(c.level) <= INT32_MAX &&
                        int64_t{c.lower.y} + cellWidth(c.level) <= INT32_MAX &&
                        int64_t{c.lower.z} + cellWidth(c.level) <= INT32_MAX,
                    src, ": cell ", i, " ", describeCell(c), " reaches past 2^31-1");
    }
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
