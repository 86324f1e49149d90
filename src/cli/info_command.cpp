// amrvk info: describe a data set and build the structures every renderer configuration starts
// from (bricks, ABRs with value ranges, macrocell value ranges), with sizes and build times.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "accel/abrs.h"
#include "accel/brick_grid.h"
#include "accel/bricks.h"
#include "accel/majorant_bounds.h"
#include "accel/range_grid.h"
#include "accel/support_range.h"
#include "amr/readers.h"
#include "amr/value_percentiles.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"
#include "core/strings.h"
#include "scene/limits.h"
#include "scene/majorant_check.h"
#include "scene/volume.h"

namespace amrvk::cli {

namespace {

const char* kInfoHelp =
    "Reads an AMR data set, validates it, builds bricks, active brick regions (ABRs) with value "
    "ranges, and "
    "macrocell value ranges, and reports the data and the structures: format, voxel and world "
    "bounds, leaf "
    "cells per level (level 0 = finest), fields, the field's range, volume-weighted mean and percentiles by cell "
    "count (what the spiky and foggy presets follow), "
    "brick/ABR "
    "statistics, bytes per structure and build times. With --check-majorants it instead checks "
    "every traversal's majorants against the exact reconstruction (exit status 1 on a failure).";

// --check-majorants: every traversal's boxes against the exact reconstruction, for every TF.
int checkMajorantsOf(const std::string& input, const amr::ReadOptions& ro, const std::string& gridSpec,
                     uint32_t kdLeaves, const std::string& tfList, const std::vector<double>& tfRange, bool json) {
    amr::Model model;
    {
        ProgressStage stage("reading " + input);
        model = amr::readModel(input, ro);
    }
    const std::shared_ptr<const scene::Volume> volume =
        scene::makeVolume(std::move(model), ro.fields.empty() ? std::string() : ro.fields[0]);
    float lo = volume->valueLo(), hi = volume->valueHi();
    if (tfRange.size() == 2) {
        lo = float(tfRange[0]);
        hi = float(tfRange[1]);
        AMRVK_CHECK(lo < hi, "--tf-range ", lo, " ", hi, ": LO must be below HI");
    }
    scene::MajorantCheckOptions options;
    options.grid = gridSpec;
    accel::parseGridDims(gridSpec, volume->bounds());  // a bad --grid is an error before any work
    options.kdLeaves = kdLeaves;
    const std::vector<std::string> specs = tfList.empty() ? scene::presetNames() : splitList(tfList);
    for (const std::string& spec : specs) {
        // As render fits them: presets follow the data unless --tf-range fixes them.
        scene::TransferFunction tf = tfRange.size() == 2 ? scene::loadTransferFunction(trim(spec), lo, hi).rescaled(lo, hi)
                                                         : scene::loadTransferFunction(trim(spec), volume->percentiles);
        options.tfs.push_back(std::move(tf));
    }
    ProgressBar bar("checking majorants", "boxes");
    options.onProgress = [&bar](const std::string& set, uint64_t done, uint64_t total) { bar.update(done, total, set); };
    const std::vector<scene::BoxSetCheck> checks = scene::checkMajorants(volume, options);
    bar.finish();

    uint64_t failed = 0;
    for (const scene::BoxSetCheck& c : checks) failed += c.ok() ? 0 : 1;
    if (json) {
        using Json = nlohmann::ordered_json;
        Json sets = Json::array();
        for (const scene::BoxSetCheck& c : checks) {
            Json tfs = Json::array();
            for (const auto& t : c.tfs)
                tfs.push_back({{"tf", t.tf}, {"failures", t.failures}, {"worstRatio", t.worstRatio}});
            sets.push_back({{"boxes", c.boxes}, {"traversals", c.traversals}, {"builtForTf", c.tf}, {"count", c.count},
                            {"withData", c.withData}, {"vertices", c.vertices}, {"rangeFailures", c.rangeFailures},
                            {"worstExcess", c.worstExcess}, {"worst", c.worst}, {"tfs", tfs}, {"seconds", c.seconds},
                            {"ok", c.ok()}});
        }
        const Json j = {{"source", volume->model.source}, {"field", volume->field().name},
                        {"leafCells", volume->model.cellCount()},
                        {"positionMargin", accel::positionMargin(volume->bounds())},
                        {"gpuErrorUlps", accel::kGpuErrorUlps}, {"tfRange", Json::array({lo, hi})},
                        {"majorantCheck", sets}, {"ok", failed == 0}};
        std::printf("%s\n", j.dump(2).c_str());
    } else {
        std::printf("majorant check of %s, field '%s' (%llu cells), TFs over [%.9g, %.9g], position margin %.3g voxel\n",
                    oneLineMessage(volume->model.source).c_str(), oneLineMessage(volume->field().name).c_str(),
                    (unsigned long long)volume->model.cellCount(), double(lo), double(hi),
                    accel::positionMargin(volume->bounds()));
        for (const scene::BoxSetCheck& c : checks) {
            std::printf("  %-22s %-18s %9llu boxes (%llu with data), %llu values, %.2f s: %s\n",
                        oneLineMessage(c.boxes + (c.tf.empty() ? "" : " (" + c.tf + ")")).c_str(), c.traversals.c_str(),
                        (unsigned long long)c.count, (unsigned long long)c.withData,
                        (unsigned long long)c.vertices, c.seconds, c.ok() ? "ok" : "FAILED");
            if (c.rangeFailures > 0)
                std::printf("    %llu ranges too narrow; worst by %.3g of the largest |value|: %s\n",
                            (unsigned long long)c.rangeFailures, c.worstExcess, c.worst.c_str());
            for (const auto& t : c.tfs)
                if (t.failures > 0)
                    std::printf("    %s: %llu majorants too small (worst: exact maximum %.6g x the majorant)\n",
                                oneLineMessage(t.tf).c_str(), (unsigned long long)t.failures, t.worstRatio);
        }
    }
    AMRVK_CHECK(failed == 0, "--check-majorants: ", failed, " of ", checks.size(), " box sets failed (see above)");
    return 0;
}

std::string mib(uint64_t bytes) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f MiB", double(bytes) / (1024.0 * 1024.0));
    return buf;
}


// What `amrvk info` reports: the data read, its bricks, ABRs with their ranges and the macrocell
// ranges, with the time each took.
struct InfoData {
    amr::Model model;
    std::string field;
    amr::ModelSummary summary;
    amr::FieldStats stats;
    amr::Percentiles percentiles;
    accel::BrickSet bricks;
    accel::BrickStats brickStats;
    std::vector<float> brickValues;
    accel::AbrSet abrs;
    std::vector<accel::ValueRange> abrRanges;
    glm::ivec3 gridDims{0};
    accel::RangeGrid grid;
    double readSeconds = 0, abrSeconds = 0;

