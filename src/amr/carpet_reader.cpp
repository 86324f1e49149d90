// Carpet (Cactus) HDF5 files (shared/data/amr/FORMATS.md 4.5): one (nz, ny, nx) dataset per
// variable, iteration, timelevel, refinement level and component, named
// "THORN::var it=N tl=T [m=M ]rl=L[ c=C]", values at the VERTICES of a box-in-box hierarchy
// (refinement factors powers of two). Each dataset's "active" attribute is the bboxset of the
// points it owns, in the global index space of the finest level (stride = that level's spacing).
//
// Vertices onto cells (docs/formats.md "Carpet"): on each level, the cell between 8 neighbouring
// active vertices (of any of its components) takes the mean of their 8 values (trilinear
// interpolation at its centre). The cells of a level then nest exactly inside those of the next
// coarser one (a vertex-centred dual cell would not). A coarser cell all of whose children are
// cells of the finer level is replaced by them; finer cells under any other coarser cell are
// dropped, so the leaves never overlap and tile rl0's cells.
#include <hdf5.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <string_view>
#include <utility>

#include "amr/block_structured.h"
#include "amr/hdf5_util.h"
#include "amr/readers.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/strings.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

namespace {

constexpr const char* kGlobalGroup = "Parameters and Global Attributes";
constexpr size_t kMaxLinks = size_t(1) << 20;  // root entries listed at most (a damaged file)

// "THORN::var it=N tl=T [m=M ]rl=L[ c=C]"; rl and c are 0 when absent (one level / component).
struct DatasetKey {
    std::string var;
    int64_t it = 0;
    int tl = 0, m = 0, rl = 0, c = 0;
};

bool parseNumber(const std::string& s, int64_t& out) {
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size() && out >= 0 && out <= kMaxIndex;
}

// Parsed by hand from the end (a regex recursed per character and overflowed the stack on a
// name of 30,000 characters): the var is everything before the last " it=".
// With `file`, a name of this form whose number is beyond kMaxIndex is an error naming it (it was
// skipped: a level of rl=2147483648 was left out, and iterations above 2^30 - 1 ignored).
bool parseDatasetKey(const std::string& name, DatasetKey& key, const std::string* file = nullptr) {
    const size_t at = name.rfind(" it=");
    if (at == std::string::npos || at == 0) return false;
    // The fields after the var, in their fixed order; it and tl required.
    static constexpr std::string_view kFields[] = {"it", "tl", "m", "rl", "c"};
    int64_t v[5] = {0, 0, 0, 0, 0};
    std::string_view rest = std::string_view(name).substr(at + 1);
    size_t field = 0;
    while (!rest.empty()) {
        const size_t end = std::min(rest.find(' '), rest.size());
        const std::string_view token = rest.substr(0, end);
        const size_t eq = token.find('=');
        if (eq == std::string_view::npos) return false;
        const std::string_view k = token.substr(0, eq);
        while (field < 5 && kFields[field] != k) {
            if (field < 2) return false;  // it and tl come first
            ++field;
        }
        if (field == 5) return false;
        const std::string digits(token.substr(eq + 1));
        if (!parseNumber(digits, v[field])) {
            AMRVK_CHECK(!file || digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos, *file,
                        ": '", elide(name, 120), "': ", k, "=", elide(digits), " is beyond this reader's limit of ",
                        kMaxIndex);
            return false;
        }
        ++field;
        if (end == rest.size()) break;
        rest = rest.substr(end + 1);
        if (rest.empty()) return false;  // a trailing space
    }
    if (field < 2) return false;
    key = {name.substr(0, at), v[0], int(v[1]), int(v[2]), int(v[3]), int(v[4])};
    return true;
}

herr_t collectName(hid_t, const char* name, const H5L_info_t*, void* data) {
    auto* names = static_cast<std::vector<std::string>*>(data);
    names->emplace_back(name);
    return names->size() >= kMaxLinks ? 1 : 0;
}

// HDF5 access for one Carpet file; every error names the file and the object.
class CarpetFile {
public:
    explicit CarpetFile(const fs::path& path) : mName(path.string()), mFile(openHdf5ReadOnly(path)) {}
    const std::string& name() const { return mName; }
    hid_t root() const { return mFile.get(); }

