// Chombo HDF5 plotfiles (shared/data/amr/FORMATS.md 4.2): per level a "boxes" compound dataset
// (inclusive lo_i.. hi_k in that level's index space), all boxes' data concatenated in
// "data:datatype=0" (per box: components one after another, each x fastest, boxes grown by
// outputGhost) and their start indices in "data:offsets=0". 2-D files become one-cell-thick slabs.
#include <hdf5.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <type_traits>
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

// HDF5 access for one file; every error names the file and the object.
class ChomboFile {
public:
    explicit ChomboFile(const fs::path& path)
        : mName(path.string()), mFile(openHdf5ReadOnly(path)) {}

    const std::string& name() const { return mName; }
    hid_t root() const { return mFile.get(); }

    H5Id openGroup(hid_t loc, const std::string& name) const {
        H5Id g(H5Gopen2(loc, name.c_str(), H5P_DEFAULT), H5Gclose);
        AMRVK_CHECK(g.valid(), mName, ": missing group '", name, "'");
        return g;
    }
    H5Id openDataset(hid_t loc, const std::string& name) const {
        H5Id d(H5Dopen2(loc, name.c_str(), H5P_DEFAULT), H5Dclose);
        AMRVK_CHECK(d.valid(), mName, ": missing dataset '", name, "'");
        return d;
    }
    bool hasAttribute(hid_t loc, const std::string& name) const {
        return H5Aexists(loc, name.c_str()) > 0;
    }
    bool hasLink(hid_t loc, const std::string& name) const {
        return H5Lexists(loc, name.c_str(), H5P_DEFAULT) > 0;
    }
    // Scalar numeric attribute converted by HDF5 to T (int or double).
    template <typename T>
    T readScalar(hid_t loc, const std::string& name) const {
        static_assert(std::is_same_v<T, int> || std::is_same_v<T, double>);
        H5Id a = openAttribute(loc, name);
        H5Id space(H5Aget_space(a.get()), H5Sclose);
        AMRVK_CHECK(H5Sget_simple_extent_npoints(space.get()) == 1, mName, ": attribute '", name,
                    "' is not a single value");
        T v{};
        AMRVK_CHECK(H5Aread(a.get(), std::is_same_v<T, int> ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE, &v) >= 0, mName,
                    ": cannot read attribute '", name, "' as a number");
        return v;
    }
    std::string readString(hid_t loc, const std::string& name) const {
        H5Id a = openAttribute(loc, name);
        H5Id type(H5Aget_type(a.get()), H5Tclose);
        AMRVK_CHECK(H5Tget_class(type.get()) == H5T_STRING, mName, ": attribute '", name,
                    "' is not a string");
        std::string out;
        if (H5Tis_variable_str(type.get()) > 0) {
            H5Id mem(H5Tcopy(H5T_C_S1), H5Tclose);
            H5Tset_size(mem.get(), H5T_VARIABLE);
            char* s = nullptr;
            AMRVK_CHECK(H5Aread(a.get(), mem.get(), &s) >= 0, mName, ": cannot read attribute '",
                        name, "'");
            out = s ? s : "";
            H5free_memory(s);
        } else {
            const size_t n = H5Tget_size(type.get());
            out.assign(n, '\0');
            AMRVK_CHECK(H5Aread(a.get(), type.get(), out.data()) >= 0, mName,
                        ": cannot read attribute '", name, "'");
            out.resize(strnlen(out.c_str(), n));
        }
        while (!out.empty() && out.back() == ' ') out.pop_back();
        return out;
    }
    // Compound int members `members` (matched by name) of a scalar attribute or of each element
    // of a 1-D dataset; returns count x members.size() ints.
    std::vector<int> readIntCompound(hid_t obj, bool isAttribute, const std::string& what,
                                     const std::vector<std::string>& members) const {
        H5Id type(isAttribute ? H5Aget_type(obj) : H5Dget_type(obj), H5Tclose);
        AMRVK_CHECK(H5Tget_class(type.get()) == H5T_COMPOUND, mName, ": '", what,
                    "' is not a compound");
        for (const std::string& m : members)
            AMRVK_CHECK(H5Tget_member_index(type.get(), m.c_str()) >= 0, mName, ": '", what,
                        "' has no member '", m, "'");
        H5Id mem(H5Tcreate(H5T_COMPOUND, sizeof(int) * members.size()), H5Tclose);
        for (size_t i = 0; i < members.size(); ++i)
            H5Tinsert(mem.get(), members[i].c_str(), i * sizeof(int), H5T_NATIVE_INT);
        H5Id space(isAttribute ? H5Aget_space(obj) : H5Dget_space(obj), H5Sclose);
        const hssize_t count = H5Sget_simple_extent_npoints(space.get());
        AMRVK_CHECK(count >= 0, mName, ": cannot size '", what, "'");
        std::vector<int> out(static_cast<size_t>(count) * members.size());
        if (count == 0) return out;
        const herr_t rc = isAttribute
                              ? H5Aread(obj, mem.get(), out.data())
                              : H5Dread(obj, mem.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data());
        AMRVK_CHECK(rc >= 0, mName, ": cannot read '", what, "'");
        return out;
    }
    std::vector<IndexBox> readBoxes(hid_t obj, bool isAttribute, const std::string& what,
                                    int dim) const {
        const char* axes[] = {"i", "j", "k"};
        std::vector<std::string> members;
        for (const char* side : {"lo_", "hi_"})
            for (int a = 0; a < dim; ++a) members.push_back(std::string(side) + axes[a]);
        std::vector<int> v = readIntCompound(obj, isAttribute, what, members);
        std::vector<IndexBox> boxes(v.size() / members.size());
        for (size_t b = 0; b < boxes.size(); ++b) {
            for (int a = 0; a < dim; ++a) {
                boxes[b].lo[a] = v[b * members.size() + static_cast<size_t>(a)];
                boxes[b].hi[a] = v[b * members.size() + static_cast<size_t>(dim + a)];
            }
            checkedBoxCells(boxes[b].lo, boxes[b].hi, strCat(mName, ": '", what, "' box ", b));
        }
        return boxes;
    }
    std::vector<int64_t> readInt64Dataset(hid_t loc, const std::string& name) const {
        H5Id d = openDataset(loc, name);
        const hsize_t n = extent1d(d.get(), name);
        std::vector<int64_t> out(n);
        if (n > 0)
            AMRVK_CHECK(
                H5Dread(d.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) >= 0,
                mName, ": cannot read dataset '", name, "'");
        return out;
    }
    hsize_t extent1d(hid_t dataset, const std::string& name) const {
        H5Id space(H5Dget_space(dataset), H5Sclose);
        AMRVK_CHECK(H5Sget_simple_extent_ndims(space.get()) == 1, mName, ": dataset '", name,
                    "' is not one-dimensional");
        hsize_t n = 0;
        H5Sget_simple_extent_dims(space.get(), &n, nullptr);
        return n;
    }
    // Reads `count` values from index `start` of a 1-D dataset, converted to double.
    void readRange(hid_t dataset, const std::string& name, hsize_t start, hsize_t count,
                   double* out) const {
        H5Id fileSpace(H5Dget_space(dataset), H5Sclose);
        H5Id memSpace(H5Screate_simple(1, &count, nullptr), H5Sclose);
        AMRVK_CHECK(H5Sselect_hyperslab(fileSpace.get(), H5S_SELECT_SET, &start, nullptr, &count,
                                        nullptr) >= 0 &&
                        H5Dread(dataset, H5T_NATIVE_DOUBLE, memSpace.get(), fileSpace.get(),
                                H5P_DEFAULT, out) >= 0,
                    mName, ": cannot read values ", start, "..", start + count, " of '", name,
                    "' (truncated or damaged file?)");
    }
    H5Id openAttribute(hid_t loc, const std::string& name) const {
        H5Id a(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose);
        AMRVK_CHECK(a.valid(), mName, ": missing attribute '", name, "'");
        return a;
    }

private:
    std::string mName;
    H5Id mFile;
};

