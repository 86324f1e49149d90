#include "amr/synthetic.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>

#include "core/error.h"
#include "core/file_io.h"

namespace fs = std::filesystem;

namespace amrvk::amr {

namespace {

constexpr uint64_t kBestFirstLeaves = 32768;  // exact count curve up to this many leaves
constexpr uint64_t kChunkCells = 1 << 20;     // cells buffered before a write
constexpr double kTolerance = 1.4;            // accepted count range [N / 1.4, 1.4 N]
constexpr int kMaxPasses = 40;
constexpr int kMaxBlockCells = 32;            // largest block edge B
// B is halved until N >= minBlocks * B^3: 64 blocks, 512 for the teapot, whose stadium alone
// takes a few hundred leaves (with fewer its object stays unresolved).
constexpr uint64_t kMinBlocks = 64, kMinTeapotBlocks = 512;

// ---- Hashing: splitmix64 finaliser; all randomness derives from (seed, position, level). ----

inline uint64_t mix64(uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ull;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebull;
    x ^= x >> 31;
    return x;
}

inline uint64_t hashPoint(uint64_t seedHash, glm::ivec3 p, int level) {
    uint64_t h = mix64(seedHash ^ static_cast<uint32_t>(p.x));
    h = mix64(h ^ (uint64_t{static_cast<uint32_t>(p.y)} << 1));
    h = mix64(h ^ (uint64_t{static_cast<uint32_t>(p.z)} << 2) ^ (uint64_t(level) << 40));
    return h;
}

// Uniform in [-1, 1), exact in float.
inline float signedUnit(uint64_t h) {
    return static_cast<float>(static_cast<int64_t>(h >> 40)) * (1.0f / 8388608.0f) - 1.0f;
}

// Sequential seeded numbers for the shape parameters of a kind.
class SeedStream {
public:
    explicit SeedStream(uint64_t seed) : mState(mix64(seed ^ 0x5851f42d4c957f2dull)) {}
    double uniform() {  // [0, 1)
        mState += 0x9e3779b97f4a7c15ull;
        return static_cast<double>(mix64(mState) >> 11) * 0x1.0p-53;
    }
    double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }

private:
    uint64_t mState;
};

struct NodeEval {
    float score = 0;  // refinement score; the node is refined when min(score, ancestors) >= t
    float value = 0;  // cell value (approximate cell average) if the node is a leaf
};

inline glm::ivec3 childOffset(int i) { return {i & 1, (i >> 1) & 1, (i >> 2) & 1}; }

// Node centre and width in the unit cube [0, 1)^3 of the domain.
struct UnitNode {
    glm::dvec3 centre;
    double width;
};
inline UnitNode unitNode(glm::ivec3 lower, int level, double invDomain) {
    const double w = std::ldexp(1.0, level);
    return {(glm::dvec3(lower) + 0.5 * w) * invDomain, w * invDomain};
}

inline double ramp(double x) { return std::clamp(x + 0.5, 0.0, 1.0); }

// ---- cloud: density = exp(sigma * g - (r / rc)^4), g hierarchical hashed value noise. ----
// Refining a node creates the 19 new points of its 3x3x3 grid: trilinear interpolation of the
// corner values plus a hashed displacement of amplitude A * 2^(-H * depth). Shared faces and
// edges use only their own corners, so same-level neighbours agree: g is continuous.
class CloudKind {
public:
    struct State {
        std::array<float, 8> g;    // noise at the corners, corner i at lower + width * offset(i)
        std::array<float, 8> rho;  // density at the corners
    };

    CloudKind(uint64_t seed, int rootLevel) : mRoot(rootLevel), mSeedHash(mix64(seed + 0x1234567ull)) {
        SeedStream s(seed);
        mCentre = glm::dvec3(s.range(0.46, 0.54), s.range(0.46, 0.54), s.range(0.46, 0.54));
        mInvDomain = std::ldexp(1.0, -rootLevel);
        for (int l = 0; l <= rootLevel; ++l)
            mAmp[static_cast<size_t>(l)] =
                static_cast<float>(kAmp * std::exp2(-kHurst * (rootLevel - l)));
    }
    int rootLevel() const { return mRoot; }

    NodeEval root(State& s) const {
        const int w = 1 << mRoot;
        for (int i = 0; i < 8; ++i) {
            glm::ivec3 p = childOffset(i) * w;
            s.g[static_cast<size_t>(i)] = kAmp * signedUnit(hashPoint(mSeedHash, p, mRoot + 1));
            s.rho[static_cast<size_t>(i)] = density(p, s.g[static_cast<size_t>(i)]);
        }
        return evalCorners(s, {0, 0, 0}, mRoot);
    }