    std::vector<std::string> rootNames() const {
        std::vector<std::string> names;
        hsize_t idx = 0;
        AMRVK_CHECK(H5Literate(root(), H5_INDEX_NAME, H5_ITER_NATIVE, &idx, collectName, &names) >= 0, mName,
                    ": cannot list the root group");
        return names;
    }
    H5Id openDataset(const std::string& name) const {
        H5Id d(H5Dopen2(root(), name.c_str(), H5P_DEFAULT), H5Dclose);
        AMRVK_CHECK(d.valid(), mName, ": cannot open dataset '", name, "'");
        return d;
    }
    // Extent of a dataset, slowest axis first.
    std::vector<hsize_t> dims(hid_t dataset) const {
        H5Id space(H5Dget_space(dataset), H5Sclose);
        const int n = H5Sget_simple_extent_ndims(space.get());
        if (n < 0 || n > 8) return {};
        std::vector<hsize_t> d(static_cast<size_t>(n));
        H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
        return d;
    }
    // Numeric attribute of exactly `count` values, converted to T (int or double).
    template <typename T>
    std::vector<T> readNumbers(hid_t obj, const std::string& objName, const char* attr, size_t count) const {
        H5Id a(H5Aopen(obj, attr, H5P_DEFAULT), H5Aclose);
        AMRVK_CHECK(a.valid(), mName, ": '", objName, "' has no attribute '", attr, "'");
        H5Id space(H5Aget_space(a.get()), H5Sclose);
        H5Id type(H5Aget_type(a.get()), H5Tclose);
        const H5T_class_t cls = H5Tget_class(type.get());
        AMRVK_CHECK((cls == H5T_INTEGER || cls == H5T_FLOAT) &&
                        H5Sget_simple_extent_npoints(space.get()) == hssize_t(count),
                    mName, ": attribute '", attr, "' of '", objName, "' is not ", count, " number(s)");
        std::vector<T> v(count);
        AMRVK_CHECK(H5Aread(a.get(), std::is_same_v<T, int> ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE, v.data()) >= 0,
                    mName, ": cannot read attribute '", attr, "' of '", objName, "'");
        return v;
    }
    std::string readString(hid_t obj, const std::string& objName, const char* attr) const {
        H5Id a(H5Aopen(obj, attr, H5P_DEFAULT), H5Aclose);
        AMRVK_CHECK(a.valid(), mName, ": '", objName, "' has no attribute '", attr, "'");
        H5Id type(H5Aget_type(a.get()), H5Tclose);
        H5Id space(H5Aget_space(a.get()), H5Sclose);
        AMRVK_CHECK(H5Tget_class(type.get()) == H5T_STRING && H5Tis_variable_str(type.get()) == 0 &&
                        H5Sget_simple_extent_npoints(space.get()) == 1,
                    mName, ": attribute '", attr, "' of '", objName, "' is not a fixed-length string");
        const size_t n = H5Tget_size(type.get());
        AMRVK_CHECK(n <= (size_t(1) << 20), mName, ": attribute '", attr, "' of '", objName, "' is ", n,
                    " bytes long (limit 1 MiB)");
        std::string out(n, '\0');
        AMRVK_CHECK(H5Aread(a.get(), type.get(), out.data()) >= 0, mName, ": cannot read attribute '", attr, "'");
        out.resize(strnlen(out.c_str(), n));
        return out;
    }

private:
    std::string mName;
    H5Id mFile;
};

// An inclusive box of vertex indices in one level's index space.
struct VertexBox {
    glm::ivec3 lo{0}, hi{0};
};

// One dataset of the chosen iteration and timelevel: a component of a refinement level.
struct Patch {
    std::string dataset;
    int rl = 0;
    glm::ivec3 shape{0};    // vertices per axis (x, y, z)
    glm::ivec3 iorigin{0};  // level index of element [0,0,0]
    glm::dvec3 origin{0.0}, delta{0.0};
    int stride = 0;  // this level's spacing in finest-level index units
    std::vector<VertexBox> active;
    double time = 0;
};

int64_t parseIndex(const std::string& s, const std::string& what) {
    int64_t v = 0;
    const bool neg = !s.empty() && s[0] == '-';
    AMRVK_CHECK(parseNumber(neg ? s.substr(1) : s, v), what, ": '", elide(s), "' is not an index in [-", kMaxIndex,
                ", ", kMaxIndex, "]");
    return neg ? -v : v;
}

// The boxes of an "active" bboxset "bboxset<...>(set<bbox>:{([lo]:[hi]:[stride]/...),...},...)",
// in the level's own index (global index / stride); `stride` is the level's spacing.
// "[a,b,c]" at text[at] with integers (optionally negative): their texts, and `at` moved past it.
bool scanTriple(std::string_view text, size_t& at, bool allowNegative, std::string_view (&out)[3]) {
    size_t i = at;
    if (i >= text.size() || text[i++] != '[') return false;
    for (int k = 0; k < 3; ++k) {
        const size_t start = i;
        if (allowNegative && i < text.size() && text[i] == '-') ++i;
        const size_t digits = i;
        while (i < text.size() && text[i] >= '0' && text[i] <= '9') ++i;
        if (i == digits || i >= text.size() || text[i] != (k < 2 ? ',' : ']')) return false;
        out[k] = text.substr(start, i - start);
        ++i;
    }
    at = i;
    return true;
}

// The boxes of an "active" bboxset "bboxset<...>(set<bbox>:{([lo]:[hi]:[stride]/...),...},...)",
// in the level's own index (global index / stride); `stride` is the level's spacing. Scanned by
// hand, in one pass (a regex recursed per character and overflowed the stack on long numbers).
std::vector<VertexBox> parseActive(const std::string& text, int& stride, const std::string& what) {
    AMRVK_CHECK(text.rfind("bboxset<", 0) == 0 && text.size() < (size_t(1) << 20), what, ": '",
                text.substr(0, 60), "' is not a Carpet bboxset");
    std::vector<VertexBox> out;
    const std::string_view all(text);
    for (size_t from = all.find("(["); from != std::string_view::npos; from = all.find("([", from + 1)) {
        std::string_view lo[3], hi[3], step[3];
        size_t at = from + 1;
        if (!scanTriple(all, at, true, lo) || at >= all.size() || all[at++] != ':' || !scanTriple(all, at, true, hi) ||
            at >= all.size() || all[at++] != ':' || !scanTriple(all, at, false, step))
            continue;
        int64_t v[9];
        for (int i = 0; i < 3; ++i) {
            v[i] = parseIndex(std::string(lo[i]), what);
            v[i + 3] = parseIndex(std::string(hi[i]), what);
            v[i + 6] = parseIndex(std::string(step[i]), what);
        }
        AMRVK_CHECK(v[6] > 0 && v[6] == v[7] && v[6] == v[8] && std::has_single_bit(uint64_t(v[6])), what,
                    ": stride [", v[6], ",", v[7], ",", v[8], "] is not one power of two on every axis");
        AMRVK_CHECK(stride == 0 || stride == v[6], what, ": boxes of strides ", stride, " and ", v[6]);
        stride = int(v[6]);
        VertexBox b;
        for (int a = 0; a < 3; ++a) {
            AMRVK_CHECK(v[a] % stride == 0 && v[a + 3] % stride == 0 && v[a] <= v[a + 3], what, ": box [", v[0], ",",
                        v[1], ",", v[2], "]:[", v[3], ",", v[4], ",", v[5], "] is empty or not on stride ", stride);
            b.lo[a] = int(v[a] / stride);
            b.hi[a] = int(v[a + 3] / stride);
        }
        out.push_back(b);
    }
    return out;
}

Patch readPatch(const CarpetFile& file, const std::string& dataset, int rl) {
    const std::string what = strCat(file.name(), ": '", dataset, "'");
    H5Id d = file.openDataset(dataset);
    const std::vector<hsize_t> dims = file.dims(d.get());
    AMRVK_CHECK(dims.size() == 3, what, " is not a 3-D dataset (", dims.size(), " axes)");
    Patch p{.dataset = dataset, .rl = rl};
    for (int a = 0; a < 3; ++a) {
        AMRVK_CHECK(dims[size_t(2 - a)] >= 1 && dims[size_t(2 - a)] <= hsize_t(kMaxIndex), what, " has ",
                    dims[size_t(2 - a)], " points on axis ", a, " (limit ", kMaxIndex, ")");
        p.shape[a] = int(dims[size_t(2 - a)]);
    }
    const int level = file.readNumbers<int>(d.get(), dataset, "level", 1)[0];
    AMRVK_CHECK(level == rl, what, " has attribute level ", level, " but its name says rl=", rl);
    const std::vector<int> io = file.readNumbers<int>(d.get(), dataset, "iorigin", 3);
    const std::vector<int> ioff = file.readNumbers<int>(d.get(), dataset, "ioffset", 3);
    const std::vector<double> origin = file.readNumbers<double>(d.get(), dataset, "origin", 3);
    const std::vector<double> delta = file.readNumbers<double>(d.get(), dataset, "delta", 3);
    p.time = file.readNumbers<double>(d.get(), dataset, "time", 1)[0];
    for (int a = 0; a < 3; ++a) {
        p.iorigin[a] = int(checkedInRange(io[size_t(a)], -kMaxIndex, kMaxIndex - p.shape[a], what + " iorigin"));
        AMRVK_CHECK(ioff[size_t(a)] == 0, what, " has ioffset ", ioff[size_t(a)],
                    " (only vertex-centred Carpet grids, ioffset 0, are supported)");
        AMRVK_CHECK(std::isfinite(origin[size_t(a)]) && std::isfinite(delta[size_t(a)]) && delta[size_t(a)] > 0,
                    what, " has origin ", origin[size_t(a)], " and delta ", delta[size_t(a)],
                    " (need finite values and delta > 0)");
        p.origin[a] = origin[size_t(a)];
        p.delta[a] = delta[size_t(a)];
    }
    p.active = parseActive(file.readString(d.get(), dataset, "active"), p.stride, what + " attribute active");
    if (p.stride == 0) p.stride = 1 << 30;  // no active point: checked against the level's stride later
    for (const VertexBox& b : p.active)
        for (int a = 0; a < 3; ++a)
            AMRVK_CHECK(b.lo[a] >= p.iorigin[a] && b.hi[a] < p.iorigin[a] + p.shape[a], what, " owns points ",
                        b.lo[a], "..", b.hi[a], " on axis ", a, " outside its ", p.shape[a], " points from ",
                        p.iorigin[a]);
    return p;
}

// All of a dataset's values, x fastest, as double.
std::vector<double> readValues(const CarpetFile& file, const Patch& p) {
    const std::string what = strCat(file.name(), ": '", p.dataset, "'");
    const uint64_t n = checkedProduct({uint64_t(p.shape.x), uint64_t(p.shape.y), uint64_t(p.shape.z)}, what);
    checkAllocation(checkedProduct({n, sizeof(double)}, what), what);
    H5Id d = file.openDataset(p.dataset);
    H5Id type(H5Dget_type(d.get()), H5Tclose);
    const H5T_class_t cls = H5Tget_class(type.get());
    AMRVK_CHECK(cls == H5T_FLOAT || cls == H5T_INTEGER, what, " does not hold numbers");
    std::vector<double> v(n);
    AMRVK_CHECK(H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) >= 0, what,
                ": cannot read its values (truncated or damaged file?)");
    return v;
}