// Ghost cells stored around each box (data_attributes/outputGhost, 0 when absent); also checks
// the level's component count.
glm::ivec3 readOutputGhost(const ChomboFile& file, hid_t group, const std::string& levelName,
                           int dim, int ncomp) {
    glm::ivec3 ghost{0};
    if (!file.hasLink(group, "data_attributes")) return ghost;
    H5Id attrs = file.openGroup(group, "data_attributes");
    if (file.hasAttribute(attrs.get(), "comps")) {
        const int comps = file.readScalar<int>(attrs.get(), "comps");
        AMRVK_CHECK(comps == ncomp, file.name(), ": ", levelName, " has ", comps,
                    " components, num_components is ", ncomp);
    }
    if (!file.hasAttribute(attrs.get(), "outputGhost")) return ghost;
    H5Id attr = file.openAttribute(attrs.get(), "outputGhost");
    const char* names[] = {"intvecti", "intvectj", "intvectk"};
    const std::vector<std::string> members(names, names + dim);
    const std::vector<int> g =
        file.readIntCompound(attr.get(), true, levelName + "/outputGhost", members);
    for (int a = 0; a < dim; ++a) ghost[a] = g.at(static_cast<size_t>(a));
    for (int a = 0; a < dim; ++a) checkedInRange(ghost[a], 0, kMaxIndex, file.name() + ": " + levelName + "/outputGhost");
    return ghost;
}