    void refine(glm::ivec3 lower, int level, const State& s, State* cs, NodeEval* ce) const {
        const int half = 1 << (level - 1);
        const float amp = mAmp[static_cast<size_t>(level)];
        std::array<float, 27> g{}, rho{};
        auto at = [](int i, int j, int k) { return static_cast<size_t>(i + 3 * j + 9 * k); };
        for (int c = 0; c < 8; ++c) {
            glm::ivec3 o = childOffset(c) * 2;
            g[at(o.x, o.y, o.z)] = s.g[static_cast<size_t>(c)];
            rho[at(o.x, o.y, o.z)] = s.rho[static_cast<size_t>(c)];
        }
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 3; ++i) {
                    if (((i | j | k) & 1) == 0) continue;  // a corner: known
                    // Trilinear interpolation at a midpoint = mean of the corners it spans.
                    float sum = 0;
                    int n = 0;
                    for (int kk = (k == 1 ? 0 : k); kk <= (k == 1 ? 2 : k); kk += 2)
                        for (int jj = (j == 1 ? 0 : j); jj <= (j == 1 ? 2 : j); jj += 2)
                            for (int ii = (i == 1 ? 0 : i); ii <= (i == 1 ? 2 : i); ii += 2) {
                                sum += g[at(ii, jj, kk)];
                                ++n;
                            }
                    glm::ivec3 p = lower + glm::ivec3(i, j, k) * half;
                    float v = sum / static_cast<float>(n) +
                              amp * signedUnit(hashPoint(mSeedHash, p, level));
                    g[at(i, j, k)] = v;
                    rho[at(i, j, k)] = density(p, v);
                }
        for (int c = 0; c < 8; ++c) {
            glm::ivec3 o = childOffset(c);
            State& child = cs[c];
            for (int q = 0; q < 8; ++q) {
                glm::ivec3 oq = o + childOffset(q);
                child.g[static_cast<size_t>(q)] = g[at(oq.x, oq.y, oq.z)];
                child.rho[static_cast<size_t>(q)] = rho[at(oq.x, oq.y, oq.z)];
            }
            ce[c] = evalCorners(child, lower + o * half, level - 1);
        }
    }

private:
    static constexpr float kAmp = 1.0f;     // displacement amplitude at the root
    static constexpr double kHurst = 0.45;  // amplitude halves every 1/H levels: rough, turbulent
    static constexpr float kSigma = 1.2f;   // log-density contrast
    static constexpr double kRadius = 0.32; // envelope radius (unit cube)

    float density(glm::ivec3 p, float g) const {
        glm::dvec3 d = glm::dvec3(p) * mInvDomain - mCentre;
        // Clamped at e^-40 so far-away values stay normal positive floats.
        return static_cast<float>(std::exp(std::max(-40.0, static_cast<double>(kSigma * g) - envelope(glm::dot(d, d)))));
    }
    // Value: mean corner density. Score: an estimate of the density range inside the node,
    // densityMax * (1 - exp(-logRange)), where the log-density range adds the corner range of
    // g, the displacement the next level would add, and the envelope's exact range over the box
    // (corners alone miss a bump inside a coarse node).
    NodeEval evalCorners(const State& s, glm::ivec3 lower, int level) const {
        float gLo = s.g[0], gHi = s.g[0], sum = 0;
        for (size_t i = 0; i < 8; ++i) {
            gLo = std::min(gLo, s.g[i]);
            gHi = std::max(gHi, s.g[i]);
            sum += s.rho[i];
        }
        const double w = std::ldexp(1.0, level) * mInvDomain;
        const glm::dvec3 lo = glm::dvec3(lower) * mInvDomain, hi = lo + w;
        const glm::dvec3 nearest = glm::clamp(mCentre, lo, hi) - mCentre;
        const glm::dvec3 farthest = glm::max(glm::abs(lo - mCentre), glm::abs(hi - mCentre));
        const double eLo = envelope(glm::dot(nearest, nearest)), eHi = envelope(glm::dot(farthest, farthest));
        const double unresolved = level > 0 ? mAmp[static_cast<size_t>(level)] : 0.0;
        const double logRange = kSigma * (gHi - gLo + unresolved) + (eHi - eLo);
        const double densityMax = std::exp(kSigma * (gHi + unresolved) - eLo);
        return {static_cast<float>(densityMax * -std::expm1(-logRange)), sum * 0.125f};
    }
    // Log-density drop of the envelope at squared distance r2 (unit cube) from the centre.
    static double envelope(double r2) {
        const double x = r2 / (kRadius * kRadius);
        return x * x;
    }

    int mRoot;
    uint64_t mSeedHash;
    glm::dvec3 mCentre{0.5};
    double mInvDomain = 1;
    std::array<float, kMaxLevel + 2> mAmp{};
};

// Kinds whose node value and score depend on the node alone (no state passed to children):
// the octree interface in terms of Derived::eval(lower, level).
template <class Derived>
class PointwiseKind {
public:
    struct State {};