    const amr::Field& fieldRef() const { return model.field(field); }
    double bricksPerAbr() const {
        return abrs.abrs.empty() ? 0 : double(abrs.brickList.size()) / double(abrs.abrs.size());
    }
    uint32_t maxBricksPerAbr() const {
        uint32_t m = 0;
        for (const auto& a : abrs.abrs) m = std::max(m, a.brickCount);
        return m;
    }
    glm::dvec3 worldLo() const { return model.voxelToWorld.toWorld(glm::dvec3(summary.bounds.lower)); }
    glm::dvec3 worldHi() const { return model.voxelToWorld.toWorld(glm::dvec3(summary.bounds.upper)); }
};

InfoData gatherInfo(const std::string& input, const amr::ReadOptions& ro, const std::string& bricksFile,
                    const std::string& gridSpec) {
    InfoData d;
    Timer readTimer;
    {
        ProgressStage stage("reading " + input);
        d.model = amr::readModel(input, ro);
    }
    d.readSeconds = readTimer.seconds();
    const amr::Field& field = ro.fields.empty() ? d.model.defaultField() : d.model.field(ro.fields[0]);
    d.field = field.name;
    d.summary = amr::summarize(d.model);
    d.stats = amr::computeFieldStats(d.model, field);
    d.percentiles = amr::percentilesOf(field.values);
    {
        ProgressStage stage("bricks");
        d.bricks = bricksFile.empty() ? accel::buildBricks(d.model) : accel::readBricksFile(bricksFile, d.model);
    }
    d.brickStats = accel::computeBrickStats(d.bricks);
    d.brickValues = accel::brickOrderValues(d.bricks, d.fieldRef());
    Timer abrTimer;
    {
        ProgressStage stage("active brick regions");
        d.abrs = accel::buildAbrs(d.bricks);
        d.abrRanges = accel::computeAbrValueRanges(d.abrs, accel::SupportRangeQuery(d.bricks, d.brickValues),
                                                   accel::positionMargin(d.summary.bounds));
    }
    d.abrSeconds = abrTimer.seconds();
    d.gridDims = accel::parseGridDims(gridSpec, d.summary.bounds);
    {
        ProgressStage stage("macrocell value ranges");
        d.grid = accel::buildRangeGrid(accel::buildBrickGrid(d.bricks, d.summary.bounds, d.gridDims), d.bricks,
                                       d.brickValues);
    }
    return d;
}

struct Mem {
    const char* name;
    uint64_t bytes;
};
std::vector<Mem> infoMemory(const InfoData& d) {
    uint64_t fieldBytes = 0;
    for (const auto& f : d.model.fields) fieldBytes += f.values.size() * sizeof(float);
    return {
        {"cells", d.model.cells.size() * sizeof(amr::Cell)},
        {"fields", fieldBytes},
        {"bricks", d.bricks.bricks.size() * sizeof(accel::Brick)},
        {"brickCellIds", d.bricks.cellIds.size() * sizeof(uint32_t)},
        {"brickValues", d.brickValues.size() * sizeof(float)},
        {"abrs", d.abrs.abrs.size() * sizeof(accel::Abr)},
        {"abrBrickLists", d.abrs.brickList.size() * sizeof(uint32_t)},
        {"abrValueRanges", d.abrRanges.size() * sizeof(accel::ValueRange)},
        {"macrocellValueRanges", d.grid.memoryBytes()},
    };
}

uint64_t totalOf(const std::vector<Mem>& memory) {
    uint64_t total = 0;
    for (const auto& m : memory) total += m.bytes;
    return total;
}

void printInfoJson(const InfoData& d) {
    using Json = nlohmann::ordered_json;
    const amr::Model& model = d.model;
    auto vec = [](glm::dvec3 v) { return Json::array({v.x, v.y, v.z}); };
    const std::vector<Mem> memory = infoMemory(d);
    Json mem = Json::object(), attributes = Json::object();
    for (const auto& m : memory) mem[m.name] = m.bytes;
    mem["total"] = totalOf(memory);
    for (const auto& [k, v] : model.attributes) attributes[k] = v;
    const Json j = {
        {"source", model.source}, {"format", model.format}, {"leafCells", model.cellCount()},
        {"cellsPerLevel", d.summary.cellsPerLevel}, {"minLevel", d.summary.minLevel}, {"maxLevel", d.summary.maxLevel},
        {"fields", model.availableFields}, {"field", d.field},
        {"valueRange", Json::array({double(d.stats.minValue), double(d.stats.maxValue)})},
        {"volumeWeightedMean", d.stats.volumeWeightedMean},
        {"valuePercentiles", d.percentiles.values},
        {"voxelBounds",
         {{"lower", vec(glm::dvec3(d.summary.bounds.lower))}, {"upper", vec(glm::dvec3(d.summary.bounds.upper))}}},
        {"worldBounds", {{"lower", vec(d.worldLo())}, {"upper", vec(d.worldHi())}}},
        {"bricks", d.brickStats.brickCount},
        {"singleCellBricks", d.brickStats.singleCellBricks},
        {"averageCellsPerBrick", d.brickStats.averageCellsPerBrick}, {"abrs", uint64_t(d.abrs.abrs.size())},
        {"averageBricksPerAbr", d.bricksPerAbr()}, {"maxBricksPerAbr", d.maxBricksPerAbr()},
        {"macrocellDims", Json::array({d.gridDims.x, d.gridDims.y, d.gridDims.z})}, {"memoryBytes", mem},
        {"buildSeconds",
         {{"read", d.readSeconds}, {"bricks", d.bricks.buildSeconds}, {"abrs", d.abrSeconds},
          {"macrocells", d.grid.buildSeconds}}},
        {"peakResidentBytes", peakResidentBytes()}, {"attributes", attributes}};
    std::printf("%s\n", j.dump(2).c_str());
}

void printInfoText(const InfoData& d) {
    const amr::Model& model = d.model;
    const amr::ModelSummary& summary = d.summary;
    const glm::dvec3 worldLo = d.worldLo(), worldHi = d.worldHi();
    // Names and attributes come from the file: shown escaped, each on its line.
    std::printf("source        %s\n", oneLineMessage(model.source).c_str());
    std::printf("format        %s\n", model.format.c_str());
    for (const auto& [k, v] : model.attributes)
        std::printf("  %-11s %s\n", oneLineMessage(k).c_str(), oneLineMessage(v).c_str());
    std::printf("fields        %s\n", oneLineMessage(join(model.availableFields, ", ")).c_str());
    std::printf("voxel bounds  [%lld %lld %lld] - [%lld %lld %lld)  (finest-level units)\n",
                (long long)summary.bounds.lower.x, (long long)summary.bounds.lower.y, (long long)summary.bounds.lower.z,
                (long long)summary.bounds.upper.x, (long long)summary.bounds.upper.y,
                (long long)summary.bounds.upper.z);
    std::printf("world bounds  [%g %g %g] - [%g %g %g]\n", worldLo.x, worldLo.y, worldLo.z, worldHi.x, worldHi.y,
                worldHi.z);
    std::printf("leaf cells    %llu on levels %d..%d (0 = finest)\n", (unsigned long long)model.cellCount(),
                summary.minLevel, summary.maxLevel);
    for (size_t l = 0; l < summary.cellsPerLevel.size(); ++l)
        if (summary.cellsPerLevel[l])
            std::printf("  level %-4zu  %llu cells of width %lld\n", l, (unsigned long long)summary.cellsPerLevel[l],
                        (long long)amr::cellWidth(int(l)));
    std::printf("field '%s'   range [%.9g, %.9g], volume-weighted mean %.9g\n", oneLineMessage(d.field).c_str(),
                double(d.stats.minValue), double(d.stats.maxValue), d.stats.volumeWeightedMean);
    const amr::Percentiles& p = d.percentiles;
    std::printf("  percentiles by cell count: P50 %.6g, P75 %.6g, P90 %.6g, P97 %.6g, P99 %.6g\n", double(p[50]),
                double(p[75]), double(p[90]), double(p[97]), double(p[99]));
    std::printf("bricks        %llu (%.1f cells/brick, %llu single-cell, largest %llu cells) in %.3f s\n",
                (unsigned long long)d.brickStats.brickCount, d.brickStats.averageCellsPerBrick,
                (unsigned long long)d.brickStats.singleCellBricks, (unsigned long long)d.brickStats.largestBrickCells,
                d.bricks.buildSeconds);
    std::printf("ABRs          %zu (%.2f bricks/ABR, max %u) in %.3f s\n", d.abrs.abrs.size(), d.bricksPerAbr(),
                d.maxBricksPerAbr(), d.abrSeconds);
    std::printf("macrocells    %dx%dx%d value ranges in %.3f s\n", d.gridDims.x, d.gridDims.y, d.gridDims.z,
                d.grid.buildSeconds);
    const std::vector<Mem> memory = infoMemory(d);
    std::printf("memory        %s in all\n", mib(totalOf(memory)).c_str());
    for (const auto& m : memory) std::printf("  %-20s %s\n", m.name, mib(m.bytes).c_str());
    std::printf("read time     %.3f s; peak resident memory %s\n", d.readSeconds, mib(peakResidentBytes()).c_str());
}

}  // namespace

