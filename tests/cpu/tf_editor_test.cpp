// The TF editor, as edits of a TfChannels: presets and TFs become editable without changing the
// TF, nodes are added in order, dragged only between their neighbours, the ends stay, the range
// maps positions, ParaView JSON written by it reads back to the same TF, every preset of a
// ParaView file is listed (unusable ones skipped with a reason), undo/redo restore whole TFs, and
// the edited TF is the caller's (no second copy).
#include "viewer/logic/tf_editor.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"
#include "test_data.h"

using namespace amrvk;
using viewer::TfEditor;

namespace {
void expectSameTf(const scene::TransferFunction& a, const scene::TransferFunction& b, float tol) {
    ASSERT_EQ(a.nodeCount(), b.nodeCount());
    for (size_t i = 0; i < a.nodeCount(); ++i) {
        EXPECT_NEAR(a.positions()[i], b.positions()[i], tol) << "node " << i;
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.colors()[i][c], b.colors()[i][c], 1e-6f) << "node " << i;
    }
}
// The same TF as a function: equal values at many points (node sets may differ).
void expectSameValues(const scene::TransferFunction& a, const scene::TransferFunction& b, float lo, float hi) {
    for (int i = 0; i <= 200; ++i) {
        const float v = lo + (hi - lo) * float(i) / 200.0f;
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.evaluate(v)[c], b.evaluate(v)[c], 1e-5f) << "value " << v;
    }
}
}  // namespace

TEST(TfEditor, PresetsAndTransferFunctionsRoundTrip) {
    for (const std::string& name : scene::presetNames()) {
        scene::TfChannels c = TfEditor::preset(name, 2.0f, 10.0f);
        const TfEditor e(c);
        expectSameTf(e.transferFunction(), scene::makePreset(name, 2.0f, 10.0f), 1e-5f);
    }
    const scene::TransferFunction tf({-1.0f, 0.0f, 3.0f}, {glm::vec4(0.1f, 0.2f, 0.3f, 0.0f),
                                                            glm::vec4(1.0f, 0.5f, 0.0f, 2.0f),
                                                            glm::vec4(0.0f, 0.0f, 1.0f, 0.5f)});
    scene::TfChannels c = scene::TfChannels::split(tf);
    const TfEditor e(c);
    EXPECT_EQ(e.lo(), -1.0f);
    EXPECT_EQ(e.hi(), 3.0f);
    expectSameTf(e.transferFunction(), tf, 1e-6f);
    // Channels with different spans (a ParaView file) become editable as the same function.
    scene::TfChannels apart;
    apart.name = "apart";
    apart.colorPositions = {0.0f, 10.0f};
    apart.colors = {glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)};
    apart.opacityPositions = {2.0f, 5.0f, 8.0f};
    apart.alphas = {0.0f, 1.0f, 0.25f};
    scene::TfChannels edited = apart;
    const TfEditor f(edited);
    EXPECT_EQ(f.lo(), 0.0f);
    EXPECT_EQ(f.hi(), 10.0f);
    expectSameValues(f.transferFunction(), apart.merged(), -1.0f, 11.0f);
}

TEST(TfEditor, EditsTheCallersTfInPlace) {
    scene::TfChannels tf = TfEditor::preset("grey", 0.0f, 100.0f);
    TfEditor e(tf);
    e.addNode(0.5f, 3.0f);
    EXPECT_EQ(tf.opacityPositions.size(), 3u) << "the caller's TF is the one that changed";
    EXPECT_EQ(tf.opacityPositions[1], 50.0f);
    EXPECT_EQ(tf.alphas[1], 3.0f);
    e.setRange(0.0f, 10.0f);
    EXPECT_EQ(tf.opacityPositions[1], 5.0f);
    EXPECT_EQ(tf.colorPositions.back(), 10.0f);
}

TEST(TfEditor, NodesStayOrderedAndTheEndsStay) {
    scene::TfChannels tf = TfEditor::preset("grey", 0.0f, 100.0f);
    TfEditor e(tf);
    ASSERT_EQ(e.opacity().size(), 2u);
    const size_t mid = e.addNode(0.5f, 3.0f);
    EXPECT_EQ(mid, 1u);
    EXPECT_EQ(e.addNode(0.25f, 1.0f), 1u);
    EXPECT_EQ(e.addNode(-4.0f, -1.0f), 1u) << "clamped to x = 0, inserted after the end node";
    EXPECT_EQ(e.opacity()[1].x, 0.0f);
    EXPECT_EQ(e.opacity()[1].alpha, 0.0f);
    e.removeNode(1);
    // Drag the middle node past its neighbours: it stops at them.
    e.moveNode(2, 0.1f, 5.0f);
    EXPECT_EQ(e.opacity()[2].x, 0.25f);
    EXPECT_EQ(e.opacity()[2].alpha, 5.0f);
    e.moveNode(0, 0.7f, 0.5f);  // the end keeps x = 0
    EXPECT_EQ(e.opacity()[0].x, 0.0f);
    EXPECT_EQ(e.opacity()[0].alpha, 0.5f);
    EXPECT_THROW(e.removeNode(0), Error);
    EXPECT_THROW(e.removeNode(e.opacity().size() - 1), Error);
    EXPECT_THROW(e.removeNode(99), Error);
    // The TF: alpha 5 at value 25 (x = 0.25 of [0, 100]).
    const scene::TransferFunction t = e.transferFunction();
    EXPECT_NEAR(t.evaluate(25.0f).a, 5.0f, 1e-5f);
    EXPECT_NEAR(t.maxAlpha(0.0f, 100.0f), 5.0f, 1e-5f);
    // Picking.
    EXPECT_EQ(e.nodeNear(0.26f, 4.9f, 0.02f, 0.2f), std::optional<size_t>(2));
    EXPECT_FALSE(e.nodeNear(0.6f, 4.9f, 0.02f, 0.2f).has_value());
}