    explicit PointwiseKind(int rootLevel) : mRoot(rootLevel), mInvDomain(std::ldexp(1.0, -rootLevel)) {}
    int rootLevel() const { return mRoot; }
    NodeEval root(State&) const { return self().eval({0, 0, 0}, mRoot); }
    void refine(glm::ivec3 lower, int level, const State&, State*, NodeEval* ce) const {
        const int half = 1 << (level - 1);
        for (int c = 0; c < 8; ++c) ce[c] = self().eval(lower + childOffset(c) * half, level - 1);
    }

protected:
    const Derived& self() const { return static_cast<const Derived&>(*this); }
    int mRoot;
    double mInvDomain;  // 1 / domain width in finest units
};

// ---- shells: nested spherical bands, box-filtered to the cell width. ----
class ShellsKind : public PointwiseKind<ShellsKind> {
public:
    ShellsKind(uint64_t seed, int rootLevel) : PointwiseKind(rootLevel) {
        SeedStream s(seed);
        mCentre = glm::dvec3(s.range(0.48, 0.52), s.range(0.48, 0.52), s.range(0.48, 0.52));
        for (size_t i = 0; i < kShells; ++i) {
            double r = 0.06 + 0.045 * static_cast<double>(i) + s.range(-0.007, 0.007);
            double h = s.range(0.008, 0.016);
            mInner[i] = r - 0.5 * h;
            mOuter[i] = r + 0.5 * h;
            mValue[i] = s.range(0.3, 1.0);
        }
    }
private:
    friend class PointwiseKind;

    static constexpr size_t kShells = 5;
    static constexpr double kBackground = 0.02;

    // Score: jump * width / (1 + (d / width)^6), d = distance of the centre to the boundary.
    NodeEval eval(glm::ivec3 lower, int level) const {
        UnitNode n = unitNode(lower, level, mInvDomain);
        const double r = glm::length(n.centre - mCentre);
        const double invW = 1.0 / n.width;
        double value = kBackground, score = 0;
        for (size_t i = 0; i < kShells; ++i) {
            value += mValue[i] * (ramp((r - mInner[i]) * invW) - ramp((r - mOuter[i]) * invW));
            for (double b : {mInner[i], mOuter[i]}) {
                double x = (r - b) * invW;
                x *= x;
                score = std::max(score, mValue[i] * n.width / (1.0 + x * x * x));
            }
        }
        return {static_cast<float>(score), static_cast<float>(value)};
    }

    glm::dvec3 mCentre{0.5};
    std::array<double, kShells> mInner{}, mOuter{}, mValue{};
};

// ---- teapot in a stadium: a torus with a ball in its hole, tiny inside a huge domain. ----
// Only nodes whose circumscribed sphere meets the object's surface refine, so the coarse
// surroundings stay a handful of cells per level and leaves next to the object jump levels.
class TeapotKind : public PointwiseKind<TeapotKind> {
public:
    TeapotKind(uint64_t seed, int rootLevel, double majorRadiusUnits) : PointwiseKind(rootLevel) {
        SeedStream s(seed);
        mCentre = glm::dvec3(s.range(0.3, 0.7), s.range(0.3, 0.7), s.range(0.3, 0.7));
        double cz = s.range(-1.0, 1.0), phi = s.range(0.0, 6.283185307179586);
        double sz = std::sqrt(1.0 - cz * cz);
        mAxis = glm::dvec3(sz * std::cos(phi), sz * std::sin(phi), cz);
        mMajor = majorRadiusUnits * mInvDomain;
        mMinor = 0.35 * mMajor;
        mBall = 0.6 * mMajor;
    }
private:
    friend class PointwiseKind;

    static constexpr double kTorusValue = 1.0, kBallValue = 0.6;

    NodeEval eval(glm::ivec3 lower, int level) const {
        UnitNode n = unitNode(lower, level, mInvDomain);
        const glm::dvec3 q = n.centre - mCentre;
        const double along = glm::dot(q, mAxis);
        const double q2 = glm::dot(q, q);
        const double radial = std::sqrt(std::max(0.0, q2 - along * along));
        const double sdTorus = std::hypot(radial - mMajor, along) - mMinor;
        const double sdBall = std::sqrt(q2) - mBall;
        const bool torus = sdTorus < sdBall;
        const double sd = torus ? sdTorus : sdBall;
        const double inside = torus ? kTorusValue : kBallValue;
        // Near-constant low surroundings: 1% of the object value with a 10% linear drift.
        const double background = 0.01 * (1.0 + 0.1 * (n.centre.x - 0.5));
        const double value = background + (inside - background) * ramp(-sd / n.width);
        const double x = std::abs(sd) / (0.8660254037844386 * n.width);
        const double score = x <= 1.0 ? (inside - background) * n.width * (1.0 - 0.5 * x) : 0.0;
        return {static_cast<float>(score), static_cast<float>(value)};
    }

    glm::dvec3 mCentre{0.5}, mAxis{0, 0, 1};
    double mMajor = 0, mMinor = 0, mBall = 0;
};