int runInfo(const std::vector<std::string>& argv) {
    CLI::App app(kInfoHelp, "amrvk info");
    setUpCommand(app);
    std::string input, gridSpec = "auto", bricksFile;
    bool json = false;
    ReadArgs read;
    app.add_option("input", input, "the data set")->required()->type_name("INPUT");
    addReadOptions(app, read, false);
    app.add_option("--grid", gridSpec, "macrocell grid (auto: 128 on the longest axis)")
        ->capture_default_str()
        ->type_name("auto|N|NxMxK");
    app.add_option("--bricks", bricksFile, "use the bricks of an ExaBrick .bricks file instead of building them")
        ->type_name("FILE");
    app.add_flag("--json", json, "print one JSON object on stdout instead of text");
    bool checkMajorants = false;
    std::string tfList;
    std::vector<double> tfRange;
    int64_t kdLeaves = 4096;
    app.add_flag("--check-majorants", checkMajorants,
                 "check every traversal's boxes (macrocells, ABRs, brick bounds and domains, kd leaves per TF): the "
                 "exact range of the reconstruction over each box, grown by the position margin, must fit its stored "
                 "range with room for the GPU's float error, and its alpha maximum under every TF its majorant");
    app.add_option("--tfs", tfList, "--check-majorants: TF presets or files, comma-separated (default: every preset)")
        ->type_name("LIST");
    app.add_option("--tf-range", tfRange,
                   "--check-majorants: map the TFs onto [LO, HI], presets in their range-fixed shape (default: presets "
                   "fitted to the data as render fits them)")
        ->expected(2)
        ->type_name("LO HI");
    app.add_option("--kd-leaves", kdLeaves, "--check-majorants: leaves of the kd-trees")
        ->check(interval(1, scene::kMaxKdLeaves))
        ->capture_default_str()
        ->type_name("N");
    if (!parseCommandLine(app, argv)) return 0;
    const amr::ReadOptions ro = readOptions(read);
    if (checkMajorants) {
        AMRVK_CHECK(bricksFile.empty(), "--check-majorants builds its own bricks (drop --bricks)");
        return checkMajorantsOf(input, ro, gridSpec, uint32_t(kdLeaves), tfList, tfRange, json);
    }
    for (const char* name : {"--tfs", "--tf-range", "--kd-leaves"})
        AMRVK_CHECK(app.count(name) == 0, name, " applies only with --check-majorants");

    const InfoData d = gatherInfo(input, ro, bricksFile, gridSpec);
    if (json)
        printInfoJson(d);
    else
        printInfoText(d);
    return 0;
}

