#include "render/auto_select.h"

#include <algorithm>
#include <cmath>

#include "accel/range_grid.h"
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

// The --grid values (macrocells on the longest axis) of `factors` times auto's, in order, without
// auto's own, repeats, or fewer than 4. Relative to auto so a small data set is not probed at a
// resolution it has no cells for (Enzo DD0018's 137,502 cells at 256^3: 22 s of range build for
// a probe 4.9x slower than the best).
std::vector<std::string> gridChoices(const scene::Volume& volume, const std::vector<double>& factors) {
    const glm::ivec3 dims = accel::parseGridDims("auto", volume.bounds(), volume.cellCount);
    const int longest = std::max({dims.x, dims.y, dims.z});
    std::vector<std::string> out;
    for (double f : factors) {
        const int n = std::clamp(int(std::lround(f * double(longest))), 1, 4096);
        const std::string g = std::to_string(n);
        if (n >= 4 && n != longest && std::find(out.begin(), out.end(), g) == out.end()) out.push_back(g);
    }
    return out;
}

}  // namespace

const AutoProbe* pickAmongTies(const std::vector<AutoProbe>& probes, double tieTolerance) {
    auto structures = [](const scene::StructureConfig& c) {
        const scene::StructurePlan p = c.plan();
        return int(p.abrs) + int(p.samplerBvh) + int(p.samplerBoxes) + int(p.denseGrid) + int(p.boxMajorants) +
               int(p.boxesPerTf) + int(p.rayQueryCulling) + int(p.supportRangeQuery) + int(p.subMajorants);
    };
    double best = 0;
    for (const AutoProbe& p : probes)
        if (!p.predicted) best = std::max(best, p.efficiency);
    const AutoProbe* pick = nullptr;
    for (const AutoProbe& p : probes) {
        if (p.predicted || !(p.efficiency >= (1.0 - tieTolerance) * best)) continue;
        if (!pick || structures(p.config) < structures(pick->config) ||
            (structures(p.config) == structures(pick->config) && p.efficiency > pick->efficiency))
            pick = &p;
    }
    return pick;
}

int nextFinerGrid(const std::vector<AutoProbe>& probes, const scene::StructureConfig& combination, int finest,
                  int maxGrid) {
    const std::string finestGrid = std::to_string(finest);
    const AutoProbe* best = nullptr;
    const AutoProbe* atFinest = nullptr;
    for (const AutoProbe& p : probes) {
        if (p.predicted || !(p.efficiency > 0) || p.config.traversal != combination.traversal ||
            p.config.sampler != combination.sampler || p.config.backend != combination.backend ||
            p.config.subMajorants != combination.subMajorants)
            continue;
        if (!best || p.efficiency > best->efficiency) best = &p;
        if (p.config.grid == finestGrid) atFinest = &p;
    }
    const int next = std::min(2 * finest, maxGrid);
    if (finest <= 0 || !atFinest || atFinest != best || 2 * next < 3 * finest) return 0;  // not won, or hardly finer
    return next;
}

namespace {

// One --traversal auto search: the probe settings, the candidates the constraints and the data
// leave, and the probes so far with the best among them. autoSelect runs its steps in order.
class AutoSearch {
public:
    AutoSearch(Renderer& renderer, const scene::RenderSettings& settings, const AutoConstraints& constraints,
               const AutoOptions& options, const std::function<void(const std::string&)>& onProbe)
        : mRenderer(renderer), mConstraints(constraints), mOptions(options), mOnProbe(onProbe) {
        mCpu = renderer.context().deviceReport().type == "CPU";
        const int size = options.probeSize > 0 ? options.probeSize : mCpu ? 96 : 1024;
        // A CPU device's probe is small, so it takes more samples: its time is less noisy.
        mProbeSpp = options.probeSpp > 0 ? options.probeSpp : mCpu ? 16 : 2;
        AMRVK_CHECK(size >= 8 && mProbeSpp >= 2, "internal: probe too small");
        mSettings = settings;
        mSettings.width = mSettings.height = size;
        mSettings.seed = settings.seed + 7919u;
        mPathsPerSpp = double(size) * double(size);
        mChoice.probeSize = size;
        chooseCandidates();
        mBase.grid = constraints.grid.value_or("auto");
        mBase.kdLeaves = constraints.kdLeaves;
        mBase.subMajorants = constraints.subMajorants.value_or(0);
    }

