// amrvk info: describe a data set and build the structures every renderer configuration starts
// from (bricks, ABRs with value ranges, macrocell value ranges), with sizes and build times.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "accel/abrs.h"
#include "accel/bricks.h"
#include "accel/bricks_file.h"
#include "accel/majorant_bounds.h"
#include "amr/readers.h"
#include "amr/step_time.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/stats.h"
#include "core/strings.h"
#include "scene/limits.h"
#include "scene/majorant_check.h"
#include "scene/structure_config.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"
#include "scene/volume.h"
#include "scene/volume_scene.h"

namespace amrvk::cli {

namespace {

const char* kInfoHelp =
    "Reads an AMR data set, validates it, builds its bricks and then, for each --traversal with --sampler, exactly "
    "the host structures render builds for that combination (by default grid-dda and abr: the macrocell value "
    "ranges and the active brick regions (ABRs) with theirs), and reports the data and the structures: format, "
    "voxel and world bounds, leaf cells per level (level 0 = finest), fields, the field's range, volume-weighted "
    "mean and percentiles by cell count (what the spiky and foggy presets follow), brick/ABR statistics, bytes per "
    "structure and build times. With --check-majorants it instead checks every traversal's majorants against the "
    "exact reconstruction (exit status 1 on a failure).";

// --check-majorants: every traversal's boxes against the exact reconstruction, for every TF.
int checkMajorantsOf(const std::string& input, const amr::ReadOptions& ro, const std::string& gridSpec,
                     uint32_t kdLeaves, uint32_t subMajorants, const std::string& tfList, const std::vector<double>& tfRange,
                     bool json) {
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
        AMRVK_CHECK(std::isfinite(lo) && std::isfinite(hi), "--tf-range ", lo, " ", hi, ": LO and HI must be finite");
        AMRVK_CHECK(lo < hi, "--tf-range ", lo, " ", hi, ": LO must be below HI");
    }
    scene::MajorantCheckOptions options;
    options.grid = gridSpec;
    accel::parseGridDims(gridSpec, volume->bounds());  // a bad --grid is an error before any work
    options.kdLeaves = kdLeaves;
    options.subMajorants = subMajorants;
    const std::vector<std::string> specs = tfList.empty() ? scene::presetNames() : splitList(tfList);
    AMRVK_CHECK(!specs.empty(), "--tfs '", elide(tfList), "': names no TF (presets or files, comma-separated)");
    for (const std::string& spec : specs) {
        // As render fits them: presets follow the data unless --tf-range fixes them.
        scene::TransferFunction tf = tfRange.size() == 2 ? scene::loadTransferFunction(trim(spec), lo, hi).rescaled(lo, hi)
                                                         : scene::loadTransferFunction(trim(spec), volume->percentiles, volume->volumeHistogram);
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
                            {"withData", c.withData}, {"sampledEvery", c.sampledEvery}, {"vertices", c.vertices},
                            {"rangeFailures", c.rangeFailures},
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
            std::printf("  %-22s %-18s %9llu boxes (%llu with data%s), %llu values, %.2f s: %s\n",
                        oneLineMessage(c.boxes + (c.tf.empty() ? "" : " (" + c.tf + ")")).c_str(), c.traversals.c_str(),
                        (unsigned long long)c.count, (unsigned long long)c.withData,
                        c.sampledEvery > 1 ? strCat("; of 1 in ", c.sampledEvery, " refined macrocells").c_str() : "",
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

// One structure combination's host structures as scene::VolumeScene built them for its plan.
struct CombinationInfo {
    std::string label;  // e.g. "grid-dda/grid/sw grid 128"
    std::vector<std::pair<std::string, uint64_t>> hostBytes;  // VolumeScene::hostBytes, model and bricks first
    scene::VolumeScene::Timing seconds;
    double combinationSeconds = 0;  // bricks included
    // Statistics of what it built (zero where the plan has no such structure).
    glm::ivec3 gridDims{0};
    uint64_t abrCount = 0, abrBrickRefs = 0;
    uint32_t maxBricksPerAbr = 0;
    uint64_t hostTotal() const {
        uint64_t t = 0;
        for (const auto& [name, bytes] : hostBytes) t += bytes;
        return t;
    }
};

// What `amrvk info` reports: the data read and its bricks (scene::makeVolume), then for each asked
// combination exactly the structures scene::planOf lists (scene::VolumeScene), with their times.
struct InfoData {
    std::shared_ptr<const scene::Volume> volume;
    amr::FieldStats stats;  // of the field as read
    accel::BrickStats brickStats;
    std::vector<CombinationInfo> combinations;
    double readSeconds = 0;

    const amr::Model& model() const { return volume->model; }
    const amr::ModelSummary& summary() const { return volume->summary; }
    const CombinationInfo* withAbrs() const {
        for (const CombinationInfo& c : combinations)
            if (c.abrCount) return &c;
        return nullptr;
    }
    const CombinationInfo* withGrid() const {
        for (const CombinationInfo& c : combinations)
            if (c.gridDims.x) return &c;
        return nullptr;
    }
    // The union of every combination's structures by name, each at its largest.
    std::vector<std::pair<std::string, uint64_t>> memory() const {
        std::vector<std::pair<std::string, uint64_t>> out;
        for (const CombinationInfo& c : combinations)
            for (const auto& [name, bytes] : c.hostBytes) {
                auto it = std::find_if(out.begin(), out.end(), [&](const auto& m) { return m.first == name; });
                if (it == out.end())
                    out.emplace_back(name, bytes);
                else
                    it->second = std::max(it->second, bytes);
            }
        return out;
    }
};

CombinationInfo describeCombination(const scene::VolumeScene& scene) {
    CombinationInfo c;
    c.label = scene.config().labelWithGrid();
    c.hostBytes = scene.hostBytes();
    c.seconds = scene.buildSeconds;
    c.combinationSeconds = scene.combinationBuildSeconds();
    if (scene.grid) c.gridDims = scene.grid->dims;
    if (scene.abrs) {
        c.abrCount = scene.abrs->abrs.size();
        c.abrBrickRefs = scene.abrs->brickList.size();
        for (const accel::Abr& a : scene.abrs->abrs) c.maxBricksPerAbr = std::max(c.maxBricksPerAbr, a.brickCount);
    }
    return c;
}

InfoData gatherInfo(const std::string& input, const amr::ReadOptions& ro, const std::string& bricksFile,
                    const std::vector<scene::StructureConfig>& configs) {
    InfoData d;
    Timer readTimer;
    amr::Model model;
    {
        ProgressStage stage("reading " + input);
        model = amr::readModel(input, ro);
    }
    d.readSeconds = readTimer.seconds();
    const std::string field = ro.fields.empty() ? std::string() : ro.fields[0];
    if (bricksFile.empty()) {
        d.volume = scene::makeVolume(std::move(model), field);
    } else {
        accel::BrickSet given = accel::readBricksFile(bricksFile, model);
        d.volume = scene::makeVolume(std::move(model), field, std::move(given));
    }
    d.stats = d.volume->fieldStats;
    d.brickStats = accel::computeBrickStats(d.volume->bricks);
    // One scene switched from combination to combination: each builds what its plan lists and
    // frees what the next one does not use, as a renderer's scene does.
    std::optional<scene::VolumeScene> scene;
    for (const scene::StructureConfig& config : configs) {
        if (scene)
            scene->configure(config);
        else
            scene.emplace(d.volume, config);
        d.combinations.push_back(describeCombination(*scene));
    }
    return d;
}

nlohmann::ordered_json combinationJson(const CombinationInfo& c) {
    using Json = nlohmann::ordered_json;
    Json bytes = Json::object();
    for (const auto& [name, b] : c.hostBytes) bytes[name] = b;
    bytes["total"] = c.hostTotal();
    const scene::VolumeScene::Timing& t = c.seconds;
    return {{"combination", c.label},
            {"hostBytes", bytes},
            {"buildSeconds",
             {{"abrs", t.abrs}, {"samplerBvh", t.samplerBvh}, {"macrocells", t.grid}, {"traversalRanges", t.domains},
              {"dense", t.dense}, {"brickGrid", t.brickGrid}, {"combination", c.combinationSeconds}}}};
}

void printInfoJson(const InfoData& d) {
    using Json = nlohmann::ordered_json;
    const amr::Model& model = d.model();
    const scene::Volume& v = *d.volume;
    auto vec = [](glm::dvec3 x) { return Json::array({x.x, x.y, x.z}); };
    Json mem = Json::object(), attributes = Json::object(), combinations = Json::array();
    uint64_t total = 0;
    for (const auto& [name, bytes] : d.memory()) {
        mem[name] = bytes;
        total += bytes;
    }
    mem["total"] = total;
    for (const auto& [k, val] : model.attributes) attributes[k] = val;
    for (const CombinationInfo& c : d.combinations) combinations.push_back(combinationJson(c));
    Json j = {
        {"source", model.source}, {"format", model.format}, {"leafCells", model.cellCount()},
        {"cellsPerLevel", d.summary().cellsPerLevel}, {"minLevel", d.summary().minLevel},
        {"maxLevel", d.summary().maxLevel}, {"fields", model.availableFields}, {"field", v.field().name},
        {"units", v.field().units},  // "" = not known
        {"valueRange", Json::array({double(d.stats.minValue), double(d.stats.maxValue)})},
        {"volumeWeightedMean", d.stats.volumeWeightedMean},
        {"valuePercentiles", v.percentiles.values},
        {"voxelBounds",
         {{"lower", vec(glm::dvec3(v.bounds().lower))}, {"upper", vec(glm::dvec3(v.bounds().upper))}}},
        {"worldBounds", {{"lower", vec(v.worldLo())}, {"upper", vec(v.worldHi())}}},
        {"bricks", d.brickStats.brickCount},
        {"singleCellBricks", d.brickStats.singleCellBricks},
        {"averageCellsPerBrick", d.brickStats.averageCellsPerBrick}};
    Json seconds = {{"read", d.readSeconds}, {"bricks", v.bricks.buildSeconds}};
    if (const CombinationInfo* a = d.withAbrs()) {
        j["abrs"] = a->abrCount;
        j["averageBricksPerAbr"] = double(a->abrBrickRefs) / double(a->abrCount);
        j["maxBricksPerAbr"] = a->maxBricksPerAbr;
        seconds["abrs"] = a->seconds.abrs + a->seconds.domains;  // ABRs and their value ranges
    }
    if (const CombinationInfo* g = d.withGrid()) {
        j["macrocellDims"] = Json::array({g->gridDims.x, g->gridDims.y, g->gridDims.z});
        seconds["macrocells"] = g->seconds.grid;
    }
    j["combinations"] = combinations;
    j["memoryBytes"] = mem;
    j["buildSeconds"] = seconds;
    j["peakResidentBytes"] = peakResidentBytes();
    j["attributes"] = attributes;
    // When the data set is (amr/step_time.h): {"redshift": z} or {"time": t}, null without one.
    j["when"] = nullptr;
    if (const std::optional<amr::StepTime> t = amr::stepTimeOf(model.attributes))
        j["when"] = {{t->kind == amr::StepTime::Kind::Redshift ? "redshift" : "time", t->value}};
    std::printf("%s\n", j.dump(2).c_str());
}

void printCombinationText(const CombinationInfo& c) {
    std::printf("combination   %s: host structures in %.3f s (bricks included)\n", c.label.c_str(),
                c.combinationSeconds);
    if (c.abrCount)
        std::printf("  ABRs        %llu (%.2f bricks/ABR, max %u) in %.3f s, their value ranges in %.3f s\n",
                    (unsigned long long)c.abrCount, double(c.abrBrickRefs) / double(c.abrCount), c.maxBricksPerAbr,
                    c.seconds.abrs, c.seconds.domains);
    if (c.gridDims.x)
        std::printf("  macrocells  %dx%dx%d value ranges in %.3f s\n", c.gridDims.x, c.gridDims.y, c.gridDims.z,
                    c.seconds.grid);
    for (const auto& [name, bytes] : c.hostBytes) std::printf("  %-20s %s\n", name.c_str(), mib(bytes).c_str());
    std::printf("  %-20s %s\n", "total", mib(c.hostTotal()).c_str());
}

void printInfoText(const InfoData& d) {
    const amr::Model& model = d.model();
    const scene::Volume& v = *d.volume;
    const amr::ModelSummary& summary = d.summary();
    const glm::dvec3 worldLo = v.worldLo(), worldHi = v.worldHi();
    // Names and attributes come from the file: shown escaped, each on its line.
    std::printf("source        %s\n", oneLineMessage(model.source).c_str());
    std::printf("format        %s\n", model.format.c_str());
    for (const auto& [k, val] : model.attributes)
        std::printf("  %-11s %s\n", oneLineMessage(k).c_str(), oneLineMessage(val).c_str());
    if (const std::optional<amr::StepTime> t = amr::stepTimeOf(model.attributes))
        std::printf("when          %s%s\n", amr::describe(*t).c_str(),
                    t->kind == amr::StepTime::Kind::Time ? " (code units)" : "");
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
    std::printf("field '%s'   range [%.9g, %.9g], volume-weighted mean %.9g\n", oneLineMessage(v.field().name).c_str(),
                double(d.stats.minValue), double(d.stats.maxValue), d.stats.volumeWeightedMean);
    std::printf("  units: %s\n", v.field().units.empty() ? "not known (the source does not say)"
                                                          : oneLineMessage(v.field().units).c_str());
    const amr::Percentiles& p = v.percentiles;
    std::printf("  percentiles by cell count: P50 %.6g, P75 %.6g, P90 %.6g, P97 %.6g, P99 %.6g\n", double(p[50]),
                double(p[75]), double(p[90]), double(p[97]), double(p[99]));
    std::printf("bricks        %llu (%.1f cells/brick, %llu single-cell, largest %llu cells) in %.3f s\n",
                (unsigned long long)d.brickStats.brickCount, d.brickStats.averageCellsPerBrick,
                (unsigned long long)d.brickStats.singleCellBricks, (unsigned long long)d.brickStats.largestBrickCells,
                v.bricks.buildSeconds);
    for (const CombinationInfo& c : d.combinations) printCombinationText(c);
    std::printf("read time     %.3f s; peak resident memory %s\n", d.readSeconds, mib(peakResidentBytes()).c_str());
}

// The combinations of --traversal LIST and --sampler, each validated as render validates it.
std::vector<scene::StructureConfig> infoConfigs(const std::string& traversals, const std::string& sampler,
                                                const std::string& gridSpec) {
    std::vector<scene::StructureConfig> out;
    for (const std::string& t : splitList(traversals)) {
        scene::StructureConfig c;
        c.traversal = scene::parseTraversal(trim(t));
        c.sampler = scene::parseSampler(sampler);
        c.backend = scene::Backend::Sw;  // host structures only: the sw back-end's BVH
        c.grid = gridSpec;
        c.validate();
        out.push_back(c);
    }
    AMRVK_CHECK(!out.empty(), "--traversal: give at least one traversal");
    return out;
}

}  // namespace

int runInfo(const std::vector<std::string>& argv) {
    CLI::App app(kInfoHelp, "amrvk info");
    setUpCommand(app);
    std::string input, gridSpec = "auto", bricksFile, traversals = "grid-dda,abr", sampler = "grid";
    bool json = false;
    ReadArgs read;
    app.add_option("input", input, "the data set")->required()->type_name("INPUT");
    addReadOptions(app, read, false);
    app.add_option("--grid", gridSpec, "macrocell grid (auto: 128 on the longest axis, at most 2 macrocells per leaf cell)")
        ->capture_default_str()
        ->type_name("auto|N|NxMxK");
    app.add_option("--bricks", bricksFile, "use the bricks of an ExaBrick .bricks file instead of building them")
        ->type_name("FILE");
    app.add_option("--traversal", traversals,
                   "the combinations to build and describe, one per traversal (comma-separated): each builds "
                   "exactly what render builds for it")
        ->capture_default_str()
        ->type_name("LIST");
    app.add_option("--sampler", sampler, "the sampler of those combinations")
        ->capture_default_str()
        ->type_name("ext-brick|abr|grid|dense");
    app.add_flag("--json", json, "print one JSON object on stdout instead of text");
    bool checkMajorants = false;
    std::string tfList;
    std::vector<double> tfRange;
    int64_t kdLeaves = 4096;
    app.add_flag("--check-majorants", checkMajorants,
                 "check every traversal's boxes (macrocells, ABRs, brick bounds and domains, kd leaves per TF, the "
                 "sub-boxes of the macrocells each TF makes loose): the exact range of the reconstruction over each "
                 "box, grown by the position margin, must fit its stored range with room for the GPU's float error, "
                 "and its alpha maximum under every TF its majorant (sub-boxes: of at most 2^18 per TF, those of every "
                 "k-th refined macrocell)");
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
    std::string subMajorants = "8";
    app.add_option("--sub-majorants", subMajorants,
                   "--check-majorants: the largest division of the sub-boxes checked (off: none)")
        ->check(CLI::IsMember({"off", "2", "4", "8", "16"}))
        ->capture_default_str()
        ->type_name("off|N");
    if (!parseCommandLine(app, argv)) return 0;
    const amr::ReadOptions ro = readOptions(read);
    if (checkMajorants) {
        AMRVK_CHECK(bricksFile.empty(), "--check-majorants builds its own bricks (drop --bricks)");
        for (const char* name : {"--traversal", "--sampler"})
            AMRVK_CHECK(app.count(name) == 0, name, " does not apply with --check-majorants (it checks every traversal)");
        return checkMajorantsOf(input, ro, gridSpec, uint32_t(kdLeaves), scene::parseSubMajorants(subMajorants), tfList,
                                tfRange, json);
    }
    for (const char* name : {"--tfs", "--tf-range", "--kd-leaves", "--sub-majorants"})
        AMRVK_CHECK(app.count(name) == 0, name, " applies only with --check-majorants");
    const InfoData d = gatherInfo(input, ro, bricksFile, infoConfigs(traversals, sampler, gridSpec));
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
    read.scale = "linear";  // a conversion keeps the values as they are unless asked
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
    // The name as typed, but on one line with control characters escaped (issue 52, point 16).
    std::printf("wrote %s.cells with %llu cells and %zu field(s)\n", oneLineMessage(base).c_str(),
                static_cast<unsigned long long>(model.cellCount()), model.fields.size());
    return 0;
}

}  // namespace amrvk::cli