// Teapot torus major radius in finest-node units for `leaves` target leaves in a domain
// 2^nodeRootLevel nodes wide: grows as sqrt(leaves) so that they refine the surface down to the
// finest or next node level (refining every touching node to the finest gives about 2x leaves).
double teapotMajorRadius(double leaves, int nodeRootLevel) {
    double r = 0.17 * std::sqrt(std::max(leaves, 8.0));
    return std::min(r, std::ldexp(1.0, nodeRootLevel) / 8.0);
}

// ---- Sinks: where the leaves of a depth-first pass go. Each stops the pass past `cap`. ----

using ProgressFn = std::function<void(std::string_view, double)>;

class SinkBase {
public:
    static constexpr bool kCountsOnly = false;  // true: takes whole blocks via countBlock()

    SinkBase(uint64_t cap, uint64_t expected, const ProgressFn* progress, std::string phase)
        : mCap(cap), mExpected(std::max<uint64_t>(expected, 1)), mProgress(progress), mPhase(std::move(phase)) {}
    bool stopped() const { return mCount > mCap; }
    uint64_t count() const { return mCount; }  // cells

protected:
    // Progress each time the cell count passes a multiple of 65536.
    void counted(uint64_t cells = 1) {
        const uint64_t before = mCount;
        mCount += cells;
        if ((before >> 16) != (mCount >> 16) && mProgress && *mProgress)
            (*mProgress)(mPhase, std::min(0.99, static_cast<double>(mCount) / static_cast<double>(mExpected)));
    }
    uint64_t mCount = 0;

private:
    uint64_t mCap, mExpected;
    const ProgressFn* mProgress;
    std::string mPhase;
};

class CountSink : public SinkBase {
public:
    static constexpr bool kCountsOnly = true;
    using SinkBase::SinkBase;
    void countBlock(uint64_t cells) { counted(cells); }
};

class LevelCounter {
public:
    void add(int level) { mPerLevel[static_cast<size_t>(level)]++; }
    void fill(SyntheticStats& st) const {
        st.cellsPerLevel.clear();
        st.minLevel = 0;
        st.maxLevel = 0;
        bool any = false;
        for (size_t l = 0; l < mPerLevel.size(); ++l) {
            if (mPerLevel[l] == 0) continue;
            if (!any) st.minLevel = static_cast<int>(l);
            st.maxLevel = static_cast<int>(l);
            any = true;
        }
        st.cellsPerLevel.assign(mPerLevel.begin(), mPerLevel.begin() + st.maxLevel + 1);
    }

private:
    std::array<uint64_t, kMaxLevel + 1> mPerLevel{};
};

class MemorySink : public SinkBase {
public:
    MemorySink(uint64_t cap, uint64_t expected, const ProgressFn* progress)
        : SinkBase(cap, expected, progress, "generating") {}
    void emit(const Cell& c, float v) {
        counted();
        mCells.push_back(c);
        mValues.push_back(v);
        mLevels.add(c.level);
    }
    const LevelCounter& levels() const { return mLevels; }
    std::vector<Cell> takeCells() { return std::move(mCells); }
    std::vector<float> takeValues() { return std::move(mValues); }

private:
    std::vector<Cell> mCells;
    std::vector<float> mValues;
    LevelCounter mLevels;
};

class FileSink : public SinkBase {
public:
    FileSink(const fs::path& cellsPath, const fs::path& scalarsPath, uint64_t cap, uint64_t expected,
             const ProgressFn* progress)
        : SinkBase(cap, expected, progress, "writing"), mCellsOut(cellsPath), mScalarsOut(scalarsPath) {
        mCells.reserve(kChunkCells);
        mValues.reserve(kChunkCells);
    }
    void emit(const Cell& c, float v) {
        counted();
        mCells.push_back(c);
        mValues.push_back(v);
        mLevels.add(c.level);
        if (mCells.size() == kChunkCells) flush();
    }
    uint64_t commit() {
        flush();
        mCellsOut.commit();
        mScalarsOut.commit();
        return mCellsOut.bytesWritten() + mScalarsOut.bytesWritten();
    }
    const LevelCounter& levels() const { return mLevels; }

private:
    void flush() {
        mCellsOut.writeSpan(std::span<const Cell>(mCells));
        mScalarsOut.writeSpan(std::span<const float>(mValues));
        mCells.clear();
        mValues.clear();
    }
    AtomicFileWriter mCellsOut, mScalarsOut;
    std::vector<Cell> mCells;
    std::vector<float> mValues;
    LevelCounter mLevels;
};

// ---- Traversals ----

