// The viewer's layout (viewer/logic/viewer_layout.*): at the sizes people use and at tiny ones, the
// panel and the picture never share a pixel (checked pixel by pixel, not only with overlaps()),
// both lie in the window, the picture keeps the image's aspect and fills its area on one axis,
// and the panel width a user drags to is kept within its limits.
#include "viewer/logic/viewer_layout.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

using namespace amrvk;
using session::PixelRect;

namespace {

// Every pixel of the window counted: in the panel, in the picture, in both.
struct PixelCensus {
    long panel = 0, picture = 0, both = 0, outside = 0;
};
PixelCensus census(const viewer::ViewerLayout& l) {
    PixelCensus c;
    for (int y = 0; y < l.window.height; ++y)
        for (int x = 0; x < l.window.width; ++x) {
            const double px = x + 0.5, py = y + 0.5;
            const bool inPanel = l.panel.contains(px, py), inPicture = l.picture.contains(px, py);
            c.panel += inPanel;
            c.picture += inPicture;
            c.both += inPanel && inPicture;
            c.outside += !l.window.contains(px, py);
        }
    return c;
}

void expectSound(const viewer::ViewerLayout& l, int imageWidth, int imageHeight, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_FALSE(session::overlaps(l.panel, l.picture));
    EXPECT_TRUE(session::inside(l.panel, l.window));
    EXPECT_TRUE(session::inside(l.picture, l.area));
    EXPECT_TRUE(session::inside(l.area, l.window));
    EXPECT_FALSE(session::overlaps(l.panel, l.area));
    if (l.window.empty()) return;
    EXPECT_EQ(l.area.width + l.panel.width, l.window.width) << "area and panel share the width";
    ASSERT_FALSE(l.picture.empty()) << "a window with pixels always shows the picture";
    // Aspect: within the rounding of one pixel on each side.
    const double aspect = double(imageWidth) / imageHeight;
    EXPECT_LE(std::abs(l.picture.width - aspect * l.picture.height), 0.5 * aspect + 1.0);
    // As large as fits: it fills the area's width or its height.
    EXPECT_TRUE(l.picture.width == l.area.width || l.picture.height == l.area.height);
    // Centred (to a pixel).
    EXPECT_LE(std::abs((l.picture.x - l.area.x) - (l.area.right() - l.picture.right())), 1);
    EXPECT_LE(std::abs((l.picture.y - l.area.y) - (l.area.bottom() - l.picture.bottom())), 1);
}

}  // namespace

TEST(ViewerLayout, TheIssuesWindowSplitsAsComputedByHand) {
    // 1024x720 with the default panel and a 512x512 image: the area is 1024 - 440 = 584 wide, the
    // picture 584x584, 68 rows from the top; the panel is x in [584, 1024).
    const viewer::ViewerLayout l = viewer::viewerLayout(1024, 720, viewer::kPanelDefaultWidth, 512, 512);
    EXPECT_EQ(l.panel, (PixelRect{584, 0, 440, 720}));
    EXPECT_EQ(l.area, (PixelRect{0, 0, 584, 720}));
    EXPECT_EQ(l.picture, (PixelRect{0, 68, 584, 584}));
    // A wide image in the same window is as wide as the area: 584 x 584 * 9 / 16 = 328.5 -> 329 rows.
    const viewer::ViewerLayout wide = viewer::viewerLayout(1024, 720, viewer::kPanelDefaultWidth, 1600, 900);
    EXPECT_EQ(wide.picture.width, 584);
    EXPECT_EQ(wide.picture.height, 329);
    EXPECT_EQ(wide.picture.y, (720 - 329) / 2);
}