TEST(TfEditor, RangeColourMapAndErrors) {
    scene::TfChannels tf = TfEditor::preset("ramp", 0.0f, 1.0f);
    TfEditor e(tf);
    const float alphaMid = e.transferFunction().evaluate(0.5f).a;
    e.setRange(10.0f, 20.0f);
    EXPECT_NEAR(e.transferFunction().evaluate(15.0f).a, alphaMid, 1e-6f) << "positions follow the range";
    EXPECT_THROW(e.setRange(1.0f, 1.0f), Error);
    EXPECT_THROW(e.setRange(2.0f, NAN), Error);
    EXPECT_EQ(e.lo(), 10.0f) << "a rejected range changes nothing";
    const auto opacityBefore = e.opacity().size();
    e.setColorMap(scene::builtInChannels("foggy"));
    EXPECT_EQ(e.colorMapName(), "foggy");
    EXPECT_EQ(e.opacity().size(), opacityBefore) << "a colour map keeps the opacity curve";
    EXPECT_NEAR(e.transferFunction().evaluate(15.0f).a, alphaMid, 1e-6f);
    // Many range changes there and back leave the nodes where they were (to float rounding).
    e.addNode(0.3f, 0.7f);
    const std::vector<viewer::OpacityNode> before = e.opacity();
    for (int i = 0; i < 100; ++i) {
        e.setRange(-1000.0f, 3.0f);
        e.setRange(10.0f, 20.0f);
    }
    for (size_t i = 0; i < before.size(); ++i) EXPECT_NEAR(e.opacity()[i].x, before[i].x, 1e-5f) << i;
}

TEST(TfEditor, ParaViewJsonRoundTripAndPresetLists) {
    scene::TfChannels tf = TfEditor::preset("ramp", -2.0f, 6.0f);
    TfEditor e(tf);
    e.addNode(0.3f, 0.8f);
    const auto dir = test::scratchDir();
    test::writeAll(dir / "edited.json", e.toParaViewJson("my edit"));
    const scene::TransferFunction back = scene::loadParaViewPreset(dir / "edited.json", "my edit");
    expectSameTf(back, e.transferFunction(), 1e-5f);

    test::writeAll(dir / "many.json",
                   R"([{"Name": "a", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]},
                       {"Name": "indexed", "IndexedColors": [1, 0, 0]},
                       {"Name": "b", "RGBPoints": [5, 1, 0, 0, 6, 0, 1, 0], "Points": [5, 0, 0.5, 0, 6, 1, 0.5, 0]}])");
    const scene::ParaViewPresets list = scene::loadParaViewPresets(dir / "many.json");
    ASSERT_EQ(list.presets.size(), 2u);
    EXPECT_EQ(list.presets[0].name, "a");
    EXPECT_EQ(list.presets[1].name, "b");
    ASSERT_EQ(list.skipped.size(), 1u);
    EXPECT_NE(list.skipped[0].find("indexed"), std::string::npos) << list.skipped[0];
    scene::TfChannels g = TfEditor::preset("grey", 0.0f, 1.0f);
    TfEditor f(g);
    f.setPreset(list.presets[1]);
    EXPECT_EQ(f.lo(), 0.0f) << "a preset keeps the range";
    EXPECT_NEAR(f.transferFunction().evaluate(1.0f).a, 1.0f, 1e-6f);
}

TEST(TfEditor, UndoAndRedoRestoreWholeStates) {
    scene::TfChannels tf = TfEditor::preset("grey", 0.0f, 1.0f);
    viewer::TfHistory h(tf);
    EXPECT_FALSE(h.canUndo());
    TfEditor e(tf);
    e.addNode(0.5f, 2.0f);
    h.push(tf);
    e.setRange(0.0f, 4.0f);
    h.push(tf);
    EXPECT_EQ(h.undo().opacityPositions.back(), 1.0f);
    EXPECT_EQ(h.current().alphas.size(), 3u);
    EXPECT_EQ(h.undo().alphas.size(), 2u);
    EXPECT_FALSE(h.canUndo());
    EXPECT_EQ(h.redo().alphas.size(), 3u);
    scene::TfChannels g = h.current();
    TfEditor(g).moveNode(1, 0.6f, 1.0f);
    h.push(g);  // drops the redo branch
    EXPECT_FALSE(h.canRedo());
    EXPECT_NEAR(h.current().opacityPositions[1], 0.6f, 1e-7f);
}
