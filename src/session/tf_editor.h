#pragma once
// The transfer-function editor's model (window-free): a colour map and an opacity curve over
// normalised positions in [0, 1], and the value range [lo, hi] they are mapped onto (ParaView's
// colour/opacity editor). The opacity curve always has a node at 0 and at 1; the nodes in between
// can be added, dragged (between their neighbours) and removed. Every edit keeps the state valid;
// transferFunction() gives the TF the renderer uses. History gives undo/redo of whole states.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "scene/transfer_function.h"

namespace amrvk::session {

struct OpacityNode {
    float x = 0;      // position in [0, 1] of the value range
    float alpha = 0;  // >= 0: extinction per finest cell width before the density scale
};

class TfEditor {
public:
    // The built-in colour map and opacity of `preset` over [lo, hi].
    TfEditor(std::string_view preset, float lo, float hi);
    // Takes a TF as it is: its node range becomes the value range, both channels its nodes.
    explicit TfEditor(const scene::TransferFunction& tf);

    scene::TransferFunction transferFunction() const;

    // Colour map: a built-in preset's or any TfChannels' colours (positions renormalised to
    // [0, 1]); the opacity curve stays.
    void setColorMap(const scene::TfChannels& channels);
    const std::string& colorMapName() const { return mColorMap.name; }
    const std::vector<float>& colorPositions() const { return mColorMap.colorPositions; }
    const std::vector<glm::vec3>& colors() const { return mColorMap.colors; }
    // Colour and opacity of a loaded preset (positions renormalised), keeping the value range.
    void setPreset(const scene::TfChannels& channels);

    const std::vector<OpacityNode>& opacity() const { return mOpacity; }
    // Inserts a node in order (x clamped to [0, 1], alpha to >= 0); returns its index.
    size_t addNode(float x, float alpha);
    // Removes node i; the end nodes stay (throws for them and for an index out of range).
    void removeNode(size_t i);
    // Moves node i: x stays between its neighbours (the end nodes keep x), alpha >= 0.
    void moveNode(size_t i, float x, float alpha);
    // The node nearest to (x, alpha) within the tolerances, if any (for picking with the mouse).
    std::optional<size_t> nodeNear(float x, float alpha, float toleranceX, float toleranceAlpha) const;

    float lo() const { return mLo; }
    float hi() const { return mHi; }
    // lo < hi, both finite; throws otherwise (one line naming the values).
    void setRange(float lo, float hi);

    // The current TF as a ParaView JSON preset file's text (field units, channels kept apart).
    std::string toParaViewJson(const std::string& name) const;

    // Both channels in field units (positions mapped onto the value range).
    scene::TfChannels channels() const;

private:
    scene::TfChannels mColorMap;     // colour channel only, positions in [0, 1]
    std::vector<OpacityNode> mOpacity;
    float mLo = 0, mHi = 1;
};

// Undo/redo over whole editor states: push() after each finished edit (a drag counts once).
class TfHistory {
public:
    explicit TfHistory(TfEditor initial) : mStates{std::move(initial)} {}
    const TfEditor& current() const { return mStates[mAt]; }
    void push(const TfEditor& state);
    bool canUndo() const { return mAt > 0; }
    bool canRedo() const { return mAt + 1 < mStates.size(); }
    const TfEditor& undo();
    const TfEditor& redo();

private:
    std::vector<TfEditor> mStates;
    size_t mAt = 0;
    static constexpr size_t kMaxStates = 256;
};

}  // namespace amrvk::session
