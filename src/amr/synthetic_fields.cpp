#include "amr/synthetic_fields.h"

#include <algorithm>

namespace amrvk::amr {

namespace {

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

// Sequential seeded numbers for the shape parameters of a field.
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

constexpr double kTwoPi = 6.283185307179586;

// Cloud shape.
constexpr float kCloudAmp = 1.0f;     // displacement amplitude at the root
constexpr double kCloudHurst = 0.45;  // amplitude halves every 1/H levels: rough, turbulent
constexpr float kCloudSigma = 1.2f;   // log-density contrast
constexpr double kCloudRadius = 0.32; // envelope radius (unit cube)

// Log-density drop of the cloud envelope at squared distance r2 (unit cube) from the centre.
double cloudEnvelope(double r2) {
    const double x = r2 / (kCloudRadius * kCloudRadius);
    return x * x;
}

constexpr double kShellsBackground = 0.02;
constexpr double kTorusValue = 1.0, kBallValue = 0.6;

}  // namespace

CloudField::CloudField(uint64_t seed, int rootLevel, double time)
    : mRoot(rootLevel), mSeedHash(mix64(seed + 0x1234567ull)) {
    SeedStream s(seed);
    mCentre = glm::dvec3(s.range(0.46, 0.54), s.range(0.46, 0.54), s.range(0.46, 0.54));
    // At T = 0 the offset is exactly 0 and the contrast exactly kCloudSigma: the field without time.
    const double phase = kTwoPi * time;
    mCentre += 0.06 * glm::dvec3(std::sin(phase), 1.0 - std::cos(phase), 0.0);
    mSigma = static_cast<float>(kCloudSigma * (1.0 + 0.25 * std::sin(phase)));
    mInvDomain = std::ldexp(1.0, -rootLevel);
    for (int l = 0; l <= rootLevel; ++l)
        mAmp[static_cast<size_t>(l)] =
            static_cast<float>(kCloudAmp * std::exp2(-kCloudHurst * (rootLevel - l)));
}

NodeEval CloudField::root(State& s) const {
    const int w = 1 << mRoot;
    for (int i = 0; i < 8; ++i) {
        glm::ivec3 p = childOffset(i) * w;
        s.g[static_cast<size_t>(i)] = kCloudAmp * signedUnit(hashPoint(mSeedHash, p, mRoot + 1));
        s.rho[static_cast<size_t>(i)] = density(p, s.g[static_cast<size_t>(i)]);
    }
    return evalCorners(s, {0, 0, 0}, mRoot);
}

void CloudField::refine(glm::ivec3 lower, int level, const State& s, State* cs, NodeEval* ce) const {
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

float CloudField::density(glm::ivec3 p, float g) const {
    glm::dvec3 d = glm::dvec3(p) * mInvDomain - mCentre;
    // Clamped at e^-40 so far-away values stay normal positive floats.
    return static_cast<float>(
        std::exp(std::max(-40.0, static_cast<double>(mSigma * g) - cloudEnvelope(glm::dot(d, d)))));
}

// Value: mean corner density. Score: an estimate of the density range inside the node,
// densityMax * (1 - exp(-logRange)), where the log-density range adds the corner range of g, the
// displacement the next level would add, and the envelope's exact range over the box (corners
// alone miss a bump inside a coarse node).
NodeEval CloudField::evalCorners(const State& s, glm::ivec3 lower, int level) const {
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
    const double eLo = cloudEnvelope(glm::dot(nearest, nearest));
    const double eHi = cloudEnvelope(glm::dot(farthest, farthest));
    const double unresolved = level > 0 ? mAmp[static_cast<size_t>(level)] : 0.0;
    const double logRange = mSigma * (gHi - gLo + unresolved) + (eHi - eLo);
    const double densityMax = std::exp(mSigma * (gHi + unresolved) - eLo);
    return {static_cast<float>(densityMax * -std::expm1(-logRange)), sum * 0.125f};
}

ShellsField::ShellsField(uint64_t seed, int rootLevel, double time) : PointwiseField(rootLevel) {
    SeedStream s(seed);
    mCentre = glm::dvec3(s.range(0.48, 0.52), s.range(0.48, 0.52), s.range(0.48, 0.52));
    const double breath = 1.0 + 0.15 * std::sin(kTwoPi * time);  // exactly 1 at T = 0
    for (size_t i = 0; i < kShells; ++i) {
        double r = (0.06 + 0.045 * static_cast<double>(i) + s.range(-0.007, 0.007)) * breath;
        double h = s.range(0.008, 0.016) * breath;
        mInner[i] = r - 0.5 * h;
        mOuter[i] = r + 0.5 * h;
        mValue[i] = s.range(0.3, 1.0);
    }
}

// Score: jump * width / (1 + (d / width)^6), d = distance of the centre to the boundary.
NodeEval ShellsField::eval(glm::ivec3 lower, int level) const {
    UnitNode n = unitNode(lower, level, mInvDomain);
    const double r = glm::length(n.centre - mCentre);
    const double invW = 1.0 / n.width;
    double value = kShellsBackground, score = 0;
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

TeapotField::TeapotField(uint64_t seed, int rootLevel, double majorRadiusUnits, double time)
    : PointwiseField(rootLevel) {
    SeedStream s(seed);
    mCentre = glm::dvec3(s.range(0.3, 0.7), s.range(0.3, 0.7), s.range(0.3, 0.7));
    double cz = s.range(-1.0, 1.0), phi = s.range(0.0, kTwoPi) + kTwoPi * time;  // phi unchanged at T = 0
    double sz = std::sqrt(1.0 - cz * cz);
    mAxis = glm::dvec3(sz * std::cos(phi), sz * std::sin(phi), cz);
    mMajor = majorRadiusUnits * mInvDomain;
    mMinor = 0.35 * mMajor;
    mBall = 0.6 * mMajor;
}

NodeEval TeapotField::eval(glm::ivec3 lower, int level) const {
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

double teapotMajorRadius(double leaves, int nodeRootLevel) {
    double r = 0.17 * std::sqrt(std::max(leaves, 8.0));
    return std::min(r, std::ldexp(1.0, nodeRootLevel) / 8.0);
}

}  // namespace amrvk::amr
