// Enzo outputs (shared/data/amr/FORMATS.md 4.3): a text parameter file (e.g. DD0018/DD0018), a
// text grid list (<param>.hierarchy) and HDF5 grid data (<param>.cpuNNNN, one group
// /Grid<id 8 digits>/ per grid, one (nz, ny, nx) dataset per field, x fastest). A grid's level
// comes from its cell size, its integer position from round((LeftEdge - DomainLeftEdge) / dx).
// Only 3-D outputs are supported.
#include <hdf5.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "amr/block_structured.h"
#include "amr/field_units.h"
#include "amr/hdf5_util.h"
#include "amr/readers.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

namespace {

// Whitespace-separated numbers of `value`; exactly `count` of them unless count is 0.
template <typename T>
std::vector<T> parseNumbers(const std::string& value, size_t count, const std::string& context) {
    std::vector<T> out;
    const char* p = value.data();
    const char* end = p + value.size();
    for (;;) {
        while (p < end && (*p == ' ' || *p == '\t')) ++p;
        if (p == end) break;
        T v{};
        auto [next, ec] = std::from_chars(p, end, v);
        AMRVK_CHECK(ec == std::errc(), context, ": '", value, "' is not a list of numbers");
        out.push_back(v);
        p = next;
    }
    AMRVK_CHECK(count == 0 || out.size() == count, context, ": expected ", count,
                " numbers, found '", value, "'");
    return out;
}

// "key = value" lines (text after '#' ignored), in file order.
std::vector<std::pair<std::string, std::string>> readKeyValues(const fs::path& path) {
    return keyValueLines(readTextFile(path), true);
}

struct Parameters {
    glm::ivec3 topGridDims{0};
    glm::dvec3 domainLeft{0.0}, domainRight{1.0};
    int refineBy = 2;
    std::vector<std::string> dataLabels;
    std::vector<std::pair<std::string, std::string>> attributes;
    CodeUnits units;  // from the cosmology or the unit lines; 0 where the file has neither
};

// Enzo's code units (its CosmologyGetUnits): for a comoving run from the cosmology,
//   density  = 1.8788e-29 g/cm^3 * OmegaMatterNow * HubbleConstantNow^2 * (1 + CurrentRedshift)^3,
//   velocity = 1.22475e7 cm/s * ComovingBoxSize [Mpc/h] * sqrt(OmegaMatterNow) * sqrt(1 + InitialRedshift);
// else from the DensityUnits, LengthUnits and TimeUnits lines (velocity = length / time).
// A key that is missing leaves its scale unknown (0); one that is not a number is an error.
CodeUnits enzoCodeUnits(const std::map<std::string, std::string>& values, const std::string& name) {
    auto number = [&](const char* key) -> double {
        auto it = values.find(key);
        return it == values.end() ? 0.0 : parseNumbers<double>(it->second, 1, name + ": " + key)[0];
    };
    CodeUnits u;
    if (number("ComovingCoordinates") == 1) {
        const double omega = number("CosmologyOmegaMatterNow"), h = number("CosmologyHubbleConstantNow");
        const double box = number("CosmologyComovingBoxSize");
        auto it = values.find("CosmologyCurrentRedshift"), init = values.find("CosmologyInitialRedshift");
        if (omega > 0 && h > 0 && it != values.end())
            u.density = 1.8788e-29 * omega * h * h * std::pow(1 + number("CosmologyCurrentRedshift"), 3);
        if (omega > 0 && box > 0 && init != values.end())
            u.velocity = 1.22475e7 * box * std::sqrt(omega) * std::sqrt(1 + number("CosmologyInitialRedshift"));
    } else {
        const double length = number("LengthUnits"), time = number("TimeUnits");
        u.density = number("DensityUnits");
        if (length > 0 && time > 0) u.velocity = length / time;
    }
    // A scale that is not a normal positive number (inf from 1e120 cubed, 1e308 / 1e-308, or an
    // underflow) is unknown, as the units line then says (it printed "DensityUnits inf").
    for (double* v : {&u.density, &u.velocity})
        if (!(std::isnormal(*v) && *v > 0)) *v = 0;
    return u;
}

Parameters readParameters(const fs::path& path) {
    const std::string name = path.string();
    Parameters p;
    std::map<std::string, std::string> values;
    std::map<int, std::string> labels;
    for (auto& [key, value] : readKeyValues(path)) {
        if (key.rfind("DataLabel[", 0) == 0 && key.back() == ']') {
            int index = -1;
            std::from_chars(key.data() + 10, key.data() + key.size() - 1, index);
            AMRVK_CHECK(index >= 0, name, ": bad parameter name '", key, "'");
            labels[index] = value;
        } else {
            values[key] = value;
        }
    }
    auto get = [&](const std::string& key) -> const std::string& {
        auto it = values.find(key);
        AMRVK_CHECK(it != values.end(), name, ": missing parameter ", key,
                    " (not an Enzo parameter file?)");
        return it->second;
    };
    const int rank = parseNumbers<int>(get("TopGridRank"), 1, name + ": TopGridRank")[0];
    AMRVK_CHECK(rank == 3, name, ": TopGridRank ", rank, " (only 3-D Enzo outputs are supported)");
    const auto dims = parseNumbers<int>(get("TopGridDimensions"), 3, name + ": TopGridDimensions");
    const auto left = parseNumbers<double>(get("DomainLeftEdge"), 3, name + ": DomainLeftEdge");
    const auto right = parseNumbers<double>(get("DomainRightEdge"), 3, name + ": DomainRightEdge");
    for (int a = 0; a < 3; ++a) {
        const size_t i = static_cast<size_t>(a);
        p.topGridDims[a] = dims[i];
        p.domainLeft[a] = left[i];
        p.domainRight[a] = right[i];
        AMRVK_CHECK(dims[i] > 0 && dims[i] <= kMaxIndex && std::isfinite(left[i]) && std::isfinite(right[i]) &&
                        right[i] > left[i],
                    name, ": empty or non-finite domain on axis ", a, " (TopGridDimensions ", dims[i],
                    ", DomainLeftEdge ", left[i], ", DomainRightEdge ", right[i], ")");
    }
    p.refineBy = parseNumbers<int>(get("RefineBy"), 1, name + ": RefineBy")[0];
    AMRVK_CHECK(p.refineBy > 1 && std::has_single_bit(static_cast<unsigned>(p.refineBy)), name,
                ": RefineBy ", p.refineBy, " is not a power of two");
    for (auto& [index, label] : labels) p.dataLabels.push_back(label);
    for (const char* key : {"InitialTime", "InitialCycleNumber", "CosmologyCurrentRedshift",
                            "ComovingCoordinates", "MaximumRefinementLevel"})
        if (auto it = values.find(key); it != values.end())
            p.attributes.emplace_back(key, it->second);
    p.units = enzoCodeUnits(values, name);
    if (p.units.density > 0) p.attributes.emplace_back("DensityUnits", formatDouble(p.units.density));
    if (p.units.velocity > 0) p.attributes.emplace_back("VelocityUnits", formatDouble(p.units.velocity));
    return p;
}

struct GridInfo {
    int id = 0;
    glm::ivec3 dimension{0};      // incl. ghost zones
    glm::ivec3 start{0}, end{0};  // active zone, inclusive, within `dimension`
    glm::dvec3 left{0.0}, right{0.0};
    std::string baryonFile;
    int level = 0;
    glm::ivec3 position{0};  // global index of the first active cell on its level
    glm::ivec3 active() const { return end - start + 1; }
};

std::vector<GridInfo> readHierarchy(const fs::path& path) {
    const std::string name = path.string();
    // The "key = value" lines of each grid, from its "Grid = N" line to the next one.
    std::vector<std::map<std::string, std::string>> entries;
    for (auto& [key, value] : readKeyValues(path)) {
        if (key == "Grid") entries.emplace_back();
        if (!entries.empty()) entries.back()[key] = value;
    }
    AMRVK_CHECK(!entries.empty(), name, ": no 'Grid = N' entries (not an Enzo hierarchy?)");
    std::vector<GridInfo> grids;
    for (const auto& entry : entries) {
        GridInfo g;
        g.id = parseNumbers<int>(entry.at("Grid"), 1, name + ": Grid")[0];
        auto get = [&](const char* key) -> const std::string& {
            auto it = entry.find(key);
            AMRVK_CHECK(it != entry.end(), name, ": grid ", g.id, " has no ", key);
            return it->second;
        };
        auto context = [&](const char* key) { return strCat(name, ": grid ", g.id, " ", key); };
        auto vec3i = [&](const char* key) {
            auto v = parseNumbers<int>(get(key), 3, context(key));
            return glm::ivec3(v[0], v[1], v[2]);
        };
        auto vec3d = [&](const char* key) {
            auto v = parseNumbers<double>(get(key), 3, context(key));
            return glm::dvec3(v[0], v[1], v[2]);
        };
        if (entry.count("GridRank"))
            AMRVK_CHECK(parseNumbers<int>(get("GridRank"), 1, context("GridRank"))[0] == 3,
                        context("GridRank"), " is not 3");
        g.dimension = vec3i("GridDimension");
        g.start = vec3i("GridStartIndex");
        g.end = vec3i("GridEndIndex");
        g.left = vec3d("GridLeftEdge");
        g.right = vec3d("GridRightEdge");
        g.baryonFile = get("BaryonFileName");
        AMRVK_CHECK(glm::all(glm::greaterThanEqual(g.start, glm::ivec3(0))) &&
                        glm::all(glm::lessThanEqual(g.start, g.end)) &&
                        glm::all(glm::lessThan(g.end, g.dimension)) &&
                        glm::all(glm::lessThan(g.left, g.right)) && !glm::any(glm::isinf(g.left - g.right)),
                    name, ": grid ", g.id, " has an empty or inconsistent active region");
        grids.push_back(std::move(g));
    }
    return grids;
}

// Sets each grid's level and integer position from its cell size and left edge.
void placeGrids(std::vector<GridInfo>& grids, const Parameters& p, const std::string& name) {
    const glm::dvec3 rootDx = (p.domainRight - p.domainLeft) / glm::dvec3(p.topGridDims);
    for (GridInfo& g : grids) {
        const glm::dvec3 dx = (g.right - g.left) / glm::dvec3(g.active());
        const double ratio = rootDx.x / dx.x;
        const double levelReal = std::log(ratio) / std::log(double(p.refineBy));
        const long level = std::lround(levelReal);
        AMRVK_CHECK(level >= 0 && level <= kMaxLevel && std::abs(levelReal - double(level)) < 1e-3,
                    name, ": grid ", g.id, " cell size ", dx.x, " is not the root cell size ",
                    rootDx.x, " divided by a power of RefineBy ", p.refineBy);
        g.level = static_cast<int>(level);
        const glm::dvec3 dxLevel = rootDx / std::pow(double(p.refineBy), double(level));
        for (int a = 0; a < 3; ++a) {
            AMRVK_CHECK(std::abs(dx[a] / dxLevel[a] - 1.0) < 1e-6, name, ": grid ", g.id,
                        " has cell sizes ", dx.x, " ", dx.y, " ", dx.z,
                        " that differ between axes (level ", level, ")");
            const double pos = (g.left[a] - p.domainLeft[a]) / dxLevel[a];
            const double rounded = std::round(pos);
            AMRVK_CHECK(std::abs(pos - rounded) < 1e-3 && std::abs(rounded) < double(INT32_MAX),
                        name, ": grid ", g.id, " left edge ", g.left[a], " is not on a level-",
                        level, " cell boundary");
            g.position[a] = static_cast<int>(rounded);
        }
    }
}

// Open cpu files by path; every error names the file and the dataset.
class GridFiles {
public:
    hid_t open(const fs::path& path) {
        auto it = mFiles.find(path.string());
        if (it != mFiles.end()) return it->second.get();
        AMRVK_CHECK(fs::exists(path), path.string(),
                    ": no such file (grid data file named in the .hierarchy)");
        H5Id f = openHdf5ReadOnly(path);
        const hid_t id = f.get();
        mFiles.emplace(path.string(), std::move(f));
        return id;
    }

private:
    std::map<std::string, H5Id> mFiles;
};

std::string gridGroupName(int id) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "Grid%08d", id);
    return buf;
}

