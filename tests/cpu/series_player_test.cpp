// The viewer's series player (viewer/logic/series_player.h): stepping wraps, playing advances
// 1 / fps after a step reached the screen (never past one unseen), and the steps read ahead are
// the nearest, as many as the budget holds.
#include "viewer/logic/series_player.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "test_data.h"

using amrvk::viewer::SeriesPlayer;

TEST(SeriesPlayer, SteppingWrapsAndSeekingOutsideIsNamed) {
    SeriesPlayer p(5, 4);
    EXPECT_EQ(p.stepOn(1), 1u);
    EXPECT_EQ(p.stepOn(-1), 4u);
    p.seek(4);
    EXPECT_EQ(p.stepOn(1), 0u);
    EXPECT_EQ(p.stepOn(-7), 2u);
    amrvk::test::expectError([&] { p.seek(5); }, {"step 5 is outside the series (steps 0..4)"});
    amrvk::test::expectError([] { SeriesPlayer(3, 0); }, {"--series-fps: 0 is outside (0, 120]"});
    amrvk::test::expectError([&] { p.setFps(1e9); }, {"--series-fps: 1e+09 is outside"});
}

TEST(SeriesPlayer, PlayingAdvancesOnlyAfterAStepWasOnScreenForOneFrameTime) {
    SeriesPlayer p(3, 4);  // 0.25 s a step
    p.onScreen(10.0);
    EXPECT_FALSE(p.due(11.0)) << "paused";
    p.setPlaying(true);
    EXPECT_FALSE(p.due(10.2));
    EXPECT_TRUE(p.due(10.25));
    p.seek(p.stepOn(1));
    // A step that takes 3 s to build is still shown for 0.25 s once on screen.
    EXPECT_FALSE(p.due(13.0)) << "not on screen yet";
    p.onScreen(13.0);
    p.onScreen(13.1);  // the same step again: still since 13.0
    EXPECT_FALSE(p.due(13.2));
    EXPECT_TRUE(p.due(13.25));
    SeriesPlayer one(1, 4);
    one.setPlaying(true);
    one.onScreen(0);
    EXPECT_FALSE(one.due(100)) << "one step: nothing to play";
}

TEST(SeriesPlayer, TheStepsAheadAreTheNearestTheBudgetHolds) {
    SeriesPlayer p(6, 4);
    p.seek(2);
    EXPECT_EQ(p.ahead(1000, 100), (std::vector<size_t>{3, 1, 4, 0, 5}));  // every other step: 5 fit
    EXPECT_EQ(p.ahead(250, 100), (std::vector<size_t>{3, 1}));
    EXPECT_EQ(p.ahead(99, 100), std::vector<size_t>{});
    p.seek(5);
    EXPECT_EQ(p.ahead(300, 100), (std::vector<size_t>{0, 4, 1})) << "wrapping, as playing loops";
    SeriesPlayer two(2, 4);
    EXPECT_EQ(two.ahead(1000, 1), std::vector<size_t>{1}) << "each step once";
}
