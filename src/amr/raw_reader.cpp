// Raw uniform volumes (headerless, little-endian, x fastest) -> leaf cells by octree coarsening.
// The volume is padded conceptually to a power-of-two cube; padding voxels are never cells.
// A block that lies inside the volume becomes one cell of value = its voxel average when
// max - min <= threshold over its voxels (and no voxel is NaN); a block that overlaps the
// padding is always split, and single voxels outside are dropped. One bottom-up pass: every
// block reports min/max/sum to its parent, which either merges its 8 children or emits the
// still-unemitted ones. Memory: the volume plus the output cells.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <regex>
#include <type_traits>

#include "amr/block_structured.h"
#include "amr/readers.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

// Raw volumes are little-endian; voxels are read as native values (as core/image_io.cpp does).
static_assert(std::endian::native == std::endian::little, "the raw reader assumes a little-endian host");

namespace {

// Canonical type name for a type name or alias, or "" when unknown.
std::string canonicalRawType(std::string name) {
    name = toLower(name);
    if (name == "uint8" || name == "uint16" || name == "float32" || name == "float64") return name;
    if (name == "float") return "float32";
    if (name == "double") return "float64";
    return "";
}

uint64_t rawTypeBytes(const std::string& type) {
    if (type == "uint8") return 1;
    if (type == "uint16") return 2;
    if (type == "float32") return 4;
    return 8;
}

// Dimensions "<nx>x<ny>x<nz>" and a type token from a name like skull_256x256x256_uint8.raw;
// the last occurrence of each wins. Leaves the outputs untouched when absent.
void parseRawName(const std::string& stem, glm::ivec3& dims, std::string& type) {
    static const std::regex dimsRe(R"((\d+)x(\d+)x(\d+))");
    for (auto it = std::sregex_iterator(stem.begin(), stem.end(), dimsRe); it != std::sregex_iterator(); ++it) {
        glm::i64vec3 d;
        for (int a = 0; a < 3; ++a) {
            const std::string digits = (*it)[a + 1].str();
            d[a] = digits.size() > 10 ? INT64_MAX : std::stoll(digits);
        }
        if (d.x > 0 && d.y > 0 && d.z > 0 && d.x <= INT32_MAX && d.y <= INT32_MAX && d.z <= INT32_MAX)
            dims = glm::ivec3(d);
    }
    static const std::regex tokenRe(R"([A-Za-z0-9]+)");
    for (auto it = std::sregex_iterator(stem.begin(), stem.end(), tokenRe); it != std::sregex_iterator(); ++it) {
        std::string t = canonicalRawType(it->str());
        if (!t.empty()) type = t;
    }
}

// Min, max and sum over a block's voxels; `pending`: the block is inside the volume, not yet
// emitted, and may become one cell; `nan`: some voxel is NaN (never merged).
struct BlockStats {
    double lo, hi, sum;
    bool pending, nan;
};

template <typename T>
class Coarsener {
public:
    Coarsener(const std::vector<T>& voxels, glm::ivec3 dims, double threshold, Model& model,
              std::vector<float>& values)
        : mVoxels(voxels), mDims(dims), mThreshold(threshold), mModel(model), mValues(values) {}

    void run(int rootLevel) {
        BlockStats root = visit({0, 0, 0}, rootLevel);
        if (root.pending) emit({0, 0, 0}, rootLevel, root);
    }

private:
    double voxel(glm::ivec3 p) const {
        return static_cast<double>(
            mVoxels[static_cast<size_t>(p.x) +
                    static_cast<size_t>(mDims.x) * (static_cast<size_t>(p.y) + static_cast<size_t>(mDims.y) * static_cast<size_t>(p.z))]);
    }
    bool insideBlock(glm::ivec3 lower, int64_t w) const {
        return lower.x + w <= mDims.x && lower.y + w <= mDims.y && lower.z + w <= mDims.z;
    }
    static BlockStats voxelStats(double v) { return {v, v, v, true, std::isnan(v)}; }
    void emit(glm::ivec3 lower, int level, const BlockStats& s) {
        mModel.cells.push_back(Cell{lower, level});
        mValues.push_back(static_cast<float>(s.sum / cellVolume(level)));
    }

