#pragma once
// Passes over the node octree of a synthetic field (amr/synthetic.h), generic in the field and in
// where the leaves go. Nodes are cubes in finest-cell units over [0, 2^rootLevel)^3: node
// (lower, level) is 2^level wide and its child c sits at lower + childOffset(c) * 2^(level - 1).
// A NodeField (amr/synthetic_fields.h) provides
//   struct State;                   what a node hands to its children (may be empty)
//   int rootLevel() const;
//   NodeEval root(State& s) const;  the root's evaluation; fills its state
//   void refine(glm::ivec3 lower, int level, const State& s, State* childStates,
//               NodeEval* childEvals) const;  its 8 children, in childOffset order
// A node's effective score is the minimum of its own and its ancestors' scores (monotone).
// Sinks (amr/cell_sinks.h) take the leaves: emit(cell, value) per cell, or countBlock(cells)
// per block when Sink::kCountsOnly; a pass stops early once sink.stopped().
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <queue>
#include <vector>

#include "amr/model.h"

namespace amrvk::amr {

struct NodeEval {
    float score = 0;  // refinement score; the node is refined when min(score, ancestors) >= t
    float value = 0;  // cell value (approximate cell average) if the node is a leaf
};

// Child i's offset in half-widths: bit 0 = x, bit 1 = y, bit 2 = z (x fastest).
inline glm::ivec3 childOffset(int i) { return {i & 1, (i >> 1) & 1, (i >> 2) & 1}; }

// Refines node (lower, level) and calls visit(childLower, childState, childEval) for its 8
// children in childOffset order.
template <class NodeField, class Visit>
void forEachChild(const NodeField& field, glm::ivec3 lower, int level,
                  const typename NodeField::State& s, Visit&& visit) {
    std::array<typename NodeField::State, 8> cs{};
    std::array<NodeEval, 8> ce{};
    field.refine(lower, level, s, cs.data(), ce.data());
    const int half = 1 << (level - 1);
    for (size_t c = 0; c < 8; ++c) visit(lower + childOffset(static_cast<int>(c)) * half, cs[c], ce[c]);
}

// Depth-first pass: node refined iff level > blockShift and its effective score >= t; a leaf
// node becomes the (1 << blockShift)^3 cells of its complete subtree blockShift levels down.
// Cells come depth-first (a block is the depth-first subtree of its leaf node).
template <class NodeField, class Sink>
class DepthFirst {
public:
    using State = typename NodeField::State;

    DepthFirst(const NodeField& field, int blockShift, float threshold, Sink& sink)
        : mField(field), mBlockShift(blockShift), mT(threshold), mSink(sink) {}
    void run() {
        State s{};
        NodeEval e = mField.root(s);
        visit({0, 0, 0}, mField.rootLevel(), s, e.score, e.value);
    }

private:
    void visit(glm::ivec3 lower, int level, const State& s, float eff, float value) {
        if (mSink.stopped()) return;
        if (level <= mBlockShift || !(eff >= mT)) {
            if constexpr (Sink::kCountsOnly) mSink.countBlock(uint64_t{1} << (3 * mBlockShift));
            else emitBlock(lower, level, s, value, mBlockShift);
            return;
        }
        forEachChild(mField, lower, level, s, [&](glm::ivec3 childLower, const State& cs, const NodeEval& ce) {
            visit(childLower, level - 1, cs, std::min(ce.score, eff), ce.value);
        });
    }

    // The node's subtree `depth` levels down, every node refined: its leaves are the cells.
    void emitBlock(glm::ivec3 lower, int level, const State& s, float value, int depth) {
        if (depth == 0) {
            mSink.emit(Cell{lower, level}, value);
            return;
        }
        forEachChild(mField, lower, level, s, [&](glm::ivec3 childLower, const State& cs, const NodeEval& ce) {
            emitBlock(childLower, level - 1, cs, ce.value, depth - 1);
        });
    }

    const NodeField& mField;
    int mBlockShift;  // log2 B
    float mT;
    Sink& mSink;
};

// Runs one depth-first pass of `field` at threshold t into `sink`.
template <class NodeField, class Sink>
void runDepthFirst(const NodeField& field, int blockShift, float threshold, Sink& sink) {
    DepthFirst<NodeField, Sink>(field, blockShift, threshold, sink).run();
}

// Best-first expansion in decreasing effective score of the nodes above level blockShift;
// returns the scores of the expanded nodes (non-increasing). Leaves after k expansions: 1 + 7k.
// `exhausted`: nothing refinable is left.
template <class NodeField>
std::vector<float> bestFirstScores(const NodeField& field, int blockShift, uint64_t maxLeaves, bool& exhausted) {
    using State = typename NodeField::State;
    struct Entry {
        float eff;
        uint64_t order;  // insertion order: deterministic tie break
        glm::ivec3 lower;
        int level;
        State state;
    };
    auto less = [](const Entry& a, const Entry& b) {
        return a.eff < b.eff || (a.eff == b.eff && a.order > b.order);
    };
    std::priority_queue<Entry, std::vector<Entry>, decltype(less)> heap(less);
    uint64_t order = 0;
    State rs{};
    NodeEval re = field.root(rs);
    if (field.rootLevel() > blockShift && re.score > 0)
        heap.push({re.score, order++, {0, 0, 0}, field.rootLevel(), rs});
    std::vector<float> scores;
    uint64_t leaves = 1;
    while (!heap.empty() && leaves + 7 <= maxLeaves) {
        Entry e = heap.top();
        heap.pop();
        scores.push_back(e.eff);
        leaves += 7;
        if (e.level == blockShift + 1) continue;  // its children are blocks: never expanded
        forEachChild(field, e.lower, e.level, e.state, [&](glm::ivec3 childLower, const State& cs, const NodeEval& ce) {
            const float eff = std::min(ce.score, e.eff);
            if (eff > 0) heap.push({eff, order++, childLower, e.level - 1, cs});
        });
    }
    exhausted = heap.empty();
    return scores;
}

}  // namespace amrvk::amr