// Depth-first pass: node refined iff level > blockShift and its effective score >= t; a leaf
// node becomes the (1 << blockShift)^3 cells of its complete subtree blockShift levels down.
template <class Kind, class Sink>
class DepthFirst {
public:
    DepthFirst(const Kind& kind, int blockShift, float threshold, Sink& sink)
        : mKind(kind), mBlockShift(blockShift), mT(threshold), mSink(sink) {}
    void run() {
        typename Kind::State s{};
        NodeEval e = mKind.root(s);
        visit({0, 0, 0}, mKind.rootLevel(), s, e.score, e.value);
    }

private:
    void visit(glm::ivec3 lower, int level, const typename Kind::State& s, float eff, float value) {
        if (mSink.stopped()) return;
        if (level <= mBlockShift || !(eff >= mT)) {
            if constexpr (Sink::kCountsOnly) mSink.countBlock(uint64_t{1} << (3 * mBlockShift));
            else emitBlock(lower, level, s, value, mBlockShift);
            return;
        }
        std::array<typename Kind::State, 8> cs{};
        std::array<NodeEval, 8> ce{};
        mKind.refine(lower, level, s, cs.data(), ce.data());
        const int half = 1 << (level - 1);
        for (int c = 0; c < 8; ++c)
            visit(lower + childOffset(c) * half, level - 1, cs[static_cast<size_t>(c)],
                  std::min(ce[static_cast<size_t>(c)].score, eff), ce[static_cast<size_t>(c)].value);
    }

    // The node's subtree `depth` levels down, every node refined: its leaves are the cells.
    void emitBlock(glm::ivec3 lower, int level, const typename Kind::State& s, float value, int depth) {
        if (depth == 0) {
            mSink.emit(Cell{lower, level}, value);
            return;
        }
        std::array<typename Kind::State, 8> cs{};
        std::array<NodeEval, 8> ce{};
        mKind.refine(lower, level, s, cs.data(), ce.data());
        const int half = 1 << (level - 1);
        for (int c = 0; c < 8; ++c)
            emitBlock(lower + childOffset(c) * half, level - 1, cs[static_cast<size_t>(c)],
                      ce[static_cast<size_t>(c)].value, depth - 1);
    }

    const Kind& mKind;
    int mBlockShift;  // log2 B
    float mT;
    Sink& mSink;
};

// Best-first expansion in decreasing effective score of the nodes above level blockShift;
// returns the scores of the expanded nodes (non-increasing). Leaves after k expansions: 1 + 7k.
// `exhausted`: nothing refinable is left.
template <class Kind>
std::vector<float> bestFirstScores(const Kind& kind, int blockShift, uint64_t maxLeaves, bool& exhausted) {
    struct Entry {
        float eff;
        uint64_t order;  // insertion order: deterministic tie break
        glm::ivec3 lower;
        int level;
        typename Kind::State state;
    };
    auto less = [](const Entry& a, const Entry& b) {
        return a.eff < b.eff || (a.eff == b.eff && a.order > b.order);
    };
    std::priority_queue<Entry, std::vector<Entry>, decltype(less)> heap(less);
    uint64_t order = 0;
    typename Kind::State rs{};
    NodeEval re = kind.root(rs);
    if (kind.rootLevel() > blockShift && re.score > 0)
        heap.push({re.score, order++, {0, 0, 0}, kind.rootLevel(), rs});
    std::vector<float> scores;
    uint64_t leaves = 1;
    while (!heap.empty() && leaves + 7 <= maxLeaves) {
        Entry e = heap.top();
        heap.pop();
        scores.push_back(e.eff);
        leaves += 7;
        std::array<typename Kind::State, 8> cs{};
        std::array<NodeEval, 8> ce{};
        kind.refine(e.lower, e.level, e.state, cs.data(), ce.data());
        if (e.level == blockShift + 1) continue;
        const int half = 1 << (e.level - 1);
        for (size_t c = 0; c < 8; ++c) {
            float eff = std::min(ce[c].score, e.eff);
            if (eff > 0)
                heap.push({eff, order++, e.lower + childOffset(static_cast<int>(c)) * half, e.level - 1, cs[c]});
        }
    }
    exhausted = heap.empty();
    return scores;
}

// ---- Threshold search over (t, count) samples; see synthetic.h. ----

struct Sample {
    double t;
    uint64_t count;
    bool capped;  // the pass stopped early: count is a lower bound
};

class ThresholdSearch {
public:
    void add(Sample s) { mSamples.push_back(s); }
    const std::vector<Sample>& samples() const { return mSamples; }

    uint64_t maxExactCount() const {
        uint64_t m = 0;
        for (const Sample& s : mSamples)
            if (!s.capped) m = std::max(m, s.count);
        return m;
    }
    bool reached(uint64_t target) const {
        for (const Sample& s : mSamples)
            if (s.count >= target) return true;
        return false;
    }
    // Two exact samples at clearly different t with one count below `target`: the domain is full.
    bool saturated(uint64_t target) const {
        for (const Sample& a : mSamples)
            for (const Sample& b : mSamples)
                if (!a.capped && !b.capped && a.count == b.count && a.count < target && b.t > 1.5 * a.t)
                    return true;
        return false;
    }