    // Fast path for the most frequent block: 2x2x2 voxels, all inside the volume.
    BlockStats visitPair(glm::ivec3 lower) {
        const size_t sy = static_cast<size_t>(mDims.x), sz = sy * static_cast<size_t>(mDims.y);
        const size_t base = static_cast<size_t>(lower.x) + sy * static_cast<size_t>(lower.y) +
                            sz * static_cast<size_t>(lower.z);
        const std::array<size_t, 8> offsets = {0, 1, sy, sy + 1, sz, sz + 1, sz + sy, sz + sy + 1};
        std::array<double, 8> v{};
        bool nan = false;
        for (size_t i = 0; i < 8; ++i) {
            v[i] = static_cast<double>(mVoxels[base + offsets[i]]);
            if constexpr (std::is_floating_point_v<T>) nan = nan || std::isnan(v[i]);
        }
        BlockStats s{v[0], v[0], 0, true, nan};
        for (double x : v) {
            s.lo = std::min(s.lo, x);
            s.hi = std::max(s.hi, x);
            s.sum += x;
        }
        if (!nan && s.hi - s.lo <= mThreshold) return s;
        for (int i = 0; i < 8; ++i)
            emit(lower + glm::ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1), 0, voxelStats(v[static_cast<size_t>(i)]));
        s.pending = false;
        return s;
    }

    // Precondition: the block starts inside the volume (lower < dims on every axis).
    BlockStats visit(glm::ivec3 lower, int level) {
        if (level == 0) return voxelStats(voxel(lower));
        if (level == 1 && insideBlock(lower, 2)) return visitPair(lower);
        const int half = 1 << (level - 1);
        std::array<BlockStats, 8> child{};
        std::array<bool, 8> present{};
        bool all = true;
        for (int c = 0; c < 8; ++c) {
            glm::ivec3 cl = lower + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1) * half;
            present[static_cast<size_t>(c)] = cl.x < mDims.x && cl.y < mDims.y && cl.z < mDims.z;
            if (!present[static_cast<size_t>(c)]) {
                all = false;
                continue;
            }
            child[static_cast<size_t>(c)] = level == 1 ? voxelStats(voxel(cl)) : visit(cl, level - 1);
        }
        BlockStats merged{child[0].lo, child[0].hi, 0, all, false};
        for (int c = 0; c < 8; ++c) {
            const BlockStats& s = child[static_cast<size_t>(c)];
            if (!present[static_cast<size_t>(c)]) continue;
            merged.lo = std::min(merged.lo, s.lo);
            merged.hi = std::max(merged.hi, s.hi);
            merged.sum += s.sum;
            merged.pending = merged.pending && s.pending;
            merged.nan = merged.nan || s.nan;
        }
        merged.pending = merged.pending && !merged.nan && merged.hi - merged.lo <= mThreshold &&
                         insideBlock(lower, int64_t{1} << level);
        if (merged.pending) return merged;
        for (int c = 0; c < 8; ++c)
            if (present[static_cast<size_t>(c)] && child[static_cast<size_t>(c)].pending)
                emit(lower + glm::ivec3(c & 1, (c >> 1) & 1, (c >> 2) & 1) * half, level - 1,
                     child[static_cast<size_t>(c)]);
        return merged;
    }

    const std::vector<T>& mVoxels;
    glm::ivec3 mDims;
    double mThreshold;
    Model& mModel;
    std::vector<float>& mValues;
};