// The 3-D datasets of the file by variable: key and name, for every iteration and timelevel.
std::map<std::string, std::vector<std::pair<DatasetKey, std::string>>> gridDatasets(const CarpetFile& file) {
    std::map<std::string, std::vector<std::pair<DatasetKey, std::string>>> out;
    std::map<std::string, std::pair<std::string, size_t>> flat;  // var -> a dataset of other than 3 axes
    for (const std::string& name : file.rootNames()) {
        DatasetKey key;
        if (!parseDatasetKey(name, key, &file.name())) continue;
        H5Id d(H5Dopen2(file.root(), name.c_str(), H5P_DEFAULT), H5Dclose);
        if (!d.valid()) continue;  // groups
        const size_t axes = file.dims(d.get()).size();
        if (axes != 3) {  // grid scalars and arrays
            flat.emplace(key.var, std::make_pair(name, axes));
            continue;
        }
        AMRVK_CHECK(key.m == 0, file.name(), ": '", name, "' is on map ", key.m,
                    " (multi-patch Carpet files are not supported)");
        out[key.var].emplace_back(key, name);
    }
    // A variable of 3-D levels with a level of other rank (a 2-D rl=2 was called a gap).
    for (const auto& [var, dataset] : flat)
        AMRVK_CHECK(!out.count(var), file.name(), ": '", elide(dataset.first, 120), "' has ", dataset.second,
                    " axes where the other datasets of '", elide(var, 120), "' have 3 (amrvk reads 3-D Carpet grids)");
    return out;
}