int runConvert(const std::vector<std::string>& argv) {
    CLI::App app(
        "Writes the leaf cells of any supported input as ExaBrick BASE.cells plus one "
        "BASE.<field>.scalars "
        "per field.",
        "amrvk convert");
    setUpCommand(app);
    std::string input, base;
    ReadArgs read;
    app.add_option("input", input, "the data set")->required()->type_name("INPUT");
    addReadOptions(app, read, true);
    app.add_option("-o,--output", base, "output base: writes BASE.cells and BASE.<field>.scalars")
        ->required()
        ->type_name("BASE");
    if (!parseCommandLine(app, argv)) return 0;
    AMRVK_CHECK(!base.empty(), "-o BASE must not be empty");
    checkOutputs({{"-o", base + ".cells"}}, {{"input", input}});
    amr::Model model = amr::readModel(input, readOptions(read));
    amr::validate(model);  // overlaps too: the output is never bricked here
    // Every file checked before any is written: writable, distinct, none of them an input file.
    std::vector<NamedPath> outputs;
    for (const std::filesystem::path& p : amr::exaBrickFiles(model, base)) outputs.push_back({"-o", p});
    checkOutputs(outputs, inputFilesRead());
    for (const amr::Field& f : model.fields)
        if (amr::scalarsName(f.name) != f.name)  // the name from the file shown escaped, on one line
            std::fprintf(stderr, "amrvk convert: %s\n",
                         oneLineMessage(strCat("field '", f.name, "' is written as ", base, ".",
                                               amr::scalarsName(f.name), ".scalars (its name is not a file name)"))
                             .c_str());
    amr::writeExaBrick(model, base);
    std::printf("wrote %s.cells with %llu cells and %zu field(s)\n", base.c_str(),
                static_cast<unsigned long long>(model.cellCount()), model.fields.size());
    return 0;
}

}  // namespace amrvk::cli