    AutoChoice& choice() { return mChoice; }

    void measureTraversals();
    void measureAbrPairs();
    void predictSamplers();
    void measurePredictedBest();
    void measureGrids();
    void measureSubMajorants();
    void measureContendersAgain();

private:
    void chooseCandidates();
    void takeIfBest(const AutoProbe& p) {
        if (p.efficiency > mBestEfficiency) {
            mBestEfficiency = p.efficiency;
            mBestSecondsPerSpp = p.secondsPerSpp;
            mChoice.config = p.config;
        }
    }
    void consider(const AutoProbe& p) {
        takeIfBest(p);
        mChoice.probes.push_back(p);
    }
    // The best again, from the probes made so far (after some were superseded or averaged).
    void rescan(bool measuredOnly) {
        mBestEfficiency = -1;
        for (const AutoProbe& p : mChoice.probes)
            if (!(measuredOnly && p.predicted)) takeIfBest(p);
    }
    AutoProbe measure(const scene::StructureConfig& config, bool mayStop);

    Renderer& mRenderer;
    const AutoConstraints& mConstraints;
    const AutoOptions& mOptions;
    const std::function<void(const std::string&)>& mOnProbe;
    bool mCpu = false;
    uint32_t mProbeSpp = 0;
    scene::RenderSettings mSettings;  // the probes' (their size and seed)
    double mPathsPerSpp = 0;
    std::vector<scene::TraversalKind> mTraversals;
    std::vector<scene::SamplerKind> mSamplers;
    std::vector<scene::Backend> mBackends;
    scene::SamplerKind mReference = scene::SamplerKind::Grid;  // every traversal is measured with it
    scene::StructureConfig mBase;
    AutoChoice mChoice;
    double mBestEfficiency = -1, mBestSecondsPerSpp = 0;
    std::vector<AutoProbe> mMeasured;             // step 1's
    std::vector<scene::StructureConfig> mPaired;  // step 1b's
};

void AutoSearch::chooseCandidates() {
    mTraversals = mConstraints.traversal ? std::vector{*mConstraints.traversal} : scene::allTraversals();
    // Grid traversals and the grid sampler do not fit sparse data (scene::fittingTraversal): their
    // macrocells are mostly empty space. Not worth their probes.
    const amr::ModelSummary& summary = mRenderer.volume().summary;
    const bool sparse =
        scene::fittingTraversal(summary.leafVolume, summary.bounds.volume()) != scene::TraversalKind::GridDda;
    if (!mConstraints.traversal && sparse)
        std::erase_if(mTraversals, [](scene::TraversalKind t) {
            return t == scene::TraversalKind::GridDda || t == scene::TraversalKind::GridBvh;
        });
    mSamplers = mConstraints.sampler ? std::vector{*mConstraints.sampler} : scene::allSamplers();
    if (!mConstraints.sampler && sparse)
        std::erase_if(mSamplers, [](scene::SamplerKind s) { return s == scene::SamplerKind::Grid; });
    if (mConstraints.backend) {
        mBackends = {*mConstraints.backend};
    } else {
        // On CPU devices ray queries were measured 3-4x slower than the software BVH, which is
        // why --backend auto takes sw there (scene::resolveBackend); their probes would only cost
        // time (on lavapipe 10 s of Enzo's, 5.5 s for kdtree's one frame). --backend rq measures them.
        mBackends = {scene::Backend::Sw};
        if (mRenderer.context().hasRayQuery() && !mCpu) mBackends.push_back(scene::Backend::Rq);
    }
    // The reference sampler every traversal is measured with: the grid's where allowed.
    mReference = std::find(mSamplers.begin(), mSamplers.end(), scene::SamplerKind::Grid) != mSamplers.end()
                     ? scene::SamplerKind::Grid
                     : mSamplers.front();
}

AutoProbe AutoSearch::measure(const scene::StructureConfig& config, bool mayStop) {
    AutoProbe p;
    p.config = config;
    if (mOnProbe) mOnProbe(config.labelWithGrid());
    Timer wall;
    try {
        mRenderer.setStructure(config);
        scene::RenderOutput warm = mRenderer.render(mSettings, 1);
        if (mayStop && mBestSecondsPerSpp > 0 && warm.stats.gpuSeconds > mOptions.slowFactor * mBestSecondsPerSpp) {
            p.secondsPerSpp = warm.stats.gpuSeconds;
            p.note = "stopped: first frame " + std::to_string(warm.stats.gpuSeconds / mBestSecondsPerSpp) +
                     "x slower than the best";
        } else {
            // At least probeSpp samples, and enough to time minProbeSeconds: a fast combination's
            // few milliseconds are mostly noise (on lavapipe one combination measured 2.3-3.8 M
            // paths/s in runs of 0.1 s).
            const double minSeconds = mOptions.minProbeSeconds >= 0 ? mOptions.minProbeSeconds : mCpu ? 0.25 : 0.05;
            const double perSpp = std::max(warm.stats.gpuSeconds, 1e-6);
            const uint32_t spp = uint32_t(std::clamp(std::ceil(minSeconds / perSpp), double(mProbeSpp), 256.0));
            scene::RenderOutput out = mRenderer.render(mSettings, spp);
            const double paths = double(out.stats.paths);
            p.secondsPerSpp = out.stats.gpuSeconds / double(out.spp);
            p.variance = meanSampleVariance(out);
            p.lookupsPerPath = double(out.stats.counter(shared::kCounterDensityLookups)) / paths;
            p.stepsPerPath = double(out.stats.counter(shared::kCounterTraversalSteps)) / paths;
            p.nullsPerPath = double(out.stats.counter(shared::kCounterNullCollisions)) / paths;
            // A black image (variance 0) is scored by speed alone.
            const double v = p.variance > 0 ? p.variance : 1e-30;
            p.efficiency = p.secondsPerSpp > 0 ? 1.0 / (v * p.secondsPerSpp) : 0.0;
        }
    } catch (const Error& e) {
        p.note = e.what();
    }
    p.wallSeconds = wall.seconds();
    return p;
}

// 1. Every traversal (x back-end) with the reference sampler: time and counts per path.
void AutoSearch::measureTraversals() {
    for (scene::TraversalKind t : mTraversals)
        for (scene::Backend b : mBackends) {
            scene::StructureConfig c = mBase;
            c.traversal = t;
            c.sampler = mReference;
            c.backend = b;
            // Without a box hierarchy (grid-dda with the grid sampler) both back-ends do the same work.
            const scene::StructurePlan plan = c.plan();
            if (b == scene::Backend::Rq && !plan.boxMajorants && !plan.samplerBvh && !plan.samplerBoxes) continue;
            mMeasured.push_back(measure(c, true));
            consider(mMeasured.back());
        }
}

// 1b. abr traversal with the abr sampler samples in the ABR the traversal is in, with no point
//     query (tracking.glsl): not the abr sampler's cost under another traversal, so measured.
void AutoSearch::measureAbrPairs() {
    const bool abrSampler = std::find(mSamplers.begin(), mSamplers.end(), scene::SamplerKind::Abr) != mSamplers.end();
    if (abrSampler && mReference != scene::SamplerKind::Abr)
        for (const AutoProbe& t : std::vector<AutoProbe>(mMeasured))
            if (t.config.traversal == scene::TraversalKind::Abr && t.efficiency > 0) {
                scene::StructureConfig c = t.config;
                c.sampler = scene::SamplerKind::Abr;
                mPaired.push_back(c);
                consider(measure(c, true));
            }
    AMRVK_CHECK(mBestEfficiency > 0, "--traversal auto: no structure combination could render (first failure: ",
                mChoice.probes.empty() ? std::string("none tried") : mChoice.probes.front().note, ")");
}

// 2. The other samplers' unit costs, under the most efficient traversal measured (its paths, so
//    its lookups, are the same whatever the sampler). 3. Every other combination, predicted: its
//    traversal's time plus its lookups at the sampler's unit cost; the variance is the
//    traversal's (the same paths).
void AutoSearch::predictSamplers() {
    const AutoProbe anchor =
        *std::max_element(mMeasured.begin(), mMeasured.end(),
                          [](const AutoProbe& a, const AutoProbe& b) { return a.efficiency < b.efficiency; });
    std::vector<std::pair<scene::SamplerKind, double>> extraSecondsPerLookup;  // the unit costs
    for (scene::SamplerKind s : mSamplers) {
        if (s == mReference) continue;
        scene::StructureConfig c = anchor.config;
        c.sampler = s;
        const AutoProbe p = measure(c, false);
        consider(p);
        if (p.efficiency > 0 && anchor.lookupsPerPath > 0) {
            const double perLookup = (p.secondsPerSpp - anchor.secondsPerSpp) / (anchor.lookupsPerPath * mPathsPerSpp);
            extraSecondsPerLookup.emplace_back(s, perLookup);
            mChoice.lookupNs.emplace_back(s, 1e9 * perLookup);
        }
    }
    for (const AutoProbe& t : mMeasured) {
        if (!(t.efficiency > 0)) continue;
        for (const auto& [s, perLookup] : extraSecondsPerLookup) {
            if (t.config.traversal == anchor.config.traversal && t.config.backend == anchor.config.backend) continue;
            if (std::any_of(mPaired.begin(), mPaired.end(), [&](const scene::StructureConfig& c) {
                    return c.traversal == t.config.traversal && c.backend == t.config.backend && c.sampler == s;
                }))
                continue;  // measured in 1b
            AutoProbe p = t;
            p.config.sampler = s;
            p.predicted = true;
            p.wallSeconds = 0;
            // A sampler cheaper than the reference (perLookup < 0, or noise on few lookups) saves at
            // most half the traversal's time; a prediction is measured before it can win (below).
            p.secondsPerSpp =
                std::max(t.secondsPerSpp + t.lookupsPerPath * mPathsPerSpp * perLookup, 0.5 * t.secondsPerSpp);
            const double v = p.variance > 0 ? p.variance : 1e-30;
            p.efficiency = 1.0 / (v * p.secondsPerSpp);
            consider(p);
        }
    }
}

// 3b. A predicted winner is measured: the unit costs come from few lookups where the anchor makes
//     few, and their noise must not pick. Repeated while the best is a prediction.
void AutoSearch::measurePredictedBest() {
    for (int round = 0; round < 4; ++round) {
        const auto best =
            std::max_element(mChoice.probes.begin(), mChoice.probes.end(),
                             [](const AutoProbe& a, const AutoProbe& b) { return a.efficiency < b.efficiency; });
        if (!best->predicted) break;
        const scene::StructureConfig config = best->config;
        best->efficiency = 0;  // superseded by its measurement
        best->note = "predicted best, measured";
        rescan(false);
        consider(measure(config, true));
    }
}

// 4. Macrocell resolutions, measured: the winner's when it uses the grid, and those of the grid
//    traversals of step 1 that came within slowFactor of the best (the resolution can reorder
//    them: on a thin medium a coarse grid halves grid-dda's steps, not grid-bvh's). Ordered by
//    resolution, so each grid is built once.
void AutoSearch::measureGrids() {
    if (mConstraints.grid) return;
    std::vector<scene::StructureConfig> candidates;
    auto add = [&](const scene::StructureConfig& c) {
        if (!c.usesGrid()) return;
        for (const scene::StructureConfig& o : candidates)
            if (o.traversal == c.traversal && o.sampler == c.sampler && o.backend == c.backend) return;
        candidates.push_back(c);
    };
    add(mChoice.config);
    for (const AutoProbe& t : mMeasured)
        if (t.efficiency > 0 && t.efficiency * mOptions.slowFactor >= mBestEfficiency &&
            (t.config.traversal == scene::TraversalKind::GridDda ||
             t.config.traversal == scene::TraversalKind::GridBvh))
            add(t.config);
    const std::vector<std::string> grids = gridChoices(mRenderer.volume(), mOptions.gridFactors);
    for (const std::string& g : grids)
        for (scene::StructureConfig c : candidates) {
            c.grid = g;
            consider(measure(c, true));
        }
    // 4a. Finer still where the finest grid probed is a combination's best: a TF with narrow
    //     peaks gains from tight majorants (Enzo DD0018 under spiky: 256 macrocells 1.26x the
    //     default 65, benchmarks section 25). Doubling while the finest wins, up to
    //     options.maxExtendedGrid macrocells on the longest axis (a step of less than 1.5x is
    //     not taken).
    int finestProbed = 0;
    for (const std::string& g : grids) finestProbed = std::max(finestProbed, std::stoi(g));
    for (scene::StructureConfig c : candidates) {
        int finest = finestProbed;
        while ((finest = nextFinerGrid(mChoice.probes, c, finest, mOptions.maxExtendedGrid)) > 0) {
            c.grid = std::to_string(finest);
            consider(measure(c, true));
        }
    }
}

// 4c. Sub-majorants for every grid candidate at its best measured grid and at the default grid:
//     the same paths with fewer lookups where the TF makes macrocells loose, for a build per TF
//     edit.
void AutoSearch::measureSubMajorants() {
    if (mConstraints.subMajorants) return;
    std::vector<scene::StructureConfig> withSub;
    for (const AutoProbe& p : std::vector<AutoProbe>(mChoice.probes)) {
        if (p.predicted || !(p.efficiency > 0) || !p.config.usesGrid()) continue;
        scene::StructureConfig c = p.config;
        c.subMajorants = kSubMajorantsProbed;
        if (!c.hasSubMajorants() || p.efficiency * mOptions.slowFactor < mBestEfficiency) continue;
        // The combination's best grid only.
        const bool best = std::none_of(mChoice.probes.begin(), mChoice.probes.end(), [&](const AutoProbe& o) {
            return !o.predicted && o.config.traversal == c.traversal && o.config.sampler == c.sampler &&
                   o.config.backend == c.backend && o.config.subMajorants == 0 && o.efficiency > p.efficiency;
        });
        if (best && std::count(withSub.begin(), withSub.end(), c) == 0) withSub.push_back(c);
        // And at the default grid: sub-majorants tighten its macrocells where they are loose,
        // so it can beat the finer grid that won without them (and builds less).
        c.grid = mBase.grid;
        if (best && std::count(withSub.begin(), withSub.end(), c) == 0) withSub.push_back(c);
    }
    for (const scene::StructureConfig& c : withSub) {
        AutoProbe p = measure(c, true);
        if (p.efficiency > 0 && mRenderer.majorantPass().subMajorants().refined == 0) {
            p.efficiency = 0;  // the very paths and lookups of the probe without them: not a contender
            p.note = "no macrocell is loose under this TF: no sub-majorants built";
        }
        consider(p);
    }
}

// 4b. The contenders measured again: a CPU device's probes of one combination vary by up to 40%
//     from run to run (benchmarks section 25), enough to put a slower one first. Every measured
//     probe within contenderBand of the best (at most `contenders`, best first; none where one
//     is alone) is measured a second time, later, and keeps the mean of both GPU times and
//     variances. The best is then the best of these means.
void AutoSearch::measureContendersAgain() {
    std::vector<size_t> rivals;
    for (size_t i = 0; i < mChoice.probes.size(); ++i)
        if (!mChoice.probes[i].predicted && mChoice.probes[i].efficiency >= mOptions.contenderBand * mBestEfficiency)
            rivals.push_back(i);
    std::sort(rivals.begin(), rivals.end(),
              [&](size_t a, size_t b) { return mChoice.probes[a].efficiency > mChoice.probes[b].efficiency; });
    rivals.resize(std::min(rivals.size(), size_t(std::max(mOptions.contenders, 0))));
    if (rivals.size() < 2) return;
    for (size_t i : rivals) {
        const AutoProbe again = measure(mChoice.probes[i].config, false);
        AutoProbe& first = mChoice.probes[i];
        first.wallSeconds += again.wallSeconds;
        if (!(again.efficiency > 0)) continue;
        first.secondsPerSpp = 0.5 * (first.secondsPerSpp + again.secondsPerSpp);
        first.variance = 0.5 * (first.variance + again.variance);
        first.efficiency = 1.0 / ((first.variance > 0 ? first.variance : 1e-30) * first.secondsPerSpp);
        first.note = "measured twice: the mean of both";
    }
    rescan(true);
}

}  // namespace

AutoChoice autoSelect(Renderer& renderer, const scene::TransferFunction& tf, const scene::RenderSettings& settings,
                      const AutoConstraints& constraints, const AutoOptions& options,
                      const std::function<void(const std::string&)>& onProbe) {
    Timer total;
    AutoSearch search(renderer, settings, constraints, options, onProbe);
    renderer.setTransferFunction(tf);
    search.measureTraversals();
    search.measureAbrPairs();
    search.predictSamplers();
    search.measurePredictedBest();
    search.measureGrids();
    search.measureSubMajorants();
    search.measureContendersAgain();
    AutoChoice& choice = search.choice();
    // 5. Ties within the probes' noise go to the combination that builds less.
    if (const AutoProbe* pick = pickAmongTies(choice.probes, options.tieTolerance)) choice.config = pick->config;
    choice.seconds = total.seconds();
    Timer configure;
    renderer.setStructure(choice.config);
    choice.configureSeconds = configure.seconds();
    return std::move(choice);
}

}  // namespace amrvk::render