// The datasets of `var` at the latest iteration that has a refinement level 0 (coarser levels
// are not written at every iteration), timelevel 0 (the current one), by level: (component, name).
std::map<int, std::vector<std::pair<int, std::string>>> latestLevels(
    const std::string& source, const std::string& var, const std::vector<std::pair<DatasetKey, std::string>>& all,
    int64_t& iteration) {
    iteration = -1;
    for (const auto& [key, name] : all)
        if (key.tl == 0 && key.rl == 0) iteration = std::max(iteration, key.it);
    AMRVK_CHECK(iteration >= 0, source, ": '", var, "' has no dataset of timelevel 0 on refinement level 0");
    std::map<int, std::vector<std::pair<int, std::string>>> levels;
    for (const auto& [key, name] : all)
        if (key.tl == 0 && key.it == iteration) levels[key.rl].emplace_back(key.c, name);
    AMRVK_CHECK(int(levels.size()) <= kMaxLevel + 1 && levels.rbegin()->first == int(levels.size()) - 1, source,
                ": '", var, "' it=", iteration, " has refinement levels up to rl=", levels.rbegin()->first, " but only ",
                levels.size(), " of them (expected rl=0.. without gaps, at most ", kMaxLevel + 1, ")");
    for (auto& [rl, comps] : levels) std::sort(comps.begin(), comps.end());
    return levels;
}