// The blocks of one level: its valid boxes with the values of `components`, ghost cells cut away.
std::vector<Block> readLevelBlocks(const ChomboFile& file, hid_t group,
                                   const std::string& levelName, int dim, int ncomp,
                                   const std::vector<size_t>& components) {
    const glm::ivec3 ghost = readOutputGhost(file, group, levelName, dim, ncomp);
    H5Id boxesSet = file.openDataset(group, "boxes");
    const std::vector<IndexBox> boxes =
        file.readBoxes(boxesSet.get(), false, levelName + "/boxes", dim);
    const std::vector<int64_t> offsets = file.readInt64Dataset(group, "data:offsets=0");
    AMRVK_CHECK(offsets.size() == boxes.size() + 1, file.name(), ": ", levelName,
                "/data:offsets=0 has ", offsets.size(), " entries for ", boxes.size(), " boxes");
    const std::string dataName = levelName + "/data:datatype=0";
    H5Id data = file.openDataset(group, "data:datatype=0");
    const hsize_t dataSize = file.extent1d(data.get(), dataName);
    AMRVK_CHECK(offsets.front() >= 0 && static_cast<uint64_t>(offsets.back()) <= dataSize,
                file.name(), ": ", levelName, "/data:offsets=0 points past the ", dataSize,
                " values of ", dataName);

    std::vector<Block> blocks;
    std::vector<double> buffer;
    for (size_t b = 0; b < boxes.size(); ++b) {
        const IndexBox& valid = boxes[b];
        const std::string boxName = strCat(file.name(), ": ", levelName, " box ", b);
        const glm::i64vec3 grownLo = glm::i64vec3(valid.lo) - glm::i64vec3(ghost);
        const glm::i64vec3 grownHi = glm::i64vec3(valid.hi) + glm::i64vec3(ghost);
        const size_t n = checkedBoxCells(grownLo, grownHi, boxName + " grown by outputGhost");
        const IndexBox grown{glm::ivec3(grownLo), glm::ivec3(grownHi)};
        AMRVK_CHECK(offsets[b] >= 0 && offsets[b + 1] >= offsets[b] &&
                        uint64_t(offsets[b + 1] - offsets[b]) == checkedProduct({n, uint64_t(ncomp)}, boxName),
                    file.name(), ": ", levelName, " box ", b, " has ", offsets[b + 1] - offsets[b],
                    " values, expected ", n * size_t(ncomp), " (", ncomp, " components x ", n,
                    " cells)");
        // Per box: component after component, each the grown box with x fastest.
        Block block{.lo = valid.lo, .hi = valid.hi};
        checkAllocation(checkedProduct({n, sizeof(double)}, boxName), boxName);
        buffer.resize(n);
        for (size_t comp : components) {
            file.readRange(data.get(), dataName, static_cast<hsize_t>(offsets[b]) + comp * n, n,
                           buffer.data());
            block.values.push_back(cropBox(grown.dims(), ghost, valid.dims(),
                                           [&](size_t i) { return static_cast<float>(buffer[i]); }));
        }
        blocks.push_back(std::move(block));
    }
    return blocks;
}

}  // namespace

