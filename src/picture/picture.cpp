#include "picture/picture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/stats.h"
#include "core/strings.h"
#include "gpu/acceleration_structure.h"

namespace amrvk::picture {

scene::DeviceTraits deviceTraits(const gpu::Context& ctx) {
    return {ctx.deviceReport().name, ctx.deviceReport().type == "CPU", ctx.hasRayQuery()};
}

scene::BackendChoice resolveStructure(const gpu::Context& ctx, scene::StructureConfig& requested) {
    requested.validate();
    const scene::BackendChoice choice = scene::resolveBackend(requested, deviceTraits(ctx));
    requested.backend = choice.backend;
    // Limits known before anything is built (a kd-tree of 2^24 leaves took 88 s to build, then
    // failed on the device's BLAS limit).
    const scene::StructurePlan plan = requested.plan();
    if (plan.boxesPerTf && plan.rayQueryCulling) {
        const uint64_t most = gpu::maxAccelerationPrimitives(ctx);
        AMRVK_CHECK(requested.kdLeaves <= most, "--kd-leaves ", requested.kdLeaves, ": more than device '",
                    ctx.deviceReport().name, "' holds in one acceleration structure (", most, "; use --backend sw)");
    }
    return choice;
}

scene::RenderOutput Picture::render(const std::function<void(uint32_t, uint32_t)>& progress) {
    return renderer->render(renderer->settings(), described.spp, progress);
}

scene::RenderOutput Picture::renderUntil(double targetError, const std::function<void(uint32_t, uint32_t)>& progress) {
    AMRVK_CHECK(targetError > 0 && std::isfinite(targetError), "--until-error ", targetError, ": must be > 0");
    const uint32_t cap = described.spp;
    AMRVK_CHECK(cap >= 2, "--until-error needs --spp of at least 2 as its cap (got ", cap, ")");
    auto reported = [&](uint32_t, uint32_t) {
        if (progress) progress(renderer->accumulatedSpp(), cap);
    };
    // From scratch: the first batch is what the schedule gives an empty image.
    scene::RenderOutput out =
        renderer->render(renderer->settings(), scene::nextNoiseBatch({}, cap, targetError), reported);
    for (uint32_t n; (n = scene::nextNoiseBatch(out, cap, targetError)) > 0; out = renderer->output())
        renderer->accumulate(n, reported);
    return out;
}

Picture makePicture(gpu::Context& ctx, std::shared_ptr<const scene::Volume> volume,
                    const session::PictureDescription& d, Options options) {
    AMRVK_CHECK(volume != nullptr, "internal: makePicture without a volume");
    Picture p;
    auto note = [&](const std::string& line) {
        p.report.notes.push_back(line);
        if (options.note) options.note(line);
    };
    std::vector<std::string> fitted;
    session::Session fittedSession = session::resolvePicture(d, *volume, &fitted);
    for (const std::string& line : fitted) note(line);
    for (const auto& [key, value] : volume->model.attributes)
        if (key == "logFloored") note("log scale: " + value + " (values <= 0, or below --log-floor, have no logarithm)");
    if (const scene::CutAway& cut = fittedSession.settings.cut; !cut.empty()) {
        const glm::dvec3 lo = volume->worldMin(), hi = volume->worldMax();
        if (scene::keepsNothingOf(cut, lo, hi))
            note(strCat(cut.clips.empty() ? "--crop keeps"
                        : cut.crop        ? "--crop and --clip keep"
                                          : "the --clip planes keep",
                        " nothing of the data (world bounds ", lo.x, " ", lo.y, " ", lo.z, " .. ", hi.x, " ", hi.y, " ",
                        hi.z, "): the picture shows only the background"));
    }
    // The renderer is linear inside: the TF's colours as albedo (scene/tf_colors.h).
    const scene::TransferFunction tf = scene::albedoOf(fittedSession.tf, fittedSession.tfColors);
    // A TF transparent over every value of the data shows nothing: said, not a silent black
    // picture (issue 52, point 7: a constant field or a one-cell data set under the fitted layers).
    if (!(tf.maxAlpha(volume->valueLo(), volume->valueHi()) > 0.0f))
        note(strCat("the TF '", fittedSession.tf.name, "' is transparent (alpha 0) over every value of the data [",
                    volume->valueLo(), ", ", volume->valueHi(),
                    "]: the picture shows only the background (try --tf ramp, or --tf-range LO HI)"));
    if (d.fit == session::StructureFit::Probe) {
        // Probes start from the default combination; everything the user gave stays fixed.
        scene::StructureConfig start;
        start.grid = fittedSession.structure.grid;
        start.kdLeaves = fittedSession.structure.kdLeaves;
        resolveStructure(ctx, start);
        p.renderer = std::make_unique<render::Renderer>(ctx, volume, start, options.shaders);
        render::AutoConstraints constraints;
        const scene::StructureConfig& given = fittedSession.structure;
        if (d.isGiven("sampler")) constraints.sampler = given.sampler;
        if (d.isGiven("backend") && given.backend != scene::Backend::Auto) constraints.backend = given.backend;
        if (d.isGiven("grid")) constraints.grid = given.grid;
        if (d.isGiven("subMajorants")) constraints.subMajorants = given.subMajorants;
        constraints.kdLeaves = given.kdLeaves;
        {
            ProgressStage stage("--traversal auto: probing structure combinations");
            p.report.autoChoice = render::autoSelect(*p.renderer, tf, fittedSession.settings, constraints, {}, options.probe);
        }
        const render::AutoChoice& c = *p.report.autoChoice;
        fittedSession.structure = c.config;
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%.1f", c.seconds);
        const size_t predicted = size_t(std::count_if(c.probes.begin(), c.probes.end(),
                                                      [](const render::AutoProbe& a) { return a.predicted; }));
        note(strCat("--traversal auto picked ", c.config.labelWithGrid(), " from ", c.probes.size() - predicted,
                    " measured and ", predicted, " predicted combinations (", c.probeSize, "^2 probes) in ", seconds,
                    " s"));
    } else {
        scene::StructureConfig config = fittedSession.structure;
        const scene::BackendChoice backend = resolveStructure(ctx, config);
        p.report.backendReason = backend.why;
        // Said only where it matters: a combination with a box hierarchy.
        const scene::StructurePlan plan = config.plan();
        if (!backend.why.empty() && (plan.boxMajorants || plan.samplerBvh || plan.samplerBoxes)) note(backend.why);
        std::future<gpu::ComputePipeline> warm;
        if (options.warmTracer) warm = render::warmPathTracer(ctx, *options.warmTracer, config, options.shaders);
        {
            ProgressStage stage("structures for " + config.label());
            p.renderer = std::make_unique<render::Renderer>(ctx, volume, config, options.shaders);
        }
        if (options.warmTracer) p.renderer->adoptPathTracer(*options.warmTracer, warm);
    }
    p.report.buildSeconds = p.renderer->scene().combinationBuildSeconds();
    // The TF (auto's probes set it already) and the settings at once: one majorant pass, also
    // where the settings ask for minorants.
    render::Edit first{.settings = fittedSession.settings};
    if (d.fit != session::StructureFit::Probe) first.tf = tf;
    p.renderer->commit(first);
    if (!p.renderer->controlExtinctionOff().empty())
        note("--control-extinction minorant is off: " + p.renderer->controlExtinctionOff() +
             "; the trackers run without a control");
    fittedSession.settings = {};  // held by the renderer from now on
    p.described = std::move(fittedSession);
    p.volume = std::move(volume);
    return p;
}

session::Session Picture::session() const {
    session::Session s = described;
    s.settings = renderer->settings();
    return s;
}

void Picture::commit(const PictureEdit& e) {
    render::Edit r{.settings = e.settings};
    const scene::TfChannels& tf = e.tf ? *e.tf : described.tf;
    const scene::TfColors colors = e.tfColors.value_or(described.tfColors);
    if (e.tf || colors != described.tfColors) r.tf = scene::albedoOf(tf, colors);
    if (e.structure) {
        r.structure = *e.structure;
        resolveStructure(renderer->context(), *r.structure);  // refused before anything changes
    }
    renderer->commit(r);
    described.tf = tf;
    described.tfColors = colors;
    if (e.structure) described.structure = *e.structure;
}

void Picture::setTransferFunction(const scene::TfChannels& tf) { commit({.tf = tf}); }

void Picture::setTfColors(scene::TfColors colors) { commit({.tfColors = colors}); }

nlohmann::ordered_json autoChoiceJson(const render::AutoChoice& c) {
    using Json = nlohmann::ordered_json;
    Json probes = Json::array();
    for (const render::AutoProbe& p : c.probes)
        probes.push_back({{"config", p.config.label()}, {"grid", p.config.grid},
                          {"subMajorants", scene::subMajorantsName(p.config.hasSubMajorants() ? p.config.subMajorants : 0)},
                          {"secondsPerSpp", p.secondsPerSpp},
                          {"variance", p.variance}, {"efficiency", p.efficiency}, {"predicted", p.predicted},
                          {"lookupsPerPath", p.lookupsPerPath}, {"stepsPerPath", p.stepsPerPath},
                          {"nullsPerPath", p.nullsPerPath}, {"wallSeconds", p.wallSeconds}, {"note", p.note}});
    Json lookupNs = Json::object();
    for (const auto& [sampler, ns] : c.lookupNs) lookupNs[scene::samplerName(sampler)] = ns;
    return {{"pick", c.config.label()},         {"pickGrid", c.config.grid},
            {"pickSubMajorants", scene::subMajorantsName(c.config.hasSubMajorants() ? c.config.subMajorants : 0)},
            {"probeSeconds", c.seconds},        {"probes", c.probes.size()},
            {"probeSize", c.probeSize},         {"lookupNsAboveReference", std::move(lookupNs)},
            {"probeDetails", std::move(probes)}};
}

nlohmann::ordered_json renderStats(const Picture& p, const scene::RenderOutput& out, const RenderTimes& times) {
    using Json = nlohmann::ordered_json;
    const render::Renderer& renderer = *p.renderer;
    const scene::VolumeScene& scene = renderer.scene();
    const scene::Volume& volume = *p.volume;
    const scene::StructureConfig& config = renderer.config();
    const scene::RenderSettings& rs = renderer.settings();
    gpu::Context& ctx = renderer.context();
    const auto& c = out.stats.counters;
    const double paths = double(out.stats.paths);
    glm::dvec3 meanRgb(0.0);
    for (const auto& px : out.mean.pixels) meanRgb += glm::dvec3(px);
    if (!out.mean.pixels.empty()) meanRgb /= double(out.mean.pixels.size());
    Json j;
    j["input"] = volume.model.source;
    j["field"] = volume.field().name;
    j["device"] = ctx.deviceReport().name;
    j["samplesPerInvocation"] = ctx.samplesPerInvocation();
    j["threads"] = threadCount();  // host threads of the parallel steps (AMRVK_THREADS)
    j["width"] = rs.width;
    j["height"] = rs.height;
    j["spp"] = out.spp;
    if (out.spp >= 2) j["meanRelativeError"] = scene::meanRelativeError(out);  // the image's noise
    j["mode"] = scene::modeName(rs.mode);
    j["traversal"] = scene::traversalName(config.traversal);
    j["sampler"] = scene::samplerName(config.sampler);
    j["backend"] = scene::backendName(config.backend);
    j["subMajorants"] = scene::subMajorantsName(config.hasSubMajorants() ? config.subMajorants : 0);
    j["backendRequested"] = scene::backendName(p.described.structure.backend);
    j["backendReason"] = p.report.backendReason;
    j["tf"] = p.described.tf.name;
    j["seconds"] = out.stats.gpuSeconds;
    j["wallSeconds"] = times.wallSeconds;
    j["pathsPerSecond"] = out.stats.gpuSeconds > 0 ? paths / out.stats.gpuSeconds : 0.0;
    j["paths"] = out.stats.paths;
    j["densityLookups"] = c[shared::kCounterDensityLookups];
    j["realCollisions"] = c[shared::kCounterRealCollisions];
    j["nullCollisions"] = c[shared::kCounterNullCollisions];
    j["traversalSteps"] = c[shared::kCounterTraversalSteps];
    j["majorantViolations"] = c[shared::kCounterMajorantViolations];
    j["nanSamples"] = c[shared::kCounterNanSamples];
    j["bounceLimitHits"] = c[shared::kCounterBounceLimitHits];
    j["trackingCapHits"] = c[shared::kCounterTrackingCapHits];
    j["subMajorantSkips"] = c[shared::kCounterSubMajorantSkips];  // collisions decided without a lookup
    // Where the time goes: per-path distributions (exact below 8, 4 bins per octave above), the
    // SIMD lanes' share of useful lookup work, and GPU time per lookup.
    const scene::PathStats& ps = out.stats.path;
    if (ps.paths() > 0) {
        auto distribution = [&](uint32_t q, uint64_t sum) {
            const scene::PathDistribution d = scene::pathDistribution(ps, q, sum);
            return Json{{"mean", d.mean}, {"p50", d.p50}, {"p90", d.p90}, {"p99", d.p99}, {"p999", d.p999}, {"max", d.max}};
        };
        j["perPath"] = {{"lookups", distribution(shared::kPathLookups, c[shared::kCounterDensityLookups])},
                        {"nullCollisions", distribution(shared::kPathNulls, c[shared::kCounterNullCollisions])},
                        {"realCollisions", distribution(shared::kPathReal, c[shared::kCounterRealCollisions])},
                        {"traversalSteps", distribution(shared::kPathSteps, c[shared::kCounterTraversalSteps])}};
    }
    j["shadowLookupShare"] = c[shared::kCounterDensityLookups] > 0
                                 ? double(c[shared::kCounterShadowLookups]) / double(c[shared::kCounterDensityLookups])
                                 : 0.0;
    const uint64_t slots = c[shared::kCounterLookupLaneSlots];
    j["lookupLaneUtilization"] = slots > 0 ? double(c[shared::kCounterDensityLookups]) / double(slots) : 0.0;
    j["gpuNanosecondsPerLookup"] =
        c[shared::kCounterDensityLookups] > 0 ? 1e9 * out.stats.gpuSeconds / double(c[shared::kCounterDensityLookups]) : 0.0;
    j["majorantSeconds"] = renderer.majorantSeconds();
    j["tfStructureUpdateSeconds"] = renderer.structureUpdateSeconds();
    j["activeTraversalBoxes"] = renderer.activeTraversalBoxes();
    if (const scene::SubMajorantGrid& sub = renderer.majorantPass().subMajorants(); !sub.words.empty())
        j["subMajorantGrid"] = {{"refinedMacrocells", sub.refined}, {"subBoxes", sub.subBoxes},
                             {"bytes", sub.memoryBytes()}, {"bytesWanted", sub.wanted},
                             {"buildSeconds", sub.buildSeconds}};
    if (const render::MajorantPass& m = renderer.majorantPass(); m.blockCount() > 0)  // grid-dda's blocks
        j["gridBlocks"] = {{"count", m.blockCount()}, {"empty", m.emptyBlocks()}, {"crossedInOneStep", m.gridBlocksUsed()}};
    j["readSeconds"] = p.report.readSeconds;           // read and per-cell validation
    j["firstSampleSeconds"] = times.firstSampleSeconds;  // command start to the first finished batch
    j["peakHostBytes"] = peakResidentBytes();           // so far (lavapipe: device memory included)
    j["structureBuildSeconds"] = p.report.buildSeconds;
    j["structureBuildSecondsPer"] = {
        {"bricks", volume.bricks.buildSeconds},          {"abrs", scene.buildSeconds.abrs},
        {"samplerBvh", scene.buildSeconds.samplerBvh},   {"macrocells", scene.buildSeconds.grid},
        {"traversalRanges", scene.buildSeconds.domains}, {"kdTree", renderer.kdTreeBuildSeconds()},
        {"denseGrid", scene.buildSeconds.dense},         {"brickGrid", scene.buildSeconds.brickGrid}};
    Json host = Json::object();
    for (const auto& [name, bytes] : scene.hostBytes()) host[name] = bytes;
    for (const auto& [name, bytes] : renderer.hostBytes()) host[name] = bytes;
    j["hostMemoryPerStructure"] = host;
    j["deviceMemoryBytes"] = ctx.memory().currentBytes();
    j["deviceMemoryPeakBytes"] = ctx.memory().peakBytes();
    Json device = Json::object();
    for (const auto& [name, usage] : ctx.memory().perResource())
        device[name] = {{"current", usage.current}, {"peak", usage.peak}};
    j["deviceMemoryPerResource"] = device;
    if (scene.grid) j["macrocellDims"] = Json::array({scene.grid->dims.x, scene.grid->dims.y, scene.grid->dims.z});
    j["meanRGB"] = Json::array({meanRgb.x, meanRgb.y, meanRgb.z});
    if (p.report.autoChoice) j["auto"] = autoChoiceJson(*p.report.autoChoice);
    return j;
}

}  // namespace amrvk::picture