// Each level's spacing in finest-level index units, and the ratios between them (level l -> l+1).
std::vector<int> levelStrides(const std::string& source, const std::vector<std::vector<Patch>>& levels,
                              std::vector<int>& ratios) {
    std::vector<int> strides;
    for (size_t l = 0; l < levels.size(); ++l) {
        int s = 0;
        for (const Patch& p : levels[l])
            if (!p.active.empty()) {
                AMRVK_CHECK(s == 0 || s == p.stride, source, ": rl=", l, " has components of strides ", s, " and ",
                            p.stride);
                s = p.stride;
            }
        AMRVK_CHECK(s != 0, source, ": rl=", l, " owns no point (every component's active set is empty)");
        if (l > 0) {
            const int prev = strides.back();
            AMRVK_CHECK(prev > s && prev % s == 0, source, ": rl=", l, " has stride ", s, ", rl=", l - 1, " stride ",
                        prev, " (each level must refine the one before by a power of two)");
            ratios.push_back(prev / s);
        }
        strides.push_back(s);
    }
    return strides;
}

// Checks that every component's origin and delta agree with the first component of rl=0 (the
// integer index spaces and the coordinates describe one grid).
void checkGeometry(const std::string& source, const std::vector<std::vector<Patch>>& levels,
                   const std::vector<int>& strides) {
    const Patch& ref = levels[0][0];
    for (size_t l = 0; l < levels.size(); ++l)
        for (const Patch& p : levels[l])
            for (int a = 0; a < 3; ++a) {
                const double step = double(strides[l]) / strides[0];
                const double delta = ref.delta[a] * step;
                const double origin = ref.origin[a] + (p.iorigin[a] * step - ref.iorigin[a]) * ref.delta[a];
                AMRVK_CHECK(std::abs(p.delta[a] - delta) <= 1e-6 * delta &&
                                std::abs(p.origin[a] - origin) <= 1e-6 * delta,
                            source, ": '", p.dataset, "' has origin ", formatDouble(p.origin[a]), " and delta ",
                            formatDouble(p.delta[a]), " on axis ", a, "; its iorigin and stride give ",
                            formatDouble(origin), " and ", formatDouble(delta));
            }
}

// One level on a dense grid over its active vertices' bounding box (level index lo..lo+dims-1).
struct LevelGrid {
    glm::i64vec3 lo{0}, dims{0};   // vertices; cells are the dims - 1 cubes between them
    std::vector<int32_t> owner;    // per vertex: 1 + the component owning it, 0 when none does
    std::vector<uint8_t> state;    // per cell: kOutside, kInLevel, kLeaf or kCovered
    int64_t cellsAlong(int a) const { return std::max<int64_t>(dims[a] - 1, 0); }
    size_t vertex(glm::i64vec3 v) const { return size_t(((v.z - lo.z) * dims.y + v.y - lo.y) * dims.x + v.x - lo.x); }
    size_t cell(glm::i64vec3 c) const {
        return size_t(((c.z - lo.z) * cellsAlong(1) + c.y - lo.y) * cellsAlong(0) + c.x - lo.x);
    }
    bool hasCell(glm::i64vec3 c) const {
        for (int a = 0; a < 3; ++a)
            if (c[a] < lo[a] || c[a] >= lo[a] + cellsAlong(a)) return false;
        return true;
    }
};
enum : uint8_t { kOutside, kInLevel, kLeaf, kCovered };