Model readChombo(const fs::path& path, const ReadOptions& options) {
    Model model{.format = "chombo", .source = path.string()};
    const ChomboFile file(path);
    const hid_t root = file.root();

    int dim = 0;
    if (file.hasLink(root, "Chombo_global")) {
        H5Id global = file.openGroup(root, "Chombo_global");
        if (file.hasAttribute(global.get(), "SpaceDim")) dim = file.readScalar<int>(global.get(), "SpaceDim");
    }
    if (dim == 0 && file.hasLink(root, "level_0/boxes")) {
        H5Id boxes = file.openDataset(root, "level_0/boxes");
        H5Id type(H5Dget_type(boxes.get()), H5Tclose);
        dim = H5Tget_nmembers(type.get()) / 2;
    }
    AMRVK_CHECK(dim != 0, file.name(),
                ": not a Chombo file (no /Chombo_global SpaceDim and no /level_0/boxes)");
    AMRVK_CHECK(dim == 2 || dim == 3, file.name(), ": ", dim,
                "-D data (only 2-D and 3-D Chombo files are supported)");

    const int ncomp = file.readScalar<int>(root, "num_components");
    AMRVK_CHECK(ncomp > 0, file.name(), ": num_components is ", ncomp);
    for (int c = 0; c < ncomp; ++c)
        model.availableFields.push_back(file.readString(root, strCat("component_", c)));
    const std::vector<size_t> components = addSelectedFields(model, options.fields);

    const int levelCount = file.readScalar<int>(root, "num_levels");
    AMRVK_CHECK(levelCount > 0 && levelCount <= kMaxLevel + 1, file.name(), ": num_levels is ",
                levelCount);
    std::vector<H5Id> groups;
    std::vector<int> ratios;  // level l -> l+1
    std::vector<double> dx;
    for (int l = 0; l < levelCount; ++l) {
        groups.push_back(file.openGroup(root, strCat("level_", l)));
        dx.push_back(file.readScalar<double>(groups.back().get(), "dx"));
        AMRVK_CHECK(std::isfinite(dx.back()) && dx.back() > 0, file.name(), ": level_", l, " dx ", dx.back(),
                    " is not a finite positive cell size");
        if (l + 1 < levelCount) {
            const int r = file.readScalar<int>(groups.back().get(), "ref_ratio");
            AMRVK_CHECK(r > 0 && std::has_single_bit(static_cast<unsigned>(r)), file.name(),
                        ": level_", l, " ref_ratio ", r, " is not a power of two");
            ratios.push_back(r);
        }
    }
    std::vector<BlockLevel> levels = levelsWithCellWidths(ratios, file.name());
    glm::ivec3 domainLo0{0};
    for (int l = 0; l < levelCount; ++l) {
        const hid_t group = groups[static_cast<size_t>(l)].get();
        const std::string levelName = strCat("level_", l);
        BlockLevel& level = levels[static_cast<size_t>(l)];
        if (file.hasAttribute(group, "prob_domain")) {
            H5Id a = file.openAttribute(group, "prob_domain");
            level.indexOrigin =
                file.readBoxes(a.get(), true, levelName + "/prob_domain", dim).at(0).lo;
        }
        if (l == 0) domainLo0 = level.indexOrigin;

        level.blocks = readLevelBlocks(file, group, levelName, dim, ncomp, components);
    }
    appendLeafCells(model, levels, dim == 2);

    // Level-l cell i spans [i, i+1) * dx_l; Chombo cells are cubes, so one dx serves every axis.
    model.voxelToWorld.scale = glm::dvec3(dx.back());
    model.voxelToWorld.origin = glm::dvec3(domainLo0) * dx.front();
    if (dim == 2) model.voxelToWorld.origin.z = 0.0;

    model.attributes = {
        {"dimensions", std::to_string(dim)},
        {"levels", std::to_string(levelCount)},
        {"boxesPerLevel", join(blockCounts(levels))},
        {"refinementRatios", join(ratios)},
    };
    std::vector<std::string> cellSizes;
    for (double d : dx) cellSizes.push_back(formatDouble(d));
    model.attributes.emplace_back("cellSizes", join(cellSizes));
    if (file.hasAttribute(root, "time"))
        model.attributes.emplace_back("time", formatDouble(file.readScalar<double>(root, "time")));
    if (file.hasAttribute(root, "iteration"))
        model.attributes.emplace_back("iteration", std::to_string(file.readScalar<int>(root, "iteration")));
    return model;
}

}  // namespace amrvk::amr