// Names of the 3-D datasets in a grid group (fields; particle arrays are 1-D), sorted.
std::vector<std::string> listGridFields(hid_t file, const std::string& group,
                                        const std::string& fileName) {
    H5Id g(H5Gopen2(file, group.c_str(), H5P_DEFAULT), H5Gclose);
    AMRVK_CHECK(g.valid(), fileName, ": missing group /", group);
    H5G_info_t info{};
    AMRVK_CHECK(H5Gget_info(g.get(), &info) >= 0, fileName, ": cannot list /", group);
    std::vector<std::string> names;
    for (hsize_t i = 0; i < info.nlinks; ++i) {
        const ssize_t len = H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr,
                                               0, H5P_DEFAULT);
        if (len <= 0) continue;
        std::string n(static_cast<size_t>(len) + 1, '\0');
        H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, n.data(), n.size(),
                           H5P_DEFAULT);
        n.resize(static_cast<size_t>(len));
        H5Id d(H5Dopen2(g.get(), n.c_str(), H5P_DEFAULT), H5Dclose);
        if (!d.valid()) continue;
        H5Id space(H5Dget_space(d.get()), H5Sclose);
        if (H5Sget_simple_extent_ndims(space.get()) == 3) names.push_back(n);
    }
    return names;
}

// Reads /Grid<id>/<field> as float32, active zone only, x fastest.
std::vector<float> readGridField(hid_t file, const std::string& fileName, const GridInfo& g,
                                 const std::string& field) {
    const std::string dsName = strCat("/", gridGroupName(g.id), "/", field);
    H5Id d(H5Dopen2(file, dsName.c_str(), H5P_DEFAULT), H5Dclose);
    AMRVK_CHECK(d.valid(), fileName, ": missing dataset ", dsName);
    H5Id space(H5Dget_space(d.get()), H5Sclose);
    hsize_t shape[3] = {0, 0, 0};
    AMRVK_CHECK(H5Sget_simple_extent_ndims(space.get()) == 3, fileName, ": ", dsName,
                " is not a 3-D dataset");
    H5Sget_simple_extent_dims(space.get(), shape, nullptr);
    const glm::u64vec3 shape3(shape[2], shape[1], shape[0]);
    const glm::ivec3 active = g.active();
    const bool isActive = shape3 == glm::u64vec3(active);
    AMRVK_CHECK(isActive || shape3 == glm::u64vec3(g.dimension), fileName, ": ", dsName, " has shape (", shape[0],
                ", ", shape[1], ", ", shape[2], "), expected the active zone (", active.z, ", ", active.y, ", ",
                active.x, ") or the full grid with ghost zones");
    const glm::ivec3 file3(isActive ? active : g.dimension), offset(isActive ? glm::ivec3(0) : g.start);
    const uint64_t count = checkedProduct({shape3.x, shape3.y, shape3.z, sizeof(float)}, fileName + ": " + dsName);
    checkAllocation(count, fileName + ": " + dsName);
    std::vector<float> all(count / sizeof(float));
    AMRVK_CHECK(H5Dread(d.get(), H5T_NATIVE_FLOAT, H5S_ALL, H5S_ALL, H5P_DEFAULT, all.data()) >= 0,
                fileName, ": cannot read ", dsName, " (truncated or damaged file?)");
    if (isActive) return all;
    return cropBox(file3, offset, active, [&](size_t i) { return all[i]; });
}

}  // namespace

