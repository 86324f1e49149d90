#include "bench/report.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "bench/plot_script.h"
#include "core/file_io.h"
#include "picture/picture.h"

namespace amrvk::bench {

namespace {

std::string num(double v, int digits = 3) {
    if (!std::isfinite(v)) return "";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

std::string runLabel(const RunResult& r) {
    std::string s = r.config.labelWithSub();
    s += estimatorLabel(r.transmittance, r.control);
    if (r.kind == "grid-sweep" || r.kind == "auto") s += " grid " + r.config.grid;
    if (r.kind == "dvr") s = "dvr dt " + num(r.dvrStep) + " (" + r.config.label() + ")";
    if (r.kind == "pt-ae") s = "ae tracking (" + r.config.label() + ")";
    return s;
}

double mib(uint64_t bytes) { return double(bytes) / double(1 << 20); }

using Json = nlohmann::ordered_json;

// The per-path quantities' names in results.json, as render --json's perPath names them.
const char* const kPathQuantityNames[shared::kPathQuantities] = {"lookups", "nullCollisions", "realCollisions",
                                                                "traversalSteps"};

Json runJson(const RunResult& r) {
    Json j = {{"dataset", r.dataset}, {"tf", r.tf}, {"mode", r.mode}, {"kind", r.kind}, {"label", runLabel(r)},
              {"traversal", scene::traversalName(r.config.traversal)}, {"sampler", scene::samplerName(r.config.sampler)},
              {"backend", scene::backendName(r.config.backend)}, {"grid", r.config.grid}, {"gridDims", r.gridDims},
              {"kdLeaves", r.config.kdLeaves}};
    if (scene::castsShadowRays(scene::parseMode(r.mode)))
        j["transmittance"] = scene::transmittanceName(r.transmittance);
    if (r.kind != "dvr") j["controlExtinction"] = scene::controlExtinctionName(r.control);
    if (r.kind == "dvr") j["dt"] = r.dvrStep;
    j.update({{"width", r.width}, {"height", r.height}, {"frames", r.frames}});
    if (!r.error.empty()) {
        j["error"] = r.error;
        return j;
    }
    j.update({{"gpuSeconds", r.gpuSeconds}, {"fps", r.fps}, {"mPathsPerSecond", r.mPathsPerSecond},
              {"lookupsPerPath", r.lookupsPerPath}, {"stepsPerPath", r.stepsPerPath},
              {"realCollisionsPerPath", r.realPerPath}, {"nullPerRealCollision", r.nullPerReal},
              {"majorantViolations", r.violations}, {"nanSamples", r.nanSamples},
              {"structureBuildSeconds", r.buildSeconds}, {"majorantUpdateSeconds", r.majorantSeconds},
              {"tfStructureUpdateSeconds", r.tfStructureSeconds}, {"tfUpdateWallSeconds", r.tfUpdateWallSeconds},
              {"deviceBytesAfterBuild", r.deviceBytesAfterBuild}, {"deviceBytesPeak", r.deviceBytesPeak}});
    Json& device = j["deviceBytesPerResource"] = Json::object();
    for (const auto& [name, bytes] : r.deviceBytesPerResource) device[name] = bytes;
    Json& host = j["hostBytesPerStructure"] = Json::object();
    for (const auto& [name, bytes] : r.hostBytes) host[name] = bytes;
    Json& curve = j["error"] = Json::array();
    for (const ErrorSample& e : r.curve)
        curve.push_back({{"spp", e.spp}, {"seconds", e.seconds}, {"rmse", e.rmse}, {"relMse", e.relMse}});
    j["slope"] = r.slope ? Json(*r.slope) : Json();
    j["targetRmse"] = r.targetRmse;
    if (r.toTarget) {
        j["secondsToTarget"] = r.toTarget->seconds;
        j["toTargetExtrapolated"] = r.toTarget->extrapolated;
    } else {
        j["secondsToTarget"] = nullptr;
    }
    if (r.costRatioToDense > 0) j["costRatioToDense"] = r.costRatioToDense;
    Json& perPath = j["perPath"] = Json::object();
    for (uint32_t q = 0; q < shared::kPathQuantities; ++q) {
        const scene::PathDistribution& d = r.perPath[q];
        perPath[kPathQuantityNames[q]] = {{"mean", d.mean}, {"p50", d.p50}, {"p90", d.p90},
                                          {"p99", d.p99},   {"p999", d.p999}, {"max", d.max}};
    }
    j["shadowLookupShare"] = r.shadowLookupShare;
    j["lookupLaneUtilization"] = r.laneUse;
    j["subMajorantSkipsPerPath"] = r.subMajorantSkipsPerPath;
    return j;
}

// Runs of one kind and mode, keyed by row label and column (data set x TF).
struct Table {
    std::vector<std::string> rows, cols;
    std::map<std::pair<std::string, std::string>, const RunResult*> cells;
};

Table matrixTable(const BenchResults& res, const std::string& mode) {
    Table t;
    for (const RunResult& r : res.runs) {
        if ((r.kind != "matrix" && r.kind != "dense") || r.mode != mode) continue;
        const std::string row = r.config.labelWithSub(), col = r.dataset + " " + r.tf;
        if (std::find(t.rows.begin(), t.rows.end(), row) == t.rows.end()) t.rows.push_back(row);
        if (std::find(t.cols.begin(), t.cols.end(), col) == t.cols.end()) t.cols.push_back(col);
        t.cells[{row, col}] = &r;
    }
    return t;
}

// Markdown table, value(run) per cell; larger is better when `higherBetter`. Marks the best three
// (bold, with rank) and the worst (italic, "worst") per column, among the matrix runs.
std::string markdownTable(const Table& t, const std::function<double(const RunResult&)>& value, bool higherBetter,
                          const std::function<std::string(double)>& show) {
    std::string md = "| traversal / sampler / back-end |";
    for (const auto& c : t.cols) md += " " + c + " |";
    md += "\n|---|";
    for (size_t i = 0; i < t.cols.size(); ++i) md += "---:|";
    md += "\n";
    std::map<std::pair<std::string, std::string>, std::string> marks;
    for (const auto& col : t.cols) {
        std::vector<std::pair<double, std::string>> vals;
        for (const auto& row : t.rows) {
            auto it = t.cells.find({row, col});
            if (it == t.cells.end() || !it->second->error.empty() || it->second->kind != "matrix") continue;
            const double v = value(*it->second);
            if (std::isfinite(v) && v > 0) vals.emplace_back(v, row);
        }
        std::sort(vals.begin(), vals.end(), [&](const auto& a, const auto& b) { return higherBetter ? a.first > b.first : a.first < b.first; });
        for (size_t k = 0; k < vals.size() && k < 3; ++k) marks[{vals[k].second, col}] = "best " + std::to_string(k + 1);
        if (vals.size() > 3) marks[{vals.back().second, col}] = "worst";
    }
    for (const auto& row : t.rows) {
        md += "| " + row + " |";
        for (const auto& col : t.cols) {
            auto it = t.cells.find({row, col});
            std::string cell;
            if (it == t.cells.end()) cell = "";
            else if (!it->second->error.empty()) cell = "failed";
            else {
                const double v = value(*it->second);
                cell = std::isfinite(v) && v > 0 ? show(v) : "n/a";
                auto m = marks.find({row, col});
                if (m != marks.end())
                    cell = m->second == "worst" ? "_" + cell + "_ (worst)" : "**" + cell + "** (" + m->second + ")";
            }
            md += " " + cell + " |";
        }
        md += "\n";
    }
    return md;
}

std::vector<std::string> modesOf(const BenchResults& res) {
    std::vector<std::string> modes;
    for (const RunResult& r : res.runs)
        if (r.kind == "matrix" && std::find(modes.begin(), modes.end(), r.mode) == modes.end()) modes.push_back(r.mode);
    return modes;
}

std::string resultsJson(const BenchResults& res) {
    Json j = {{"device", res.device}, {"driver", res.driver}, {"deviceType", res.deviceType},
              {"commandLine", res.commandLine}, {"date", res.date}, {"tfColors", res.tfColors},
              {"width", res.width}, {"height", res.height},
              {"frames", res.frames}, {"warmupFrames", res.warmup}, {"referenceSpp", res.referenceSpp},
              {"samplesPerFrame", 1}, {"samplesPerInvocation", res.samplesPerInvocation}};
    Json& datasets = j["datasets"] = Json::array();
    for (const DatasetInfo& d : res.datasets)
        datasets.push_back({{"tag", d.tag}, {"input", d.input}, {"field", d.field}, {"cells", d.cells},
                            {"levels", d.levels}, {"bounds", d.bounds}});
    Json& references = j["references"] = Json::array();
    for (const ReferenceInfo& r : res.references)
        references.push_back({{"dataset", r.dataset}, {"tf", r.tf}, {"mode", r.mode}, {"file", r.file},
                              {"command", r.command}, {"spp", r.spp}, {"gpuSeconds", r.seconds},
                              {"rmseOfReference", r.rmseOfReference}, {"cached", r.cached}});
    Json& runs = j["runs"] = Json::array();
    for (const RunResult& r : res.runs) runs.push_back(runJson(r));
    Json& autos = j["auto"] = Json::array();
    for (const AutoResult& a : res.autos) {
        Json choice = picture::autoChoiceJson(a.choice);
        Json entry = {{"dataset", a.dataset}, {"tf", a.tf}, {"mode", a.mode}};
        for (const char* k :
             {"pick", "pickGrid", "pickSubMajorants", "probeSeconds", "probes", "probeSize", "lookupNsAboveReference"})
            entry[k] = choice[k];
        entry["pickEfficiency"] = a.pickEfficiency;
        entry["bestEfficiency"] = a.bestEfficiency;
        entry["efficiencyRatio"] = a.bestEfficiency > 0 ? a.pickEfficiency / a.bestEfficiency : 0.0;
        entry["pickFps"] = a.pickFps;
        entry["best"] = a.bestLabel;
        entry["bestFps"] = a.bestFps;
        entry["probeDetails"] = std::move(choice["probeDetails"]);
        autos.push_back(std::move(entry));
    }
    // Non-finite numbers are written as null; bytes that are not UTF-8 (paths) become U+FFFD.
    return j.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string resultsCsv(const BenchResults& res) {
    std::string csv =
        "dataset,tf,mode,kind,traversal,sampler,backend,grid,grid_dims,dt,width,height,frames,fps,mpaths_per_s,"
        "lookups_per_path,steps_per_path,real_per_path,null_per_real,violations,build_s,majorant_update_s,"
        "tf_structure_s,device_mib_after_build,device_mib_peak,final_spp,final_rmse,final_relmse,slope,target_rmse,"
        "seconds_to_target,extrapolated,cost_ratio_to_dense,lookups_p50,lookups_p90,lookups_p99,lookups_max,null_p99,"
        "steps_p99,shadow_lookup_share,lane_use,error\n";
    for (const RunResult& r : res.runs) {
        std::string err = r.error;
        std::replace(err.begin(), err.end(), ',', ';');
        std::replace(err.begin(), err.end(), '"', '\'');
        csv += r.dataset + "," + r.tf + "," + r.mode + "," + r.kind + "," + scene::traversalName(r.config.traversal) + "," +
               scene::samplerName(r.config.sampler) + "," + scene::backendName(r.config.backend) + "," + r.config.grid +
               "," + r.gridDims + "," + (r.kind == "dvr" ? num(r.dvrStep) : "") + "," + std::to_string(r.width) + "," +
               std::to_string(r.height) + "," + std::to_string(r.frames) + ",";
        if (r.error.empty()) {
            const ErrorSample last = r.curve.empty() ? ErrorSample{} : r.curve.back();
            csv += num(r.fps, 6) + "," + num(r.mPathsPerSecond, 6) + "," + num(r.lookupsPerPath, 6) + "," +
                   num(r.stepsPerPath, 6) + "," + num(r.realPerPath, 6) + "," + num(r.nullPerReal, 6) + "," +
                   std::to_string(r.violations) + "," + num(r.buildSeconds, 6) + "," + num(r.majorantSeconds, 6) + "," +
                   num(r.tfStructureSeconds, 6) + "," + num(mib(r.deviceBytesAfterBuild), 6) + "," +
                   num(mib(r.deviceBytesPeak), 6) + "," + std::to_string(last.spp) + "," + num(last.rmse, 6) + "," +
                   num(last.relMse, 6) + "," + (r.slope ? num(*r.slope, 4) : "") + "," + num(r.targetRmse, 6) + "," +
                   (r.toTarget ? num(r.toTarget->seconds, 6) : "") + "," +
                   (r.toTarget ? (r.toTarget->extrapolated ? "1" : "0") : "") + "," +
                   (r.costRatioToDense > 0 ? num(r.costRatioToDense, 4) : "") + ",";
            const scene::PathDistribution &lookups = r.perPath[shared::kPathLookups];
            csv += std::to_string(lookups.p50) + "," + std::to_string(lookups.p90) + "," + std::to_string(lookups.p99) + "," +
                   std::to_string(lookups.max) + "," + std::to_string(r.perPath[shared::kPathNulls].p99) + "," +
                   std::to_string(r.perPath[shared::kPathSteps].p99) + "," + num(r.shadowLookupShare, 4) + "," +
                   num(r.laneUse, 4) + ",\n";
        } else {
            csv += std::string(28, ',') + "\"" + err + "\"\n";
        }
    }
    return csv;
}

// The sections of one mode: frames/s, seconds to the target RMSE, per-path figures and where
// the time goes.
std::string modeMarkdown(const BenchResults& res, const std::string& mode) {
    std::string md;
    Table t = matrixTable(res, mode);
    md +=
        "## Frames/s, mode " + mode + "\n\nBest three in bold with their rank, the worst in italics (per column).\n\n";
    md += markdownTable(
        t, [](const RunResult& r) { return r.fps; }, true, [](double v) { return num(v, 3); });
    md += "\n## Seconds to the target RMSE, mode " + mode +
          "\n\nGPU seconds until the RMSE against the reference falls below the group's target (`~`: "
          "extrapolated along the measured slope; n/a: not reached).\n\n";
    md += markdownTable(
        t, [](const RunResult& r) { return r.toTarget ? r.toTarget->seconds : 0.0; }, false,
        [](double v) { return num(v, 3); });
    md += "\n## Per-path figures, mode " + mode + "\n\n";
    md +=
        "| data set | TF | combination | M paths/s | lookups/path | steps/path | null/real | violations | build s | "
        "TF edit s (GPU + host) | MiB after build / peak | final RMSE | slope | x dense cost |\n";
    md += "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const RunResult& r : res.runs) {
        if ((r.kind != "matrix" && r.kind != "dense" && r.kind != "auto") || r.mode != mode) continue;
        md += "| " + r.dataset + " | " + r.tf + " | " + runLabel(r) + " | ";
        if (!r.error.empty()) {
            md += "failed: " + r.error + " |||||||||||\n";
            continue;
        }
        md += num(r.mPathsPerSecond) + " | " + num(r.lookupsPerPath) + " | " + num(r.stepsPerPath) + " | " +
              num(r.nullPerReal) + " | " + std::to_string(r.violations) + " | " + num(r.buildSeconds) + " | " +
              num(r.majorantSeconds) + " + " + num(r.tfStructureSeconds) + " | " + num(mib(r.deviceBytesAfterBuild)) +
              " / " + num(mib(r.deviceBytesPeak)) + " | " + (r.curve.empty() ? "" : num(r.curve.back().rmse)) + " | " +
              (r.slope ? num(*r.slope, 3) : "") + " | " + (r.costRatioToDense > 0 ? num(r.costRatioToDense, 3) : "") +
              " |\n";
    }
    md += "\n## Where the time goes, per path, mode " + mode +
          "\n\nDistributions over paths (mean, p50 / p90 / p99 / max; counts above 8 within 25%), the share of "
          "lookups made by shadow rays and the SIMD lanes' share of useful lookup work.\n\n| data set | TF | "
          "combination | lookups | null collisions | real collisions | traversal steps | shadow share | lane use "
          "|\n|---|---|---|---|---|---|---|---:|---:|\n";
    for (const RunResult& r : res.runs) {
        if ((r.kind != "matrix" && r.kind != "auto") || r.mode != mode || !r.error.empty()) continue;
        auto show = [](const scene::PathDistribution& d) {
            return num(d.mean) + "; " + std::to_string(d.p50) + " / " + std::to_string(d.p90) + " / " +
                   std::to_string(d.p99) + " / " + std::to_string(d.max);
        };
        md += "| " + r.dataset + " | " + r.tf + " | " + runLabel(r) + " | " + show(r.perPath[shared::kPathLookups]) +
              " | " + show(r.perPath[shared::kPathNulls]) + " | " + show(r.perPath[shared::kPathReal]) + " | " +
              show(r.perPath[shared::kPathSteps]) + " | " + num(r.shadowLookupShare) + " | " + num(r.laneUse) + " |\n";
    }
    md += "\n";
    return md;
}

// Links the PNG plots (relative names), or says why there are none.
std::string resultsMarkdown(const BenchResults& res, const PlotOutcome& plots) {
    std::string md = "# amrvk bench results\n\n";
    md += "- device: " + res.device + " (" + res.deviceType + ", driver " + res.driver + ")\n";
    md += "- command: `" + res.commandLine + "`\n";
    md += "- date: " + res.date + "\n";
    md += "- protocol: " + std::to_string(res.width) + "x" + std::to_string(res.height) + ", 1 spp per frame, " +
          std::to_string(res.warmup) + " warm-up frames, " + std::to_string(res.frames) +
          " timed frames (GPU timer; " + std::to_string(res.samplesPerInvocation) +
          " frames per GPU thread and dispatch); references " + std::to_string(res.referenceSpp) + " spp; TF colours " +
          res.tfColors + "\n";
    md += "- data sets:";
    for (const DatasetInfo& d : res.datasets)
        md += " " + d.tag + " (" + d.input + ", field " + d.field + ", " + std::to_string(d.cells) + " cells, " +
              std::to_string(d.levels) + " levels, " + d.bounds + ");";
    md += "\n\n";
    for (const std::string& mode : modesOf(res)) md += modeMarkdown(res, mode);
    if (std::ranges::any_of(res.runs, [](const RunResult& r) { return r.kind == "dvr"; })) {
        md += "## Ray marching (dvr) against unbiased ae tracking\n\nRMSE against the ae reference; dvr's error stops "
              "falling at its step-size bias.\n\n| data set | TF | run | frames/s | lookups/path | final RMSE | slope | "
              "seconds to target |\n|---|---|---|---:|---:|---:|---:|---:|\n";
        for (const RunResult& r : res.runs) {
            if (r.kind != "dvr" && r.kind != "pt-ae") continue;
            md += "| " + r.dataset + " | " + r.tf + " | " + runLabel(r) + " | ";
            if (!r.error.empty()) {
                md += "failed: " + r.error + " ||||\n";
                continue;
            }
            md += num(r.fps) + " | " + num(r.lookupsPerPath) + " | " + (r.curve.empty() ? "" : num(r.curve.back().rmse)) +
                  " | " + (r.slope ? num(*r.slope, 3) : "") + " | " +
                  (r.toTarget ? (r.toTarget->extrapolated ? "~" : "") + num(r.toTarget->seconds) : "n/a") + " |\n";
        }
        md += "\n";
    }
    if (std::ranges::any_of(res.runs, [](const RunResult& r) { return r.kind == "grid-sweep"; })) {
        md += "## Grid sweep (frames/s against macrocell resolution)\n\n| data set | TF | traversal | grid | macrocells | "
              "frames/s | steps/path | null/real |\n|---|---|---|---:|---|---:|---:|---:|\n";
        for (const RunResult& r : res.runs) {
            if (r.kind != "grid-sweep") continue;
            md += "| " + r.dataset + " | " + r.tf + " | " + scene::traversalName(r.config.traversal) + " | " + r.config.grid +
                  " | " + r.gridDims + " | " + (r.error.empty() ? num(r.fps) : "failed") + " | " + num(r.stepsPerPath) +
                  " | " + num(r.nullPerReal) + " |\n";
        }
        md += "\n";
    }
    if (!res.autos.empty()) {
        md += "## --auto\n\nPick from short probes against the best measured combination; efficiency = 1 / (final MSE x "
              "GPU seconds).\n\n| data set | TF | mode | pick | probe s | best measured | pick / best efficiency | pick / "
              "best frames/s |\n|---|---|---|---|---:|---|---:|---:|\n";
        for (const AutoResult& a : res.autos)
            md += "| " + a.dataset + " | " + a.tf + " | " + a.mode + " | " + a.choice.config.labelWithSub() + " grid " +
                  a.choice.config.grid + " | " + num(a.choice.seconds) + " | " + a.bestLabel + " | " +
                  (a.bestEfficiency > 0 ? num(a.pickEfficiency / a.bestEfficiency) : "") + " | " +
                  (a.bestFps > 0 ? num(a.pickFps / a.bestFps) : "") + " |\n";
        md += "\n";
    }
    md += "## References\n\n| data set | TF | mode | spp | own RMSE | cached | command |\n|---|---|---|---:|---:|---|---|\n";
    for (const ReferenceInfo& r : res.references)
        md += "| " + r.dataset + " | " + r.tf + " | " + r.mode + " | " + std::to_string(r.spp) + " | " +
              num(r.rmseOfReference) + " | " + (r.cached ? "yes" : "no") + " | `" + r.command + "` |\n";
    md += "\n## Plots\n\n";
    if (!plots.note.empty()) md += plots.note + "\n";
    for (const std::string& p : plots.files)
        if (p.ends_with(".png")) md += "![" + p + "](" + p + ")\n";
    return md;
}

}  // namespace

PlotOutcome writeReports(const BenchResults& results, const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    writeFileAtomic(dir / "results.json", resultsJson(results));
    writeFileAtomic(dir / "results.csv", resultsCsv(results));
    const PlotOutcome plots = drawPlots(dir);
    writeFileAtomic(dir / "results.md", resultsMarkdown(results, plots));
    return plots;
}

}  // namespace amrvk::bench