    // Threshold predicted to give `target` cells. With `accept` set, a measured threshold whose
    // count already lies in [target / 1.4, 1.4 target] is returned as it is (passes are exact).
    double predict(uint64_t target, bool accept) const {
        const double lt = std::log(static_cast<double>(target));
        auto logCount = [](const Sample& s) { return std::log(static_cast<double>(std::max<uint64_t>(s.count, 1))); };
        if (accept) {
            const Sample* best = nullptr;
            for (const Sample& s : mSamples)
                if (!s.capped && std::abs(logCount(s) - lt) <= std::log(kTolerance) &&
                    (!best || std::abs(logCount(s) - lt) < std::abs(logCount(*best) - lt)))
                    best = &s;
            if (best) return best->t;
        }
        // Bracket: the largest t giving too many cells, the smallest t giving too few.
        const Sample* lo = nullptr;
        const Sample* hi = nullptr;
        for (const Sample& s : mSamples) {
            if (s.count >= target) {
                if (!lo || s.t > lo->t) lo = &s;
            } else if (!s.capped && (!hi || s.t < hi->t)) {
                hi = &s;
            }
        }
        if (lo && hi) {
            // Log-log interpolation inside the bracket (a capped count is a lower bound), kept
            // 15% away from its ends so the bracket shrinks on every pass.
            const double a = std::log(lo->t), b = std::log(hi->t), span = b - a;
            const double ca = logCount(*lo), cb = logCount(*hi);
            const double f = ca > cb ? (ca - lt) / (ca - cb) : 0.5;
            return std::exp(a + span * std::clamp(f, 0.15, 0.85));
        }
        // Extrapolation from the nearest exact sample with the slope to the next one.
        std::vector<Sample> exact;
        for (const Sample& s : mSamples)
            if (!s.capped && s.count > 0) exact.push_back(s);
        if (exact.empty()) return lo ? lo->t * 4.0 : hi ? hi->t / 4.0 : 1.0;
        auto dist = [&](const Sample& s) { return std::abs(logCount(s) - lt); };
        std::sort(exact.begin(), exact.end(), [&](const Sample& x, const Sample& y) { return dist(x) < dist(y); });
        const Sample& a = exact[0];
        double slope = kDefaultSlope;
        for (size_t i = 1; i < exact.size(); ++i) {
            const Sample& b = exact[i];
            if (b.count == a.count || b.t == a.t) continue;
            double sl = (std::log(b.t) - std::log(a.t)) / (logCount(b) - logCount(a));
            if (std::isfinite(sl) && sl < 0) slope = std::max(sl, -4.0);
            break;
        }
        double guess = std::log(a.t) + slope * (lt - logCount(a));
        if (lo) guess = std::max(guess, std::log(lo->t) + std::log(1.05));
        if (hi) guess = std::min(guess, std::log(hi->t) - std::log(1.05));
        return std::exp(guess);
    }

private:
    static constexpr double kDefaultSlope = -0.5;
    std::vector<Sample> mSamples;
};

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct FinalPass {
    uint64_t count;
    bool stopped;    // passed the cap: abandoned
    bool committed;  // accepted and kept
};

// Chooses the threshold (see synthetic.h), then calls finalPass(t, cap, minAccept), which runs
// the writing pass, keeps its result only when it neither passed `cap` nor fell below
// `minAccept`, and reports what happened; retried with a corrected t until one is kept.
// All counts are cells, blockCells^3 per leaf.
template <class Kind, class Final>
void searchAndGenerate(const Kind& kind, int blockShift, const SyntheticParams& params,
                       SyntheticStats& stats, Final&& finalPass) {
    constexpr uint64_t kUnlimited = std::numeric_limits<uint64_t>::max() - 1;
    const uint64_t target = std::max<uint64_t>(params.cells, 1);
    const uint64_t leafCells = uint64_t{1} << (3 * blockShift);
    const uint64_t targetLeaves = std::max<uint64_t>(target / leafCells, 1);
    const uint64_t hiCount = static_cast<uint64_t>(std::floor(static_cast<double>(target) * kTolerance));
    const uint64_t loCount = static_cast<uint64_t>(std::ceil(static_cast<double>(target) / kTolerance));
    ThresholdSearch search;

    bool exhausted = false;
    std::vector<float> scores =
        bestFirstScores(kind, blockShift, std::min(targetLeaves, kBestFirstLeaves), exhausted);
    // Exact count at threshold scores[k]: every expanded node with a score >= it.
    auto exactAt = [&](size_t k) {
        size_t n = static_cast<size_t>(std::upper_bound(scores.begin(), scores.end(), scores[k],
                                                        std::greater<float>()) - scores.begin());
        return Sample{scores[k], leafCells * (1 + 7 * static_cast<uint64_t>(n)), false};
    };
    double threshold;
    bool exact = true;  // the best-first curve alone decides: accept its count as it is
    if (scores.empty()) {
        threshold = std::numeric_limits<double>::infinity();  // nothing to refine: one block
    } else if (exhausted || targetLeaves <= kBestFirstLeaves) {
        // The curve covers the target (or all there is): the count nearest N in log scale.
        size_t best = 0;
        double bestDist = std::numeric_limits<double>::infinity();
        for (size_t k = 0; k < scores.size(); ++k) {
            double d = std::abs(std::log(static_cast<double>(leafCells * (1 + 7 * (k + 1)))) -
                                std::log(static_cast<double>(target)));
            if (d < bestDist) bestDist = d, best = k;
        }
        threshold = scores[best];
    } else {
        exact = false;
        for (size_t k = scores.size(); k >= 1; k /= 2) search.add(exactAt(k - 1));
        // Counting stages at 8x the largest exact count until N / 8 is covered.
        while (search.maxExactCount() * 8 < target && !search.reached(target) &&
               !search.saturated(target) && stats.countingPasses < kMaxPasses) {
            const uint64_t stage = std::min(target, search.maxExactCount() * 8);
            const double t = search.predict(stage, false);
            CountSink counter(4 * stage, stage, &params.progress,
                              strCat("counting pass ", stats.countingPasses + 1));
            DepthFirst<Kind, CountSink>(kind, blockShift, static_cast<float>(t), counter).run();
            ++stats.countingPasses;
            search.add({t, counter.count(), counter.stopped()});
        }
        threshold = search.predict(target, true);
    }
    for (int attempt = 0;; ++attempt) {
        const bool last = exact || attempt >= 8 || stats.countingPasses >= kMaxPasses ||
                          search.saturated(target);
        stats.threshold = threshold;
        FinalPass r = finalPass(static_cast<float>(threshold), last ? kUnlimited : hiCount,
                                last ? uint64_t{0} : loCount);
        if (r.committed) break;
        ++stats.countingPasses;
        search.add({threshold, r.count, r.stopped});
        threshold = search.predict(target, true);
    }
}