// Calls f(c) for every cell c (level index) of `g`, x fastest.
template <class F>
void forCells(const LevelGrid& g, F&& f) {
    for (int64_t z = 0; z < g.cellsAlong(2); ++z)
        for (int64_t y = 0; y < g.cellsAlong(1); ++y)
            for (int64_t x = 0; x < g.cellsAlong(0); ++x) f(g.lo + glm::i64vec3(x, y, z));
}

// A level's vertex owners, and its cells: those whose 8 corners are all active (in any component).
LevelGrid levelGrid(const std::string& source, const std::vector<Patch>& patches, size_t l) {
    LevelGrid g;
    glm::i64vec3 hi(0);
    bool any = false;
    for (const Patch& p : patches)
        for (const VertexBox& b : p.active) {
            g.lo = any ? glm::min(g.lo, glm::i64vec3(b.lo)) : glm::i64vec3(b.lo);
            hi = any ? glm::max(hi, glm::i64vec3(b.hi)) : glm::i64vec3(b.hi);
            any = true;
        }
    g.dims = hi - g.lo + int64_t(1);
    const std::string what = strCat(source, ": rl=", l, "'s active points");
    const uint64_t n = checkedProduct({uint64_t(g.dims.x), uint64_t(g.dims.y), uint64_t(g.dims.z)}, what);
    checkAllocation(checkedProduct({n, sizeof(int32_t) + 1}, what), what);
    g.owner.assign(n, 0);
    for (size_t pi = 0; pi < patches.size(); ++pi)
        for (const VertexBox& b : patches[pi].active)
            for (int64_t z = b.lo.z; z <= b.hi.z; ++z)
                for (int64_t y = b.lo.y; y <= b.hi.y; ++y)
                    for (int64_t x = b.lo.x; x <= b.hi.x; ++x) {
                        int32_t& o = g.owner[g.vertex({x, y, z})];
                        if (o == 0) o = int32_t(pi + 1);
                    }
    g.state.assign(size_t(g.cellsAlong(0) * g.cellsAlong(1) * g.cellsAlong(2)), kOutside);
    forCells(g, [&](glm::i64vec3 c) {
        bool all = true;
        for (int k = 0; k < 8 && all; ++k) all = g.owner[g.vertex(c + glm::i64vec3(k & 1, k >> 1 & 1, k >> 2))] != 0;
        if (all) g.state[g.cell(c)] = kInLevel;
    });
    return g;
}

// Leaves over all levels: rl0's cells; a finer cell is a leaf when its parent (ratio r) is one
// and all r^3 children of that parent are the finer level's cells; the parent is then covered.
std::vector<LevelGrid> leafGrids(const std::string& source, const std::vector<std::vector<Patch>>& levels,
                                 const std::vector<int>& ratios) {
    std::vector<LevelGrid> grids;
    for (size_t l = 0; l < levels.size(); ++l) {
        grids.push_back(levelGrid(source, levels[l], l));
        LevelGrid& g = grids.back();
        if (l == 0) {
            for (uint8_t& s : g.state)
                if (s == kInLevel) s = kLeaf;
            continue;
        }
        LevelGrid& coarse = grids[l - 1];
        const int64_t r = ratios[l - 1];
        forCells(coarse, [&](glm::i64vec3 P) {
            uint8_t& s = coarse.state[coarse.cell(P)];
            if (s != kLeaf) return;
            for (int64_t k = 0; k < r * r * r; ++k) {
                const glm::i64vec3 c = P * r + glm::i64vec3(k % r, k / r % r, k / (r * r));
                if (!g.hasCell(c) || g.state[g.cell(c)] == kOutside) return;
            }
            s = kCovered;
        });
        forCells(g, [&](glm::i64vec3 c) {
            uint8_t& s = g.state[g.cell(c)];
            const glm::i64vec3 P(floorDiv(c.x, r), floorDiv(c.y, r), floorDiv(c.z, r));
            if (s == kInLevel && coarse.hasCell(P) && coarse.state[coarse.cell(P)] == kCovered) s = kLeaf;
        });
    }
    return grids;
}

