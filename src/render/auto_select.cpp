#include "render/auto_select.h"

#include <cmath>

#include "core/error.h"
#include "core/stats.h"

namespace amrvk::render {

namespace {

// Mean over pixels and channels of the per-sample variance (= spp x variance of the mean).
double meanSampleVariance(const scene::RenderOutput& out) {
    const std::vector<float> v = scene::varianceOfMean(out);
    double sum = 0;
    for (float x : v) sum += x;
    return v.empty() ? 0.0 : sum / double(v.size()) * double(out.spp);
}

}  // namespace

AutoChoice autoSelect(Renderer& renderer, const scene::TransferFunction& tf,
                      const scene::RenderSettings& settings, const AutoConstraints& constraints,
                      const AutoOptions& options, const std::function<void(const std::string&)>& onProbe) {
    AMRVK_CHECK(options.probeSize >= 8 && options.probeSpp >= 2, "internal: probe too small");
    Timer total;
    scene::RenderSettings rs = settings;
    rs.width = rs.height = options.probeSize;
    rs.seed = settings.seed + 7919u;

    std::vector<scene::TraversalKind> traversals =
        constraints.traversal ? std::vector{*constraints.traversal} : scene::allTraversals();
    // Grid traversals and the grid sampler do not fit sparse data (scene::fittingTraversal): their
    // macrocells are mostly empty space. Not worth their probes.
    const amr::ModelSummary& summary = renderer.volume().summary;
    const bool sparse =
        scene::fittingTraversal(summary.leafVolume, summary.bounds.volume()) != scene::TraversalKind::GridDda;
    if (!constraints.traversal && sparse)
        std::erase_if(traversals, [](scene::TraversalKind t) {
            return t == scene::TraversalKind::GridDda || t == scene::TraversalKind::GridBvh;
        });
    std::vector<scene::SamplerKind> samplers =
        constraints.sampler ? std::vector{*constraints.sampler} : scene::allSamplers();
    if (!constraints.sampler && sparse)
        std::erase_if(samplers, [](scene::SamplerKind s) { return s == scene::SamplerKind::Grid; });
    std::vector<scene::Backend> backends;
    if (constraints.backend) backends = {*constraints.backend};
    else {
        backends = {scene::Backend::Sw};
        if (renderer.context().hasRayQuery()) backends.push_back(scene::Backend::Rq);
    }

    renderer.setTransferFunction(tf);
    AutoChoice choice;
    double bestEfficiency = -1, bestSecondsPerSpp = 0;
    auto probe = [&](const scene::StructureConfig& config) {
        AutoProbe p;
        p.config = config;
        if (onProbe) onProbe(config.labelWithGrid());
        Timer wall;
        try {
            renderer.setStructure(config);
            scene::RenderOutput warm = renderer.render(rs, 1);
            if (bestSecondsPerSpp > 0 && warm.stats.gpuSeconds > options.slowFactor * bestSecondsPerSpp) {
                p.secondsPerSpp = warm.stats.gpuSeconds;
                p.note = "stopped: first frame " + std::to_string(warm.stats.gpuSeconds / bestSecondsPerSpp) +
                         "x slower than the best";
            } else {
                scene::RenderOutput out = renderer.render(rs, options.probeSpp);
                p.secondsPerSpp = out.stats.gpuSeconds / double(out.spp);
                p.variance = meanSampleVariance(out);
                // A black image (variance 0) is scored by speed alone.
                const double v = p.variance > 0 ? p.variance : 1e-30;
                p.efficiency = p.secondsPerSpp > 0 ? 1.0 / (v * p.secondsPerSpp) : 0.0;
            }
        } catch (const Error& e) {
            p.note = e.what();
        }
        p.wallSeconds = wall.seconds();
        if (p.efficiency > bestEfficiency) {
            bestEfficiency = p.efficiency;
            bestSecondsPerSpp = p.secondsPerSpp;
            choice.config = p.config;
        }
        choice.probes.push_back(p);
    };

    scene::StructureConfig base;
    base.grid = constraints.grid.value_or("auto");
    base.kdLeaves = constraints.kdLeaves;
    for (scene::TraversalKind t : traversals)
        for (scene::SamplerKind s : samplers)
            for (scene::Backend b : backends) {
                scene::StructureConfig c = base;
                c.traversal = t;
                c.sampler = s;
                c.backend = b;
                probe(c);
            }
    AMRVK_CHECK(bestEfficiency > 0, "--traversal auto: no structure combination could render (first failure: ",
                choice.probes.empty() ? std::string("none tried") : choice.probes.front().note, ")");
    if (choice.config.usesGrid() && !constraints.grid) {
        const scene::StructureConfig winner = choice.config;
        for (const std::string& g : options.gridChoices) {
            scene::StructureConfig c = winner;
            c.grid = g;
            probe(c);
        }
    }
    choice.seconds = total.seconds();
    Timer configure;
    renderer.setStructure(choice.config);
    choice.configureSeconds = configure.seconds();
    return choice;
}

}  // namespace amrvk::render