template <class Sink>
void finishStats(SyntheticStats& stats, const Sink& sink) {
    stats.cells = sink.count();
    sink.levels().fill(stats);
}

}  // namespace

SyntheticKind parseSyntheticKind(std::string_view name) {
    if (name == "cloud") return SyntheticKind::Cloud;
    if (name == "shells") return SyntheticKind::Shells;
    if (name == "teapot") return SyntheticKind::Teapot;
    AMRVK_CHECK(false, "unknown synthetic kind '", name, "' (expected cloud, shells or teapot)");
    return SyntheticKind::Cloud;
}

std::string_view syntheticKindName(SyntheticKind kind) {
    switch (kind) {
        case SyntheticKind::Cloud: return "cloud";
        case SyntheticKind::Shells: return "shells";
        case SyntheticKind::Teapot: return "teapot";
    }
    return "?";
}

int syntheticBlockCells(const SyntheticParams& params) {
    const int requested = params.blockCells;
    AMRVK_CHECK(requested >= 1 && requested <= kMaxBlockCells && (requested & (requested - 1)) == 0,
                "--block ", requested, " is not a power of two in [1, ", kMaxBlockCells, "]");
    const uint64_t minBlocks = params.kind == SyntheticKind::Teapot ? kMinTeapotBlocks : kMinBlocks;
    uint64_t b = static_cast<uint64_t>(requested);
    while (b > 1 && params.cells < minBlocks * b * b * b) b /= 2;
    return static_cast<int>(b);
}

namespace {

int log2Exact(int powerOfTwo) { return std::countr_zero(static_cast<unsigned>(powerOfTwo)); }

// Depth of the node octree in node levels (finest nodes = blocks), before adding blockShift.
// `leaves`: the target count in blocks.
int nodeRootLevel(SyntheticKind kind, double leaves, int blockShift) {
    const double n = std::max(leaves, 8.0);
    int root = 0;
    switch (kind) {
        // Cloud and shells scores are scale-free, so the depth only caps the refinement; these
        // put the finest nodes at the finest or next level (measured for N = 1e3..1e7 with B = 1).
        // Cloud: volume-filling, most cells on the two finest levels.
        case SyntheticKind::Cloud: root = static_cast<int>(std::ceil(std::log2(n) / 3.0)) + 3; break;
        // Shells: surfaces, cells grow as 4^depth; at least 1.5 N possible cells.
        case SyntheticKind::Shells:
            root = std::max(static_cast<int>(std::lround(std::log2(n) / 2.0 - 0.75)),
                            static_cast<int>(std::ceil(std::log2(1.5 * n) / 3.0)));
            break;
        // A stadium at least 2^20 cells and 2^12 object sizes wide around an object of radius
        // ~sqrt(leaves) nodes.
        case SyntheticKind::Teapot:
            root = std::max(20 - blockShift,
                            static_cast<int>(std::ceil(std::log2(4.0 * teapotMajorRadius(leaves, 30)))) + 12);
            break;
    }
    return std::clamp(root, 3, kMaxLevel - blockShift);
}

// Target count in blocks of `blockCells`^3 cells.
double targetLeaves(const SyntheticParams& params, int blockCells) {
    return static_cast<double>(params.cells) / std::ldexp(1.0, 3 * log2Exact(blockCells));
}

}  // namespace

