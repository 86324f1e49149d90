// The TF editor's model: presets and TFs round-trip through it, nodes are added in order, dragged
// only between their neighbours, the ends stay, the range maps positions, ParaView JSON written
// by it reads back to the same TF, every preset of a ParaView file is listed (unusable ones
// skipped with a reason), and undo/redo restore whole states.
#include <gtest/gtest.h>

#include "core/error.h"
#include "session/tf_editor.h"
#include "test_data.h"

using namespace amrvk;
using session::TfEditor;

namespace {
void expectSameTf(const scene::TransferFunction& a, const scene::TransferFunction& b, float tol) {
    ASSERT_EQ(a.nodeCount(), b.nodeCount());
    for (size_t i = 0; i < a.nodeCount(); ++i) {
        EXPECT_NEAR(a.positions()[i], b.positions()[i], tol) << "node " << i;
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(a.colors()[i][c], b.colors()[i][c], 1e-6f) << "node " << i;
    }
}
}  // namespace

TEST(TfEditor, PresetsAndTransferFunctionsRoundTrip) {
    for (const std::string& name : scene::presetNames()) {
        const TfEditor e(name, 2.0f, 10.0f);
        expectSameTf(e.transferFunction(), scene::makePreset(name, 2.0f, 10.0f), 1e-5f);
    }
    const scene::TransferFunction tf({-1.0f, 0.0f, 3.0f}, {glm::vec4(0.1f, 0.2f, 0.3f, 0.0f),
                                                            glm::vec4(1.0f, 0.5f, 0.0f, 2.0f),
                                                            glm::vec4(0.0f, 0.0f, 1.0f, 0.5f)});
    const TfEditor e(tf);
    EXPECT_EQ(e.lo(), -1.0f);
    EXPECT_EQ(e.hi(), 3.0f);
    expectSameTf(e.transferFunction(), tf, 1e-6f);
}

TEST(TfEditor, NodesStayOrderedAndTheEndsStay) {
    TfEditor e("grey", 0.0f, 100.0f);
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
    const scene::TransferFunction tf = e.transferFunction();
    EXPECT_NEAR(tf.evaluate(25.0f).a, 5.0f, 1e-5f);
    EXPECT_NEAR(tf.maxAlpha(0.0f, 100.0f), 5.0f, 1e-5f);
    // Picking.
    EXPECT_EQ(e.nodeNear(0.26f, 4.9f, 0.02f, 0.2f), std::optional<size_t>(2));
    EXPECT_FALSE(e.nodeNear(0.6f, 4.9f, 0.02f, 0.2f).has_value());
}

TEST(TfEditor, RangeColourMapAndErrors) {
    TfEditor e("ramp", 0.0f, 1.0f);
    const float alphaMid = e.transferFunction().evaluate(0.5f).a;
    e.setRange(10.0f, 20.0f);
    EXPECT_NEAR(e.transferFunction().evaluate(15.0f).a, alphaMid, 1e-6f) << "positions follow the range";
    EXPECT_THROW(e.setRange(1.0f, 1.0f), Error);
    EXPECT_THROW(e.setRange(2.0f, NAN), Error);
    const auto opacityBefore = e.opacity().size();
    e.setColorMap(scene::builtInChannels("foggy"));
    EXPECT_EQ(e.colorMapName(), "foggy");
    EXPECT_EQ(e.opacity().size(), opacityBefore) << "a colour map keeps the opacity curve";
    EXPECT_NEAR(e.transferFunction().evaluate(15.0f).a, alphaMid, 1e-6f);
}

TEST(TfEditor, ParaViewJsonRoundTripAndPresetLists) {
    TfEditor e("ramp", -2.0f, 6.0f);
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
    TfEditor f("grey", 0.0f, 1.0f);
    f.setPreset(list.presets[1]);
    EXPECT_EQ(f.lo(), 0.0f) << "a preset keeps the range";
    EXPECT_NEAR(f.transferFunction().evaluate(1.0f).a, 1.0f, 1e-6f);
}

TEST(TfEditor, UndoAndRedoRestoreWholeStates) {
    session::TfHistory h(TfEditor("grey", 0.0f, 1.0f));
    EXPECT_FALSE(h.canUndo());
    TfEditor e = h.current();
    e.addNode(0.5f, 2.0f);
    h.push(e);
    e.setRange(0.0f, 4.0f);
    h.push(e);
    EXPECT_EQ(h.undo().hi(), 1.0f);
    EXPECT_EQ(h.current().opacity().size(), 3u);
    EXPECT_EQ(h.undo().opacity().size(), 2u);
    EXPECT_FALSE(h.canUndo());
    EXPECT_EQ(h.redo().opacity().size(), 3u);
    TfEditor g = h.current();
    g.moveNode(1, 0.6f, 1.0f);
    h.push(g);  // drops the redo branch
    EXPECT_FALSE(h.canRedo());
    EXPECT_EQ(h.current().opacity()[1].x, 0.6f);
}
