// The legend's ticks and labels (session/legend.*) against hand-computed answers, and the legend's
// settings in sessions.
#include "session/legend.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "scene/tf_presets.h"
#include "session/picture_description.h"
#include "session/session.h"

using namespace amrvk;
using session::LegendTick;

namespace {

std::vector<LegendTick> majors(const std::vector<LegendTick>& ticks) {
    std::vector<LegendTick> out;
    for (const LegendTick& t : ticks)
        if (t.major) out.push_back(t);
    return out;
}
std::vector<double> minorPositions(const std::vector<LegendTick>& ticks) {
    std::vector<double> out;
    for (const LegendTick& t : ticks)
        if (!t.major) out.push_back(t.position);
    return out;
}
std::vector<std::string> labels(const std::vector<LegendTick>& ticks) {
    std::vector<std::string> out;
    for (const LegendTick& t : majors(ticks)) out.push_back(t.exponent.empty() ? t.label : t.label + "^" + t.exponent);
    return out;
}
// Every tick inside [lo, hi], ascending.
void expectOrderedInside(const std::vector<LegendTick>& ticks, double lo, double hi) {
    ASSERT_FALSE(ticks.empty());
    for (size_t i = 0; i < ticks.size(); ++i) {
        EXPECT_GE(ticks[i].position, lo);
        EXPECT_LE(ticks[i].position, hi);
        if (i > 0) {
            EXPECT_LT(ticks[i - 1].position, ticks[i].position);
        }
    }
}

}  // namespace

TEST(Legend, NiceStepIsTheSmallestOneTwoOrFiveTimesAPowerOfTenAboveSpanOverCount) {
    EXPECT_DOUBLE_EQ(session::niceStep(1, 6), 0.2);   // 1/6 = 0.167 -> 0.2
    EXPECT_DOUBLE_EQ(session::niceStep(4, 6), 1);     // 0.667 -> 1
    EXPECT_DOUBLE_EQ(session::niceStep(30, 6), 5);    // 5 -> 5
    EXPECT_DOUBLE_EQ(session::niceStep(100, 6), 20);  // 16.7 -> 20
    EXPECT_DOUBLE_EQ(session::niceStep(1e-30, 6), 2e-31);
    EXPECT_DOUBLE_EQ(session::niceStep(3e30, 6), 5e29);
    EXPECT_THROW(session::niceStep(0, 6), Error);
    EXPECT_THROW(session::niceStep(INFINITY, 6), Error);
}

TEST(Legend, LinearTicksAreNiceAndTheirMinorsSubdivideTheStep) {
    // [0, 1]: step 0.2, labels with one decimal; minors every 0.05 (4 per step of 2 x 10^k).
    auto t = session::legendTicks(0, 1, false, 6);
    expectOrderedInside(t, 0, 1);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"0", "0.2", "0.4", "0.6", "0.8", "1.0"}));
    const std::vector<double> minors = minorPositions(t);
    ASSERT_EQ(minors.size(), 15u);  // 21 multiples of 0.05 in [0, 1], 6 of them labelled
    for (size_t i = 0, k = 1; i < minors.size(); ++i, ++k) {
        if (k % 4 == 0) ++k;
        EXPECT_NEAR(minors[i], 0.05 * double(k), 1e-12);
    }
    // [0, 4]: step 1, minors every 0.2 (5 per step of 1 x 10^k).
    t = session::legendTicks(0, 4, false, 6);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"0", "1", "2", "3", "4"}));
    EXPECT_EQ(minorPositions(t).size(), 16u);
    // A range that is not a multiple of the step: ticks only inside it.
    t = session::legendTicks(0.012, 4.3, false, 6);
    expectOrderedInside(t, 0.012, 4.3);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"1", "2", "3", "4"}));
    EXPECT_DOUBLE_EQ(majors(t).front().position, 1.0);
}

TEST(Legend, NegativeAndZeroCrossingRanges) {
    auto t = session::legendTicks(-40, -10, false, 6);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"-40", "-35", "-30", "-25", "-20", "-15", "-10"}));
    t = session::legendTicks(-1, 1, false, 4);  // step 0.5; zero is "0", never "-0.0"
    EXPECT_EQ(labels(t), (std::vector<std::string>{"-1.0", "-0.5", "0", "0.5", "1.0"}));
    EXPECT_EQ(majors(t)[2].position, 0.0);
}

