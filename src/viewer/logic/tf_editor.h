#pragma once
// The transfer-function editor (window-free), as edits of a scene::TfChannels: the caller's TF
// (the viewer's session) is the one copy, in field units with its colour and opacity channels
// apart (ParaView's colour/opacity editor). The editor shows it over normalised positions in
// [0, 1] of the value range [lo, hi], which is the span of the opacity curve; the curve always has
// a node at each end and the colour map spans the range too (editable() makes any TF so). Inner
// nodes can be added, dragged (between their neighbours) and removed. Every edit keeps the TF
// valid. TfHistory gives undo/redo of whole TFs.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "scene/transfer_function.h"

namespace amrvk::viewer {

struct OpacityNode {
    float x = 0;      // position in [0, 1] of the value range
    float alpha = 0;  // >= 0: extinction per finest cell width before the density scale
};

class TfEditor {
public:
    // Edits `tf`, which must stay alive and be editable() (the constructor makes it so).
    explicit TfEditor(scene::TfChannels& tf);

    // `tf` in the editor's form: the same TF (the same values everywhere) with both channels on the
    // merged nodes when they differ, an opacity node at each end and the colour map spanning the
    // range (a one-position TF gets the range [p - 0.5, p + 0.5]).
    static scene::TfChannels editable(const scene::TfChannels& tf);
    // The built-in colour map and opacity of `preset` over [lo, hi], editable.
    static scene::TfChannels preset(std::string_view name, float lo, float hi);

    scene::TransferFunction transferFunction() const { return mTf.merged(); }

    // Colour map: a built-in preset's or any TfChannels' colours (positions renormalised onto the
    // value range); the opacity curve stays.
    void setColorMap(const scene::TfChannels& channels);
    const std::string& colorMapName() const { return mTf.name; }
    std::vector<float> colorPositions() const;  // normalised
    const std::vector<glm::vec3>& colors() const { return mTf.colors; }
    // Colour and opacity of a loaded preset (positions renormalised), keeping the value range.
    void setPreset(const scene::TfChannels& channels);

    std::vector<OpacityNode> opacity() const;  // normalised positions
    // Inserts a node in order (x clamped to [0, 1], alpha to >= 0); returns its index.
    size_t addNode(float x, float alpha);
    // Removes node i; the end nodes stay (throws for them and for an index out of range).
    void removeNode(size_t i);
    // Moves node i: x stays between its neighbours (the end nodes keep x), alpha >= 0.
    void moveNode(size_t i, float x, float alpha);
    // The node nearest to (x, alpha) within the tolerances, if any (for picking with the mouse).
    std::optional<size_t> nodeNear(float x, float alpha, float toleranceX, float toleranceAlpha) const;

    float lo() const { return mTf.opacityPositions.front(); }
    float hi() const { return mTf.opacityPositions.back(); }
    // lo < hi, both finite; throws otherwise (one line naming the values). Maps every node.
    void setRange(float lo, float hi);

    // The current TF as a ParaView JSON preset file's text (field units, channels kept apart).
    std::string toParaViewJson(const std::string& name) const;

private:
    float toValue(float x) const;  // normalised -> field units (x = 0, 1 exactly lo, hi)
    float toX(float value) const;  // field units -> normalised
    scene::TfChannels& mTf;
};

// Undo/redo over whole TFs: push() after each finished edit (a drag counts once).
class TfHistory {
public:
    explicit TfHistory(scene::TfChannels initial) : mStates{std::move(initial)} {}
    const scene::TfChannels& current() const { return mStates[mAt]; }
    void push(const scene::TfChannels& state);
    bool canUndo() const { return mAt > 0; }
    bool canRedo() const { return mAt + 1 < mStates.size(); }
    const scene::TfChannels& undo();
    const scene::TfChannels& redo();

private:
    std::vector<scene::TfChannels> mStates;
    size_t mAt = 0;
    static constexpr size_t kMaxStates = 256;
};

}  // namespace amrvk::viewer