int syntheticRootLevel(const SyntheticParams& params) {
    const int block = syntheticBlockCells(params);
    const int shift = log2Exact(block);
    if (params.levels != 0) {
        AMRVK_CHECK(params.levels >= 1 && params.levels <= kMaxLevel + 1 - shift, "--levels ", params.levels,
                    " is outside [1, ", kMaxLevel + 1 - shift, "] for blocks of ", block, "^3 cells");
        return params.levels - 1 + shift;
    }
    return nodeRootLevel(params.kind, targetLeaves(params, block), shift) + shift;
}

namespace {

// Calls fn(kind, blockShift) with the concrete kind object for `params`.
template <class Fn>
void withKind(const SyntheticParams& params, Fn&& fn) {
    const int block = syntheticBlockCells(params);
    const int shift = log2Exact(block);
    const int root = syntheticRootLevel(params);
    switch (params.kind) {
        case SyntheticKind::Cloud: fn(CloudKind(params.seed, root), shift); break;
        case SyntheticKind::Shells: fn(ShellsKind(params.seed, root), shift); break;
        case SyntheticKind::Teapot:
            fn(TeapotKind(params.seed, root, teapotMajorRadius(targetLeaves(params, block), root - shift) * block),
               shift);
            break;
    }
}

void checkParams(const SyntheticParams& params) {
    AMRVK_CHECK(params.cells >= 1 && params.cells <= 100'000'000'000ull, "--cells ", params.cells,
                " is outside [1, 1e11]");
    syntheticRootLevel(params);
}

std::string fieldName(const SyntheticParams& params) {
    return params.field.empty() ? "scalars" : params.field;
}

}  // namespace

SyntheticStats generateSynthetic(const SyntheticParams& params, const fs::path& base) {
    const auto start = std::chrono::steady_clock::now();
    checkParams(params);
    fs::path cellsPath = base, scalarsPath = base;
    cellsPath += ".cells";
    scalarsPath += params.field.empty() ? ".scalars" : "." + params.field + ".scalars";
    { AtomicFileWriter probe(cellsPath); }  // fail before the search when BASE is not writable

    SyntheticStats stats;
    stats.blockCells = syntheticBlockCells(params);
    stats.rootLevel = syntheticRootLevel(params);
    withKind(params, [&](const auto& kind, int blockShift) {
        using Kind = std::decay_t<decltype(kind)>;
        searchAndGenerate(kind, blockShift, params, stats, [&](float t, uint64_t cap, uint64_t minAccept) {
            FileSink sink(cellsPath, scalarsPath, cap, params.cells, &params.progress);
            DepthFirst<Kind, FileSink>(kind, blockShift, t, sink).run();
            if (sink.stopped() || sink.count() < minAccept) return FinalPass{sink.count(), sink.stopped(), false};
            stats.bytes = sink.commit();
            finishStats(stats, sink);
            return FinalPass{sink.count(), false, true};
        });
    });
    stats.targetReached = static_cast<double>(stats.cells) * kTolerance >= static_cast<double>(params.cells);
    stats.seconds = secondsSince(start);
    return stats;
}

Model makeSyntheticModel(const SyntheticParams& params, SyntheticStats* statsOut) {
    const auto start = std::chrono::steady_clock::now();
    checkParams(params);
    SyntheticStats stats;
    stats.blockCells = syntheticBlockCells(params);
    stats.rootLevel = syntheticRootLevel(params);
    Model model;
    withKind(params, [&](const auto& kind, int blockShift) {
        using Kind = std::decay_t<decltype(kind)>;
        searchAndGenerate(kind, blockShift, params, stats, [&](float t, uint64_t cap, uint64_t minAccept) {
            MemorySink sink(cap, params.cells, &params.progress);
            DepthFirst<Kind, MemorySink>(kind, blockShift, t, sink).run();
            if (sink.stopped() || sink.count() < minAccept) return FinalPass{sink.count(), sink.stopped(), false};
            finishStats(stats, sink);
            model.cells = sink.takeCells();
            model.fields = {Field{fieldName(params), sink.takeValues()}};
            return FinalPass{sink.count(), false, true};
        });
    });
    model.format = "synthetic";
    model.source = strCat("synthetic ", syntheticKindName(params.kind), " (seed ", params.seed,
                          ", ", params.cells, " cells)");
    model.availableFields = {fieldName(params)};
    model.attributes = {{"kind", std::string(syntheticKindName(params.kind))},
                        {"seed", std::to_string(params.seed)},
                        {"rootLevel", std::to_string(stats.rootLevel)},
                        {"blockCells", std::to_string(stats.blockCells)},
                        {"threshold", strCat(stats.threshold)}};
    stats.targetReached = static_cast<double>(stats.cells) * kTolerance >= static_cast<double>(params.cells);
    stats.seconds = secondsSince(start);
    if (statsOut) *statsOut = stats;
    return model;
}

}  // namespace amrvk::amr
