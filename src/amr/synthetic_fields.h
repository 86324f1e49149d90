#pragma once
// The procedural fields of "amrvk gen" (amr/synthetic.h), evaluated on the nodes of the octree
// that amr/octree_refine.h walks (the NodeField interface described there). Positions are in
// finest-cell units over the domain [0, 2^rootLevel)^3; shapes are laid out in the unit cube of
// the domain. Everything derives from the seed: same seed and domain = the same values bit for bit.
#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "amr/model.h"
#include "amr/octree_refine.h"

namespace amrvk::amr {

// ---- cloud: density = exp(sigma * g - (r / rc)^4), g hierarchical hashed value noise. ----
// Refining a node creates the 19 new points of its 3x3x3 grid: trilinear interpolation of the
// corner values plus a hashed displacement of amplitude A * 2^(-H * depth). Shared faces and
// edges use only their own corners, so same-level neighbours agree: g is continuous.
class CloudField {
public:
    struct State {
        std::array<float, 8> g;    // noise at the corners, corner i at lower + width * offset(i)
        std::array<float, 8> rho;  // density at the corners
    };

    CloudField(uint64_t seed, int rootLevel, double time = 0);
    int rootLevel() const { return mRoot; }
    NodeEval root(State& s) const;
    void refine(glm::ivec3 lower, int level, const State& s, State* cs, NodeEval* ce) const;

private:
    float density(glm::ivec3 p, float g) const;
    NodeEval evalCorners(const State& s, glm::ivec3 lower, int level) const;

    int mRoot;
    uint64_t mSeedHash;
    glm::dvec3 mCentre{0.5};
    double mInvDomain = 1;
    float mSigma = 1;                         // log-density contrast at this time
    std::array<float, kMaxLevel + 2> mAmp{};  // displacement amplitude per node level
};

// Fields whose node value and score depend on the node alone (no state passed to children):
// the NodeField interface in terms of Derived::eval(lower, level).
template <class Derived>
class PointwiseField {
public:
    struct State {};

    explicit PointwiseField(int rootLevel) : mRoot(rootLevel), mInvDomain(std::ldexp(1.0, -rootLevel)) {}
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
class ShellsField : public PointwiseField<ShellsField> {
public:
    ShellsField(uint64_t seed, int rootLevel, double time = 0);

private:
    friend class PointwiseField;
    static constexpr size_t kShells = 5;

    NodeEval eval(glm::ivec3 lower, int level) const;

    glm::dvec3 mCentre{0.5};
    std::array<double, kShells> mInner{}, mOuter{}, mValue{};
};

// ---- teapot in a stadium: a torus with a ball in its hole, tiny inside a huge domain. ----
// Only nodes whose circumscribed sphere meets the object's surface refine, so the coarse
// surroundings stay a handful of cells per level and leaves next to the object jump levels.
class TeapotField : public PointwiseField<TeapotField> {
public:
    // majorRadiusUnits: torus major radius in finest-cell units (teapotMajorRadius * B).
    TeapotField(uint64_t seed, int rootLevel, double majorRadiusUnits, double time = 0);

private:
    friend class PointwiseField;

    NodeEval eval(glm::ivec3 lower, int level) const;

    glm::dvec3 mCentre{0.5}, mAxis{0, 0, 1};
    double mMajor = 0, mMinor = 0, mBall = 0;
};

// Teapot torus major radius in finest-node units for `leaves` target leaves in a domain
// 2^nodeRootLevel nodes wide: grows as sqrt(leaves) so that they refine the surface down to the
// finest or next node level (refining every touching node to the finest gives about 2x leaves).
double teapotMajorRadius(double leaves, int nodeRootLevel);

}  // namespace amrvk::amr