TEST(Legend, TinyAndHugeRangesGetScientificLabelsWithTheDigitsTheStepNeeds) {
    auto t = session::legendTicks(0, 1e-30, false, 6);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"0", "2e-31", "4e-31", "6e-31", "8e-31", "1.0e-30"}));
    t = session::legendTicks(0, 3e30, false, 6);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"0", "5e29", "1.0e30", "1.5e30", "2.0e30", "2.5e30", "3.0e30"}));
    // A narrow range far from zero: step 2e-4 at 1e6, so ten decimals of the mantissa.
    t = session::legendTicks(1e6, 1e6 + 1e-3, false, 6);
    expectOrderedInside(t, 1e6, 1e6 + 1e-3);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"1.0000000000e6", "1.0000000002e6", "1.0000000004e6",
                                                   "1.0000000006e6", "1.0000000008e6", "1.0000000010e6"}));
    // Fixed point while values stay below 1e5 and the step at or above 1e-4.
    EXPECT_EQ(session::tickLabel(0.0005, 1e-4), "0.0005");
    EXPECT_EQ(session::tickLabel(0.00005, 1e-5), "5e-5");
    EXPECT_EQ(session::tickLabel(25000, 5000, 100000), "2.5e4");  // one form per axis: its magnitude decides
    EXPECT_EQ(session::tickLabel(-0.0, 0.1), "0");
}

TEST(Legend, DegenerateAndBadRanges) {
    auto t = session::legendTicks(0.3, 0.3, false);
    ASSERT_EQ(t.size(), 1u);
    EXPECT_TRUE(t[0].major);
    EXPECT_EQ(t[0].label, "0.3");
    t = session::legendTicks(3, 3, true);  // log10 axis at 3: the value 10^3
    ASSERT_EQ(t.size(), 1u);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"10^3"}));
    t = session::legendTicks(std::log10(2.5), std::log10(2.5), true);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"2.5"}));
    // A span below double resolution at its magnitude still gets a labelled tick.
    t = session::legendTicks(1.0, std::nextafter(1.0, 2.0), false);
    EXPECT_GE(majors(t).size(), 1u);
    expectOrderedInside(t, 1.0, std::nextafter(1.0, 2.0));
    EXPECT_THROW(session::legendTicks(NAN, 1, false), Error);
    EXPECT_THROW(session::legendTicks(0, INFINITY, false), Error);
    EXPECT_THROW(session::legendTicks(2, 1, false), Error);
    EXPECT_THROW(session::legendTicks(0, 1, false, 1), Error);
}

TEST(Legend, LogTicksAreDecadesWithMinorTicksAtTheDigits) {
    // The Enzo sample's Density in log10: [-1.92, 3.01] holds the decades 10^-1 .. 10^3.
    auto t = session::legendTicks(-1.92, 3.01, true, 6);
    expectOrderedInside(t, -1.92, 3.01);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"10^-1", "10^0", "10^1", "10^2", "10^3"}));
    for (const LegendTick& m : majors(t)) EXPECT_EQ(m.position, std::round(m.position));
    // Minors at log10(m) + k, m = 2..9: k = -2 from 10^-1.92 = 0.012 (m = 2..9, all above 0.012 x 100),
    // k = -1, 0, 1, 2 in full: 5 x 8 = 40.
    const std::vector<double> minors = minorPositions(t);
    ASSERT_EQ(minors.size(), 40u);
    EXPECT_NEAR(minors.front(), -2 + std::log10(2.0), 1e-12);
    EXPECT_NEAR(minors.back(), 2 + std::log10(9.0), 1e-12);
}

TEST(Legend, TheDecadeAtZeroIsTenToTheZeroNotMinusZero) {
    const auto t = session::legendTicks(0, 3, true, 6);  // ceil(0 - 1e-9) is -0
    EXPECT_EQ(labels(t), (std::vector<std::string>{"10^0", "10^1", "10^2", "10^3"}));
}