// Each leaf of level l, x fastest: the mean of its 8 corner values, each taken from the component
// of `own` (one field's datasets, on the grid of `levels`) that owns the corner.
std::vector<float> leafValues(const CarpetFile& file, const LevelGrid& g, const std::vector<Patch>& own,
                              const std::vector<Patch>& level) {
    std::vector<std::vector<double>> values;
    for (size_t pi = 0; pi < level.size(); ++pi) {
        const Patch& p = own.at(pi);
        AMRVK_CHECK(p.shape == level[pi].shape && p.iorigin == level[pi].iorigin, file.name(), ": '", p.dataset,
                    "' is not on the grid of '", level[pi].dataset, "'");
        values.push_back(readValues(file, p));
    }
    std::vector<float> out;
    forCells(g, [&](glm::i64vec3 c) {
        if (g.state[g.cell(c)] != kLeaf) return;
        double mean = 0;  // a sum of eighths: the same as the sum / 8, without overflowing near 1e308
        for (int k = 0; k < 8; ++k) {
            const glm::i64vec3 v = c + glm::i64vec3(k & 1, k >> 1 & 1, k >> 2);
            const size_t pi = size_t(g.owner[g.vertex(v)] - 1);
            const glm::i64vec3 d = v - glm::i64vec3(own[pi].iorigin);  // inside: active lies in the data
            mean += values[pi][size_t((d.z * own[pi].shape.y + d.y) * own[pi].shape.x + d.x)] / 8;
        }
        // A finite mean beyond float's range was read as inf and called non-finite.
        AMRVK_CHECK(!std::isfinite(mean) || std::abs(mean) <= double(std::numeric_limits<float>::max()), file.name(),
                    ": '", elide(own[0].dataset, 120), "' has a cell whose corners' mean is ", formatDouble(mean),
                    ", beyond the 32-bit floats amrvk holds values in (at most ",
                    formatDouble(std::numeric_limits<float>::max()), " in magnitude)");
        out.push_back(static_cast<float>(mean));
    });
    return out;
}

// The components of `var` named by `names` (level -> (component, dataset)), read and checked.
std::vector<std::vector<Patch>> readPatches(const CarpetFile& file,
                                            const std::map<int, std::vector<std::pair<int, std::string>>>& names) {
    std::vector<std::vector<Patch>> levels;
    for (const auto& [rl, comps] : names) {
        levels.emplace_back();
        for (const auto& [c, name] : comps) levels.back().push_back(readPatch(file, name, rl));
    }
    return levels;
}

std::string levelSums(const std::vector<std::vector<Patch>>& levels, bool activeOnly) {
    std::vector<uint64_t> sums;
    for (const auto& level : levels) {
        uint64_t n = 0;
        for (const Patch& p : level) {
            if (!activeOnly) n += uint64_t(p.shape.x) * uint64_t(p.shape.y) * uint64_t(p.shape.z);
            else
                for (const VertexBox& b : p.active) n += IndexBox{b.lo, b.hi}.cellCount();
        }
        sums.push_back(n);
    }
    return join(sums);
}

}  // namespace

bool isCarpetFile(const fs::path& path) {
    try {
        const CarpetFile file(path);
        if (H5Lexists(file.root(), kGlobalGroup, H5P_DEFAULT) > 0) return true;
        DatasetKey key;
        for (const std::string& name : file.rootNames())
            if (parseDatasetKey(name, key)) return true;
    } catch (const Error&) {
    }
    return false;
}