template <typename T>
void coarsen(const fs::path& path, glm::ivec3 dims, double threshold, Model& model, std::vector<float>& values) {
    std::vector<T> voxels;
    BinaryReader in(path);
    in.readArray(voxels, static_cast<uint64_t>(dims.x) * static_cast<uint64_t>(dims.y) * static_cast<uint64_t>(dims.z));
    const int maxDim = std::max({dims.x, dims.y, dims.z});
    const int rootLevel = static_cast<int>(std::bit_width(static_cast<uint32_t>(maxDim - 1)));
    Coarsener<T>(voxels, dims, threshold, model, values).run(rootLevel);
}

}  // namespace

Model readRaw(const fs::path& path, const ReadOptions& options) {
    Model model{.format = "raw", .source = path.string(), .availableFields = {"value"}};
    selectFields(model.availableFields, options.fields, model.source);

    glm::ivec3 dims = options.rawDims;
    std::string type;
    if (!options.rawType.empty()) {
        type = canonicalRawType(options.rawType);
        AMRVK_CHECK(!type.empty(), path.string(), ": unknown raw voxel type '", options.rawType,
                    "' (expected uint8, uint16, float32 or float64)");
    }
    glm::ivec3 nameDims{0};
    std::string nameType;
    parseRawName(path.stem().string(), nameDims, nameType);
    if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0) {
        AMRVK_CHECK(dims == glm::ivec3(0), path.string(), ": raw dimensions ", dims.x, "x", dims.y,
                    "x", dims.z, " must all be positive");
        dims = nameDims;
    }
    if (type.empty()) type = nameType;
    AMRVK_CHECK(dims.x > 0, path.string(),
                ": raw volume dimensions unknown (name the file like NAME_256x256x128_uint8.raw "
                "or pass the dimensions)");
    AMRVK_CHECK(!type.empty(), path.string(),
                ": raw voxel type unknown (name the file like NAME_256x256x128_uint8.raw with "
                "uint8, uint16, float32 or float64, or pass the type)");
    AMRVK_CHECK(std::max({dims.x, dims.y, dims.z}) <= (1 << kMaxLevel), path.string(), ": raw dimensions ",
                dims.x, "x", dims.y, "x", dims.z, " exceed 2^", kMaxLevel);
    AMRVK_CHECK(options.rawThreshold >= 0 && std::isfinite(options.rawThreshold), path.string(),
                ": raw coarsening threshold ", options.rawThreshold, " must be finite and >= 0");

    AMRVK_CHECK(static_cast<double>(dims.x) * dims.y * dims.z < 0x1.0p50, path.string(), ": raw dimensions ",
                dims.x, "x", dims.y, "x", dims.z, " are too large");
    const uint64_t voxels = static_cast<uint64_t>(dims.x) * static_cast<uint64_t>(dims.y) * static_cast<uint64_t>(dims.z);
    const uint64_t expected = voxels * rawTypeBytes(type);
    const uint64_t actual = fileSize(path);
    checkAllocation(expected, path.string() + ": the voxels");
    AMRVK_CHECK(actual == expected, path.string(), ": file size ", actual, " bytes does not match ",
                dims.x, "x", dims.y, "x", dims.z, " ", type, " (expected ", expected, " bytes)");

    std::vector<float> values;
    if (type == "uint8") coarsen<uint8_t>(path, dims, options.rawThreshold, model, values);
    else if (type == "uint16") coarsen<uint16_t>(path, dims, options.rawThreshold, model, values);
    else if (type == "float32") coarsen<float>(path, dims, options.rawThreshold, model, values);
    else coarsen<double>(path, dims, options.rawThreshold, model, values);
    model.fields.push_back(Field{"value", std::move(values)});
    model.attributes = {{"dims", strCat(dims.x, "x", dims.y, "x", dims.z)},
                        {"voxelType", type},
                        {"threshold", strCat(options.rawThreshold)},
                        {"voxels", std::to_string(voxels)}};
    return model;
}

}  // namespace amrvk::amr