TEST(Legend, ManyDecadesAreLabelledEverySecondFifthOrTenth) {
    auto t = session::legendTicks(-3, 3, true, 6);  // 7 decades: every 2nd
    EXPECT_EQ(labels(t), (std::vector<std::string>{"10^-2", "10^0", "10^2"}));
    EXPECT_EQ(minorPositions(t), (std::vector<double>{-3, -1, 1, 3}));  // the others, no digit minors
    t = session::legendTicks(-30, 30, true, 6);                         // 61 decades: every 20th (10th gives 7)
    EXPECT_EQ(labels(t), (std::vector<std::string>{"10^-20", "10^0", "10^20"}));
    EXPECT_EQ(minorPositions(t).size(), 58u);
    t = session::legendTicks(-30, 30, true, 8);  // every 10th
    EXPECT_EQ(labels(t), (std::vector<std::string>{"10^-30", "10^-20", "10^-10", "10^0", "10^10", "10^20", "10^30"}));
}

TEST(Legend, LogRangesWithinTwoDecadesLabelOneTwoAndFive) {
    // [10^0.5, 10^1.3] = [3.16, 19.95]: 5 and 10 labelled; 4, 6, 7, 8, 9 minor.
    auto t = session::legendTicks(0.5, 1.3, true, 6);
    expectOrderedInside(t, 0.5, 1.3);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"5", "10"}));
    EXPECT_NEAR(majors(t)[0].position, std::log10(5.0), 1e-12);
    EXPECT_EQ(minorPositions(t).size(), 5u);
    // [10^-2.2, 10^-1.1] = [0.0063, 0.079]: 0.01, 0.02, 0.05 labelled.
    t = session::legendTicks(-2.2, -1.1, true, 6);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"0.01", "0.02", "0.05"}));
    // Under a factor 2.5 ([2.51, 3.98]): nice linear ticks of the value at their log10 (step 0.5).
    t = session::legendTicks(0.4, 0.6, true, 6);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"3.0", "3.5"}));
    EXPECT_NEAR(majors(t)[1].position, std::log10(3.5), 1e-12);
    // Beyond double range (10^309): nice ticks of the exponent, labelled as powers of ten.
    t = session::legendTicks(308.5, 309.2, true, 6);
    EXPECT_EQ(labels(t), (std::vector<std::string>{"10^308.6", "10^308.8", "10^309.0", "10^309.2"}));
}

TEST(Legend, TitleNotesTheLogScale) {
    session::Legend legend;
    EXPECT_EQ(session::legendTitle(legend, "Density", false), "Density");
    EXPECT_EQ(session::legendTitle(legend, "Density", true), "Density (log10 scale)");
    legend.title = "gas density";
    EXPECT_EQ(session::legendTitle(legend, "Density", true), "gas density (log10 scale)");
}

TEST(Legend, SettingsRoundTripThroughSessions) {
    session::Session s;
    s.input = "/data/x.cells";
    s.tf = scene::TfChannels::split(scene::makePreset("ramp", 0, 1));
    EXPECT_EQ(session::sessionJson(s).find("\"legend\""), std::string::npos);  // the default is not written
    s.legend = {.show = true, .place = session::LegendPlace::Overlay, .title = "T", .units = "g/cm³", .font = "/f.ttf"};
    const session::Session back = session::parseSession(session::sessionJson(s), "s.json");
    EXPECT_EQ(back.legend, s.legend);
    // The viewer's "copy as command" carries the legend.
    const std::string command = session::renderCommandLine(s, "tf.json", "o.png");
    EXPECT_NE(
        command.find(
            " --legend --legend-place overlay --legend-title T --legend-units 'g/cm³' --legend-font /f.ttf -o o.png"),
        std::string::npos)
        << command;
    const std::string bad = session::sessionJson(s);
    std::string text = bad;
    text.replace(text.find("\"overlay\""), 9, "\"corner\"");
    try {
        session::parseSession(text, "s.json");
        FAIL() << "a bad legend place was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("s.json.legend.place"), std::string::npos) << e.what();
    }
    text = bad;
    text.replace(text.find("\"show\": true"), 12, "\"show\": 1");
    EXPECT_THROW(session::parseSession(text, "s.json"), Error);
}