Model readCarpet(const fs::path& path, const ReadOptions& options) {
    Model model{.format = "carpet", .source = path.string()};
    const CarpetFile file(path);
    const auto vars = gridDatasets(file);
    AMRVK_CHECK(!vars.empty(), file.name(), ": not a Carpet file (no 3-D dataset named 'THORN::var it=N tl=T rl=L')");
    for (const auto& [var, entries] : vars) model.availableFields.push_back(var);
    const std::vector<size_t> selected = addSelectedFields(model, options.fields);

    int64_t iteration = 0;
    const std::string& first = model.availableFields[selected[0]];
    const auto names = latestLevels(file.name(), first, vars.at(first), iteration);
    const std::vector<std::vector<Patch>> levels = readPatches(file, names);
    std::vector<int> ratios;
    const std::vector<int> strides = levelStrides(file.name(), levels, ratios);
    checkGeometry(file.name(), levels, strides);
    const std::vector<LevelGrid> grids = leafGrids(file.name(), levels, ratios);
    // rl0's lowest active vertex becomes voxel 0 (finest-level index units).
    const glm::i64vec3 base = grids[0].lo * int64_t(strides[0] / strides.back());
    for (size_t l = 0; l < levels.size(); ++l) {
        const int64_t w = strides[l] / strides.back();  // cell width in finest cells
        const int32_t level = std::countr_zero(uint64_t(w));
        forCells(grids[l], [&](glm::i64vec3 c) {
            if (grids[l].state[grids[l].cell(c)] == kLeaf)
                model.cells.push_back({glm::ivec3(c * w - base), level});
        });
    }
    AMRVK_CHECK(!model.cells.empty(), file.name(), ": rl=0 has no cell (fewer than 2 active points on an axis)");
    for (size_t fi = 0; fi < selected.size(); ++fi) {
        const std::string& var = model.availableFields[selected[fi]];
        std::vector<std::vector<Patch>> own;
        if (fi > 0) {
            int64_t it = 0;
            own = readPatches(file, latestLevels(file.name(), var, vars.at(var), it));
            AMRVK_CHECK(it == iteration, file.name(), ": '", var, "' is at iteration ", it, ", '", first, "' at ",
                        iteration, " (fields read together must share one)");
            AMRVK_CHECK(own.size() == levels.size(), file.name(), ": '", var, "' has ", own.size(), " levels, '",
                        first, "' ", levels.size());
        }
        Field& field = model.fields[fi];
        for (size_t l = 0; l < levels.size(); ++l) {
            AMRVK_CHECK(own.empty() || own[l].size() == levels[l].size(), file.name(), ": '", var, "' has ",
                        own.empty() ? 0 : own[l].size(), " components on rl=", l, ", '", first, "' ", levels[l].size());
            const std::vector<float> v = leafValues(file, grids[l], own.empty() ? levels[l] : own[l], levels[l]);
            field.values.insert(field.values.end(), v.begin(), v.end());
        }
    }

    // Voxel v is finest-level index base + v; world: rl0's own map (ref's origin at its iorigin).
    const Patch& ref = levels[0][0];
    const double finestStep = double(strides.back()) / strides[0];
    model.voxelToWorld.scale = ref.delta * finestStep;
    model.voxelToWorld.origin = ref.origin + (glm::dvec3(grids[0].lo) - glm::dvec3(ref.iorigin)) * ref.delta;

    std::vector<std::string> deltas, components;
    for (const auto& level : levels) {
        deltas.push_back(formatDouble(level[0].delta.x));
        components.push_back(std::to_string(level.size()));
    }
    model.attributes = {
        {"levels", std::to_string(levels.size())},
        {"componentsPerLevel", join(components)},
        {"refinementRatios", join(ratios)},
        {"cellSizes", join(deltas)},
        {"pointsPerLevel", levelSums(levels, false)},
        {"activePointsPerLevel", levelSums(levels, true)},
        {"iteration", std::to_string(iteration)},
        {"timelevel", "0"},
        {"time", formatDouble(ref.time)},
        {"cells", "mean of the 8 active corner vertices"},
    };
    if (H5Aexists_by_name(file.root(), kGlobalGroup, "carpet_reflevels", H5P_DEFAULT) > 0) {
        H5Id g(H5Gopen2(file.root(), kGlobalGroup, H5P_DEFAULT), H5Gclose);
        const int reflevels = file.readNumbers<int>(g.get(), kGlobalGroup, "carpet_reflevels", 1)[0];
        AMRVK_CHECK(reflevels >= int(levels.size()), file.name(), ": carpet_reflevels is ", reflevels, " but rl=",
                    levels.size() - 1, " is present");
        model.attributes.emplace_back("carpetReflevels", std::to_string(reflevels));
    }
    return model;
}

}  // namespace amrvk::amr