Model readEnzo(const fs::path& path, const ReadOptions& options) {
    Model model{.format = "enzo", .source = path.string()};
    fs::path paramPath = path;
    if (path.extension() == ".hierarchy") paramPath.replace_extension();
    fs::path hierarchyPath = paramPath;
    hierarchyPath += ".hierarchy";
    const fs::path dir = paramPath.parent_path();

    const Parameters params = readParameters(paramPath);
    std::vector<GridInfo> grids = readHierarchy(hierarchyPath);
    placeGrids(grids, params, hierarchyPath.string());

    // Grid data lives beside the parameter file whatever directory the hierarchy names.
    auto dataPath = [&](const GridInfo& g) { return dir / fs::path(g.baryonFile).filename(); };
    GridFiles files;

    // Fields: the DataLabels first, then any other 3-D dataset of the first grid (Temperature,
    // Dark_Matter_Density, ...).
    const fs::path firstFile = dataPath(grids.front());
    model.availableFields = params.dataLabels;
    for (const std::string& n :
         listGridFields(files.open(firstFile), gridGroupName(grids.front().id), firstFile.string()))
        if (std::find(model.availableFields.begin(), model.availableFields.end(), n) ==
            model.availableFields.end())
            model.availableFields.push_back(n);
    const std::vector<size_t> components = addSelectedFields(model, options.fields);
    for (Field& f : model.fields) f.units = fieldUnits(enzoQuantity(f.name), params.units);

    int finest = 0;
    for (const GridInfo& g : grids) finest = std::max(finest, g.level);
    AMRVK_CHECK(double(finest) * std::log2(double(params.refineBy)) <= kMaxLevel,
                hierarchyPath.string(), ": ", finest, " levels of RefineBy ", params.refineBy,
                " exceed 2^", kMaxLevel, " finest cells per root cell");
    std::vector<BlockLevel> levels =
        levelsWithCellWidths(std::vector<int>(static_cast<size_t>(finest), params.refineBy), hierarchyPath.string());
    for (const GridInfo& g : grids) {
        const fs::path file = dataPath(g);
        const hid_t h = files.open(file);
        checkedBoxCells(g.position, glm::i64vec3(g.position) + glm::i64vec3(g.active()) - int64_t{1},
                        strCat(hierarchyPath.string(), ": grid ", g.id));
        Block block{.lo = g.position, .hi = g.position + g.active() - 1};
        for (size_t f : components)
            block.values.push_back(readGridField(h, file.string(), g, model.availableFields[f]));
        levels[static_cast<size_t>(g.level)].blocks.push_back(std::move(block));
    }
    appendLeafCells(model, levels);

    const glm::dvec3 rootDx =
        (params.domainRight - params.domainLeft) / glm::dvec3(params.topGridDims);
    model.voxelToWorld.origin = params.domainLeft;
    model.voxelToWorld.scale = rootDx / double(levels.front().cellWidth);

    model.attributes = params.attributes;
    model.attributes.emplace_back("levels", std::to_string(levels.size()));
    model.attributes.emplace_back("gridsPerLevel", join(blockCounts(levels)));
    model.attributes.emplace_back("refineBy", std::to_string(params.refineBy));
    model.attributes.emplace_back(
        "topGridDimensions",
        strCat(params.topGridDims.x, " ", params.topGridDims.y, " ", params.topGridDims.z));
    model.attributes.emplace_back("rootCellSize", formatDouble(rootDx.x));
    return model;
}

}  // namespace amrvk::amr
