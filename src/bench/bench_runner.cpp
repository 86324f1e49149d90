#include "bench/bench_runner.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <nlohmann/json.hpp>
#include <sstream>

#include "amr/readers.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/json_text.h"
#include "core/stats.h"
#include "picture/picture.h"
#include "scene/tf_files.h"
#include "scene/transfer_function.h"
#include "session/picture_description.h"

namespace amrvk::bench {

std::string estimatorLabel(scene::Transmittance transmittance, scene::ControlExtinction control) {
    std::string s;
    if (transmittance != scene::Transmittance::Ratio) s += std::string(" ") + scene::transmittanceName(transmittance);
    if (control != scene::ControlExtinction::None) s += std::string(" ") + scene::controlExtinctionName(control);
    return s;
}

namespace {

// `s` with every character but letters, digits, '-' and '_' replaced by '_' (file names).
std::string fileTag(const std::string& s) {
    std::string out;
    for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return out;
}

using scene::Backend;
using scene::Mode;
using scene::SamplerKind;
using scene::StructureConfig;
using scene::TraversalKind;

bool isCpuDevice(const gpu::Context& ctx) { return ctx.deviceReport().type == "CPU"; }

std::string fmt(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

std::vector<uint32_t> powersOfTwoUpTo(uint32_t n) {
    std::vector<uint32_t> out;
    for (uint32_t k = 1; k < n; k *= 2) out.push_back(k);
    out.push_back(n);
    return out;
}

double efficiency(const RunResult& r) {
    if (!r.error.empty() || r.curve.empty()) return 0;
    const ErrorSample& last = r.curve.back();
    const double mse = last.rmse * last.rmse;
    return mse > 0 && last.seconds > 0 ? 1.0 / (mse * last.seconds) : 0.0;
}

class Runner {
public:
    Runner(gpu::Context& ctx, const BenchOptions& o, const BenchProgress& progress)
        : mCtx(ctx), mOpt(o), mProgress(progress) {}

    BenchResults run();

private:
    size_t countRuns() const;
    void tick(const std::string& what) {
        if (mProgress) mProgress(mDone, mTotal, what);
    }
    ReferenceImage reference(const BenchDataset& ds, const std::string& tfName, Mode mode);
    RunResult measure(const std::string& kind, Mode mode, const StructureConfig& config, double dvrStep,
                      scene::Transmittance transmittance = scene::Transmittance::Ratio,
                      scene::ControlExtinction control = scene::ControlExtinction::None);
    // The timed runs' settings: the resolved ones with this run's mode, step and estimators.
    scene::RenderSettings settingsFor(Mode mode, double dvrStep, scene::Transmittance transmittance,
                                      scene::ControlExtinction control) const;
    // The control extinctions that combination `c` runs with (minorants: grid traversals only).
    std::vector<scene::ControlExtinction> controlsOf(const StructureConfig& c) const;
    void finishGroup(size_t first, double target);
    AutoResult autoGroup(size_t first, Mode mode);
    void measureMode(Mode mode);  // the reference, every combination, the grid sweep and auto of one mode
    // The data set's picture switched to `config` (resolved) by a commit; made by
    // picture::makePicture on first use (the old device copy is freed before each new one).
    picture::Picture& pictureFor(const StructureConfig& config);
    // Renderer::render of the picture as committed, or BenchOptions::render when set
    // (sample-parallel MPI).
    scene::RenderOutput renderAll(render::Renderer& renderer, uint32_t spp,
                                  const std::function<void(uint32_t, uint32_t)>& progress,
                                  const std::vector<uint32_t>& snapshotSpp,
                                  const std::function<void(const scene::RenderOutput&)>& snapshot);

    gpu::Context& mCtx;
    const BenchOptions& mOpt;
    BenchProgress mProgress;
    BenchResults mRes;
    size_t mDone = 0, mTotal = 0;
    std::vector<Backend> mBackends;
    // Current group.
    const BenchDataset* mDs = nullptr;
    std::shared_ptr<const scene::Volume> mVolume;
    session::PictureDescription mDesc;  // the data set's picture under the current TF (mode, structure per run)
    std::optional<picture::Picture> mPicture;         // one per data set, edited from run to run by commits
    std::optional<scene::TransferFunction> mTf;       // the albedo the renderer gets (scene::albedoOf of mTfChannels)
    scene::TfChannels mTfChannels, mOtherTfChannels;  // the TF of the runs, and the one the timed edit leaves
    std::string mTfName;
    scene::RenderSettings mSettings;  // resolved: the camera framed
    ReferenceImage mRef;
};

// The matrix's combinations: traversal x sampler x back-end, those with sub-majorants once per
// BenchOptions::subMajorants entry.
std::vector<StructureConfig> matrixOf(const BenchOptions& o, const std::vector<Backend>& backends) {
    std::vector<StructureConfig> out;
    for (TraversalKind t : o.traversals)
        for (SamplerKind s : o.samplers)
            for (Backend b : backends)
                for (uint32_t sub : o.subMajorants) {
                    StructureConfig c{.sampler = s, .traversal = t, .backend = b, .grid = o.grid, .kdLeaves = o.kdLeaves,
                                      .subMajorants = sub};
                    if (!c.hasSubMajorants()) c.subMajorants = 0;  // the structures of "off"
                    if (std::ranges::count(out, c) == 0) out.push_back(c);
                }
    return out;
}

std::vector<scene::ControlExtinction> Runner::controlsOf(const StructureConfig& c) const {
    const bool grid = c.traversal == TraversalKind::GridDda || c.traversal == TraversalKind::GridBvh;
    std::vector<scene::ControlExtinction> out;
    for (scene::ControlExtinction k : mOpt.controls)
        if (grid || k == scene::ControlExtinction::None) out.push_back(k);
    if (out.empty()) out.push_back(scene::ControlExtinction::None);
    return out;
}

size_t Runner::countRuns() const {
    const size_t extra = mOpt.dense ? 1 : 0;
    size_t perTf = 0;
    for (Mode m : mOpt.modes) {
        for (const StructureConfig& c : matrixOf(mOpt, mBackends))
            perTf += controlsOf(c).size() * (scene::castsShadowRays(m) ? mOpt.transmittances.size() : 1);
        perTf += extra;
    }
    if (!mOpt.dvrSteps.empty()) perTf += mOpt.dvrSteps.size() + 1;
    size_t sweep = 0;
    for (TraversalKind t : mOpt.traversals)
        if (t == TraversalKind::GridDda || t == TraversalKind::GridBvh) sweep += mOpt.gridSweep.size();
    perTf += mOpt.modes.empty() ? 0 : sweep;
    return mOpt.datasets.size() * mOpt.tfs.size() * perTf;
}

ReferenceImage Runner::reference(const BenchDataset& ds, const std::string& tfName, Mode mode) {
    const uint32_t spp = mRes.referenceSpp;
    // The reference is a picture description like any other: rendered through picture::makePicture
    // and recorded as the amrvk render command of the same description (its cache key too).
    session::PictureDescription d = mDesc;
    d.session.settings.mode = mode;
    d.session.settings.seed = mSettings.seed + 1000003u;  // independent of the timed runs
    d.session.spp = spp;
    d.session.structure = {.sampler = SamplerKind::ExtBrick, .traversal = TraversalKind::GridDda,
                           .backend = Backend::Sw, .grid = mOpt.grid};
    const std::filesystem::path dir = mOpt.outDir / "references";
    std::filesystem::create_directories(dir);
    const std::string name = fileTag(ds.tag) + "-" + fileTag(tfName) + "-" + scene::modeName(mode);
    const std::filesystem::path meanFile = dir / (name + ".pfm"), varFile = dir / (name + ".variance.pfm"),
                                infoFile = dir / (name + ".json");
    const std::string command = session::renderCommandLine(d, "", meanFile.string(), mOpt.amrvkPath);
    session::PictureDescription keyed = d;
    keyed.session.input = std::filesystem::absolute(ds.input).string();
    // The TF's nodes too: a preset fitted to the data, or one whose definition changed, renders anew.
    const std::string key = session::renderCommandLine(keyed, "", "reference.pfm") + "\n" +
                            scene::paraViewPresetJson(scene::TfChannels::split(*mTf));
    ReferenceInfo info{ds.tag, tfName, scene::modeName(mode), meanFile.string(), command, spp, 0, 0, false};
    ReferenceImage ref;
    ref.spp = spp;
    const scene::RenderSettings& rs = mSettings;
    if (std::filesystem::exists(meanFile) && std::filesystem::exists(varFile) && std::filesystem::exists(infoFile)) {
        // A cache file that does not parse, or has another key, is rendered again.
        const std::string text = readTextFile(infoFile);
        bool shallow = true;
        try {
            checkJsonDepth(text, infoFile.string());
        } catch (const Error&) {
            shallow = false;
        }
        const nlohmann::json cached = shallow ? nlohmann::json::parse(text, nullptr, false) : nlohmann::json();
        if (cached.is_object() && cached.contains("key") && cached.at("key") == key) {
            ref.mean = readPfm(meanFile);
            Image var = readPfm(varFile);
            if (ref.mean.width == rs.width && ref.mean.height == rs.height && var.pixels.size() == ref.mean.pixels.size()) {
                for (const glm::vec4& v : var.pixels) ref.meanVariance.insert(ref.meanVariance.end(), {v.r, v.g, v.b});
                info.cached = true;
            }
        }
    }
    if (mOpt.all) info.cached = mOpt.all(info.cached);
    if (!info.cached) {
        tick("reference " + name + " (" + std::to_string(spp) + " spp)");
        mPicture.reset();  // one renderer's device memory at a time
        picture::Picture p = picture::makePicture(mCtx, mVolume, d, {.shaders = mOpt.shaders});
        scene::RenderOutput out = renderAll(*p.renderer, p.described.spp,
                                            [&](uint32_t done, uint32_t total) {
            tick("reference " + name + " " + std::to_string(done) + "/" + std::to_string(total) + " spp");
        }, {}, {});
        ref.mean = out.mean;
        ref.meanVariance = scene::varianceOfMean(out);
        const Image var = scene::varianceImage(ref.meanVariance, rs.width, rs.height);
        if (mOpt.writesFiles) {
            writeImage(meanFile, ref.mean);
            writeImage(varFile, var);
        }
        info.seconds = out.stats.gpuSeconds;
        const nlohmann::ordered_json j = {{"key", key}, {"command", command}, {"spp", spp},
                                          {"gpuSeconds", out.stats.gpuSeconds},
                                          {"device", mCtx.deviceReport().name}, {"variance", varFile.string()}};
        if (mOpt.writesFiles)
            writeFileAtomic(infoFile, j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n");
    }
    double v = 0;
    for (float x : ref.meanVariance) v += x;
    info.rmseOfReference = ref.meanVariance.empty() ? 0.0 : std::sqrt(v / double(ref.meanVariance.size()));
    mRes.references.push_back(info);
    return ref;
}

scene::RenderSettings Runner::settingsFor(Mode mode, double dvrStep, scene::Transmittance transmittance,
                                          scene::ControlExtinction control) const {
    scene::RenderSettings rs = mSettings;
    rs.mode = mode;
    rs.dvrStep = dvrStep > 0 ? dvrStep : rs.dvrStep;
    rs.transmittance = transmittance;
    rs.controlExtinction = control;
    return rs;
}

RunResult Runner::measure(const std::string& kind, Mode mode, const StructureConfig& config, double dvrStep,
                          scene::Transmittance transmittance, scene::ControlExtinction control) {
    RunResult r{.dataset = mDs->tag,
                .tf = mTfName,
                .mode = scene::modeName(mode),
                .kind = kind,
                .config = config,
                .transmittance = transmittance,
                .control = control,
                .dvrStep = dvrStep,
                .width = mSettings.width,
                .height = mSettings.height,
                .frames = mOpt.frames};
    std::string what = r.dataset + " " + r.tf + " " + r.mode + " " + config.labelWithGrid() +
                       (mode == Mode::Dvr ? " dt " + fmt(dvrStep) : "") + estimatorLabel(transmittance, control);
    tick(what + " (build)");
    const uint64_t validationBefore = mCtx.validationErrors();
    picture::Picture* pictureOf = nullptr;
    const scene::RenderSettings rs = settingsFor(mode, dvrStep, transmittance, control);
    try {
        StructureConfig resolved = config;
        picture::resolveStructure(mCtx, resolved);
        mCtx.memory().resetPeak();
        picture::Picture& picture = pictureFor(resolved);
        const render::Renderer& renderer = *picture.renderer;
        // Build time of every structure this combination uses, whether built now or kept from an
        // earlier run (the kd-tree is built per TF: it is part of tfStructureSeconds instead).
        r.buildSeconds = renderer.scene().combinationBuildSeconds();
        if (renderer.scene().grid) {
            const glm::ivec3 d = renderer.scene().grid->dims;
            r.gridDims = std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
        }
        for (const auto& hb : renderer.scene().hostBytes()) r.hostBytes.push_back(hb);
        // The settings first: the minorants of a control extinction are made with the TF's majorants.
        picture.commit({.settings = rs});
        AMRVK_CHECK(renderer.controlExtinctionOff().empty(), "--control-extinction minorant is off: ",
                    renderer.controlExtinctionOff());
        picture.commit({.tf = mOtherTfChannels});
        Timer tfTimer;
        picture.commit({.tf = mTfChannels});  // the TF edit that is timed, as the viewer makes it
        r.tfUpdateWallSeconds = tfTimer.seconds();
        r.majorantSeconds = renderer.majorantSeconds();
        r.tfStructureSeconds = renderer.structureUpdateSeconds();
        for (const auto& hb : renderer.hostBytes()) r.hostBytes.push_back(hb);
        r.deviceBytesAfterBuild = mCtx.memory().currentBytes();
        for (const auto& [name, usage] : mCtx.memory().perResource())
            if (usage.current > 0) r.deviceBytesPerResource.emplace_back(name, usage.current);
        pictureOf = &picture;
    } catch (const Error& e) {
        r.error = e.what();
    }
    if (mOpt.agree) r.error = mOpt.agree(r.error);  // every rank renders, or none does
    if (r.error.empty()) try {
        render::Renderer& renderer = *pictureOf->renderer;  // rendering only: the picture is committed
        if (mOpt.warmup > 0) {
            tick(what + " (warm-up)");
            renderer.render(rs, mOpt.warmup);
        }
        scene::RenderOutput out = renderAll(
            renderer, mOpt.frames, [&](uint32_t d, uint32_t t) { tick(what + " frame " + std::to_string(d) + "/" + std::to_string(t)); },
            powersOfTwoUpTo(mOpt.frames), [&](const scene::RenderOutput& partial) {
                ImageError e = imageError(partial.mean, mRef);
                r.curve.push_back({partial.spp, partial.stats.gpuSeconds, e.rmse(), e.relMse});
            });
        r.deviceBytesPeak = mCtx.memory().peakBytes();
        r.gpuSeconds = out.stats.gpuSeconds;
        const double paths = double(out.stats.paths);
        const auto& c = out.stats.counters;
        r.fps = r.gpuSeconds > 0 ? double(mOpt.frames) / r.gpuSeconds : 0;
        r.mPathsPerSecond = r.gpuSeconds > 0 ? paths / r.gpuSeconds * 1e-6 : 0;
        r.lookupsPerPath = double(c[shared::kCounterDensityLookups]) / paths;
        r.stepsPerPath = double(c[shared::kCounterTraversalSteps]) / paths;
        r.realPerPath = double(c[shared::kCounterRealCollisions]) / paths;
        const double real = double(c[shared::kCounterRealCollisions]);
        r.nullPerReal = real > 0 ? double(c[shared::kCounterNullCollisions]) / real : 0;
        r.violations = c[shared::kCounterMajorantViolations];
        r.nanSamples = c[shared::kCounterNanSamples];
        const uint32_t counterOf[shared::kPathQuantities] = {shared::kCounterDensityLookups, shared::kCounterNullCollisions,
                                                            shared::kCounterRealCollisions, shared::kCounterTraversalSteps};
        for (uint32_t q = 0; q < shared::kPathQuantities; ++q)
            r.perPath[q] = scene::pathDistribution(out.stats.path, q, c[counterOf[q]]);
        const double lookups = double(c[shared::kCounterDensityLookups]);
        r.shadowLookupShare = lookups > 0 ? double(c[shared::kCounterShadowLookups]) / lookups : 0;
        r.laneUse = c[shared::kCounterLookupLaneSlots] > 0 ? lookups / double(c[shared::kCounterLookupLaneSlots]) : 0;
        r.subMajorantSkipsPerPath = double(c[shared::kCounterSubMajorantSkips]) / paths;
        std::vector<double> spp, rmse;
        for (const ErrorSample& e : r.curve) {
            spp.push_back(e.spp);
            rmse.push_back(e.rmse);
        }
        r.slope = logLogSlope(spp, rmse);
        AMRVK_CHECK(mCtx.validationErrors() == validationBefore, "Vulkan validation reported ",
                    mCtx.validationErrors() - validationBefore, " error(s); last: ", mCtx.lastValidationMessage());
    } catch (const Error& e) {
        r.error = e.what();
    }
    ++mDone;
    tick(what + " done");
    return r;
}

scene::RenderOutput Runner::renderAll(render::Renderer& renderer, uint32_t spp,
                                     const std::function<void(uint32_t, uint32_t)>& progress,
                                     const std::vector<uint32_t>& snapshotSpp,
                                     const std::function<void(const scene::RenderOutput&)>& snapshot) {
    if (mOpt.render) return mOpt.render(renderer, spp, progress, snapshotSpp, snapshot);
    return renderer.render(renderer.settings(), spp, progress, snapshotSpp, snapshot);
}

picture::Picture& Runner::pictureFor(const StructureConfig& config) {
    if (!mPicture) {
        session::PictureDescription d = mDesc;
        d.session.structure = config;
        mPicture = picture::makePicture(mCtx, mVolume, d, {.shaders = mOpt.shaders});
    } else {
        mPicture->commit({.structure = config});
    }
    return *mPicture;
}

// Target time and dense cost ratio for the runs of one group (same data set, TF and mode).
void Runner::finishGroup(size_t first, double target) {
    double densePerPath = 0;
    for (size_t i = first; i < mRes.runs.size(); ++i) {
        const RunResult& r = mRes.runs[i];
        if (r.kind == "dense" && r.error.empty() && r.mPathsPerSecond > 0) densePerPath = 1.0 / r.mPathsPerSecond;
    }
    if (!(target > 0)) {
        for (size_t i = first; i < mRes.runs.size() && !(target > 0); ++i)
            if (mRes.runs[i].error.empty() && !mRes.runs[i].curve.empty()) target = 0.5 * mRes.runs[i].curve.front().rmse;
    }
    for (size_t i = first; i < mRes.runs.size(); ++i) {
        RunResult& r = mRes.runs[i];
        if (!r.error.empty()) continue;
        r.targetRmse = target;
        // Time grows in proportion to spp within a run, so the spp slope is the time slope.
        // Extrapolate only along a convergent slope (biased runs flatten out).
        r.toTarget = timeToTarget(r.curve, target, r.slope && *r.slope < -0.25 ? *r.slope : 0.0);
        if (densePerPath > 0 && r.mPathsPerSecond > 0) r.costRatioToDense = (1.0 / r.mPathsPerSecond) / densePerPath;
    }
}

// --auto for the group of runs from `first`: its pick against the most efficient timed run. The
// pick's figures come from a matching timed run, else it is timed now (kind "auto").
AutoResult Runner::autoGroup(size_t first, Mode mode) {
    AutoResult a{.dataset = mDs->tag, .tf = mTfName, .mode = scene::modeName(mode)};
    scene::RenderSettings rs = mSettings;
    rs.mode = mode;
    render::AutoConstraints constraints;
    if (mOpt.backends.size() == 1) constraints.backend = mOpt.backends.front();
    StructureConfig start{.backend = Backend::Sw, .grid = mOpt.grid};
    picture::Picture& picture = pictureFor(start);
    a.choice = render::autoSelect(*picture.renderer, *mTf, rs, constraints, {},
                                  [&](const std::string& p) { tick("auto probe " + p); });
    picture.commit({.structure = a.choice.config});  // what the probes left built, recorded
    const StructureConfig& c = a.choice.config;
    auto comparable = [](const RunResult& r) { return r.kind != "dense" && r.error.empty(); };
    // The same structures: traversal, sampler, back-end, and the grid and sub-majorants where used,
    // with the settings' shadow estimator (auto picks structures only).
    auto sameAsPick = [&](const RunResult& r) {
        return r.config.labelWithGrid() == c.labelWithGrid() && r.transmittance == rs.transmittance &&
               r.control == rs.controlExtinction;
    };
    size_t pick = mRes.runs.size();
    for (size_t i = first; i < mRes.runs.size() && pick == mRes.runs.size(); ++i)
        if (comparable(mRes.runs[i]) && sameAsPick(mRes.runs[i])) pick = i;
    if (pick == mRes.runs.size()) {
        ++mTotal;
        mRes.runs.push_back(measure("auto", mode, c, 0));
        finishGroup(pick, mRes.runs[first].targetRmse);
    }
    std::optional<size_t> best;
    for (size_t i = first; i < mRes.runs.size(); ++i)
        if (comparable(mRes.runs[i]) && (!best || efficiency(mRes.runs[i]) > efficiency(mRes.runs[*best]))) best = i;
    a.pickEfficiency = efficiency(mRes.runs[pick]);
    a.pickFps = mRes.runs[pick].fps;
    if (best) {
        const RunResult& b = mRes.runs[*best];
        a.bestLabel = b.config.labelWithGrid();
        a.bestEfficiency = efficiency(b);
        a.bestFps = b.fps;
    }
    return a;
}

void Runner::measureMode(Mode mode) {
    mRef = reference(*mDs, mTfName, mode);
    const size_t first = mRes.runs.size();
    for (const StructureConfig& c : matrixOf(mOpt, mBackends))
        for (scene::ControlExtinction k : controlsOf(c)) {
            if (!scene::castsShadowRays(mode)) {
                mRes.runs.push_back(measure("matrix", mode, c, 0, scene::Transmittance::Ratio, k));
                continue;
            }
            for (scene::Transmittance t : mOpt.transmittances)
                mRes.runs.push_back(measure("matrix", mode, c, 0, t, k));
        }
    if (mOpt.dense)
        mRes.runs.push_back(measure("dense", mode,
                                    {.sampler = SamplerKind::Dense, .backend = Backend::Sw,
                                     .grid = mOpt.grid, .denseMaxBytes = mOpt.denseMaxBytes},
                                    0));
    if (mode == mOpt.modes.front()) {
        for (TraversalKind t : {TraversalKind::GridDda, TraversalKind::GridBvh}) {
            if (std::find(mOpt.traversals.begin(), mOpt.traversals.end(), t) == mOpt.traversals.end()) continue;
            for (const std::string& g : mOpt.gridSweep)
                mRes.runs.push_back(
                    measure("grid-sweep", mode, {.traversal = t, .backend = Backend::Sw, .grid = g}, 0));
        }
    }
    finishGroup(first, mOpt.targetRmse);
    if (mOpt.autoSelect) mRes.autos.push_back(autoGroup(first, mode));
}

BenchResults Runner::run() {
    mBackends = mOpt.backends;
    if (mBackends.empty()) {
        mBackends.push_back(Backend::Sw);
        if (mCtx.hasRayQuery()) mBackends.push_back(Backend::Rq);
    }
    for (Backend b : mBackends)
        AMRVK_CHECK(b != Backend::Rq || mCtx.hasRayQuery(), "--backends rq: device '", mCtx.deviceReport().name,
                    "' has no VK_KHR_ray_query");
    const bool cpu = isCpuDevice(mCtx);
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    mRes = BenchResults{.device = mCtx.deviceReport().name,
                        .driver = mCtx.deviceReport().driver,
                        .deviceType = mCtx.deviceReport().type,
                        .commandLine = mOpt.commandLine,
                        .date = date,
                        .tfColors = scene::tfColorsName(mOpt.tfColors),
                        .width = mOpt.width > 0 ? mOpt.width : (cpu ? 256 : 1024),
                        .height = mOpt.height > 0 ? mOpt.height : (cpu ? 256 : 1024),
                        .frames = mOpt.frames,
                        .warmup = mOpt.warmup,
                        .referenceSpp = mOpt.referenceSpp > 0 ? mOpt.referenceSpp : (cpu ? 512 : 4096),
                        .samplesPerInvocation = mCtx.samplesPerInvocation()};
    mTotal = countRuns();

    for (const BenchDataset& ds : mOpt.datasets) {
        mDs = &ds;
        tick("reading " + ds.input);
        session::PictureDescription base;
        base.session.input = ds.input;
        base.session.read = mOpt.read;
        base.session.read.fields.clear();
        base.session.field = ds.field;
        base.session.tfColors = mOpt.tfColors;
        mVolume = session::loadVolume(base.session);
        const scene::Volume& volume = *mVolume;
        const amr::ModelSummary& summary = volume.summary;
        DatasetInfo info{ds.tag, ds.input, volume.field().name, volume.model.cellCount(),
                         summary.maxLevel - summary.minLevel + 1, ""};
        const glm::i64vec3 size = summary.bounds.size();
        info.bounds = std::to_string(size.x) + "x" + std::to_string(size.y) + "x" + std::to_string(size.z);
        mRes.datasets.push_back(info);

        base.session.settings = mOpt.base;
        base.session.settings.width = mRes.width;
        base.session.settings.height = mRes.height;
        base.session.settings.camera.fovYDegrees = mOpt.fovDegrees;
        if (mOpt.camera) base.session.settings.camera = *mOpt.camera;
        base.fitCamera = !mOpt.camera;
        for (const std::string& tfName : mOpt.tfs) {
            mDesc = base;
            mDesc.tfSource = session::TfSource{.name = tfName};
            mDesc.tfRange = mOpt.tfRange;
            const session::Session resolved = session::resolvePicture(mDesc, volume, nullptr);
            mSettings = resolved.settings;
            mDesc.session.settings.camera = mSettings.camera;  // framed once: runs and references agree
            mTfChannels = resolved.tf;
            mTf = scene::albedoOf(resolved.tf, resolved.tfColors);  // as the references render it
            // The timed TF edit comes from another preset, so every majorant really changes.
            session::PictureDescription other = mDesc;
            other.tfSource = session::TfSource{.name = tfName == "foggy" ? "spiky" : "foggy"};
            const session::Session o = session::resolvePicture(other, volume, nullptr);
            mOtherTfChannels = o.tf;
            mTfName = tfName;
            for (Mode mode : mOpt.modes) measureMode(mode);
            if (!mOpt.dvrSteps.empty()) {
                // The ray-marching baseline against the ae reference, next to unbiased ae tracking.
                mRef = reference(ds, tfName, Mode::Ae);
                const size_t first = mRes.runs.size();
                const StructureConfig c{.backend = Backend::Sw, .grid = mOpt.grid};
                mRes.runs.push_back(measure("pt-ae", Mode::Ae, c, 0));
                for (double dt : mOpt.dvrSteps) mRes.runs.push_back(measure("dvr", Mode::Dvr, c, dt));
                finishGroup(first, mOpt.targetRmse);
            }
        }
        mPicture.reset();
        mVolume.reset();
    }
    return mRes;
}

}  // namespace

BenchResults runBench(gpu::Context& ctx, const BenchOptions& options, const BenchProgress& progress) {
    AMRVK_CHECK(!options.datasets.empty(), "bench: no input data set");
    AMRVK_CHECK(options.frames >= 2, "--frames ", options.frames, " must be at least 2");
    Runner runner(ctx, options, progress);
    return runner.run();
}

}  // namespace amrvk::bench