TEST(ViewerLayout, PanelAndPictureNeverShareAPixelAtCommonSizes) {
    const int windows[][2] = {{800, 600}, {1280, 800}, {1920, 1080}, {1024, 720}, {640, 480}, {3840, 2160}};
    const int images[][2] = {{512, 512}, {48, 32}, {1920, 1080}, {256, 1024}, {1, 1}};
    const int panels[] = {viewer::kPanelDefaultWidth, 0, viewer::kPanelMinWidth, 700, 100000};
    for (const auto& w : windows)
        for (const auto& im : images)
            for (int p : panels) {
                const viewer::ViewerLayout l = viewer::viewerLayout(w[0], w[1], p, im[0], im[1]);
                const std::string what = std::to_string(w[0]) + "x" + std::to_string(w[1]) + " image " +
                                         std::to_string(im[0]) + "x" + std::to_string(im[1]) + " panel " +
                                         std::to_string(p);
                expectSound(l, im[0], im[1], what);
                EXPECT_GE(l.panel.width, viewer::kPanelMinWidth) << what;
                EXPECT_GE(l.area.width, viewer::kPictureMinWidth) << what;
                if (p >= viewer::kPanelMinWidth && p <= w[0] - viewer::kPictureMinWidth) {
                    EXPECT_EQ(l.panel.width, p) << what << ": a width within the limits is kept";
                }
            }
    // Pixel by pixel at the issue's sizes (independent of overlaps()).
    for (const auto& w : windows) {
        if (w[0] > 1920) continue;
        const viewer::ViewerLayout l = viewer::viewerLayout(w[0], w[1], viewer::kPanelDefaultWidth, 512, 512);
        const PixelCensus c = census(l);
        EXPECT_EQ(c.both, 0);
        EXPECT_EQ(c.panel, long(l.panel.width) * l.panel.height);
        EXPECT_EQ(c.picture, long(l.picture.width) * l.picture.height);
        EXPECT_GT(c.picture, 0);
    }
}

TEST(ViewerLayout, TinyAndEmptyWindows) {
    for (int w = 0; w <= 40; ++w)
        for (int h = 0; h <= 12; ++h) {
            const viewer::ViewerLayout l = viewer::viewerLayout(w, h, viewer::kPanelDefaultWidth, 640, 480);
            const std::string what = std::to_string(w) + "x" + std::to_string(h);
            expectSound(l, 640, 480, what);
            const PixelCensus c = census(l);
            EXPECT_EQ(c.both, 0) << what;
            EXPECT_EQ(l.picture.empty(), w == 0 || h == 0) << what;
        }
    // Just under and at the width that holds both minimums.
    const int both = viewer::kPanelMinWidth + viewer::kPictureMinWidth;
    EXPECT_EQ(viewer::viewerLayout(both - 1, 300, 440, 8, 8).panel.width, (both - 1) / 2);
    EXPECT_EQ(viewer::viewerLayout(both, 300, 440, 8, 8).panel.width, viewer::kPanelMinWidth);
    // Minimised (GLFW reports 0x0) and nonsense sizes: nothing to show, no error.
    const viewer::ViewerLayout none = viewer::viewerLayout(-3, 500, 440, 8, 8);
    EXPECT_TRUE(none.window.empty() && none.panel.empty() && none.picture.empty());
    EXPECT_THROW(viewer::viewerLayout(800, 600, 440, 0, 10), Error);
}

TEST(ViewerLayout, TheDefaultWindowShowsTheImagePixelForPixel) {
    for (const auto& im : {std::pair{512, 512}, std::pair{800, 600}, std::pair{48, 32}, std::pair{1920, 1080}}) {
        int w = 0, h = 0;
        viewer::defaultWindowSize(im.first, im.second, w, h);
        const viewer::ViewerLayout l = viewer::viewerLayout(w, h, viewer::kPanelDefaultWidth, im.first, im.second);
        EXPECT_EQ(l.panel.width, viewer::kPanelDefaultWidth);
        if (im.first >= viewer::kPictureMinWidth) {
            EXPECT_EQ(l.picture.width, im.first);
            EXPECT_EQ(l.picture.height, im.second);
        }
        EXPECT_GE(h, 600) << "room for the panel";
    }
}
