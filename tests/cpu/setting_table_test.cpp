// The picture settings declared once (session/setting_table.h; issue 54, point 1): each row's
// declared invalidation is what the renderer's rule (scene::invalidatedBy over settingsChanges, or
// a structure change) gives for an edit of it; its default lies within its limits; its words for
// a refused value are the ones every front end prints (tests/python/test_setting_table.py walks the
// three front ends); and a value read from text is checked (shown to refuse a value just outside).
#include "session/setting_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "core/strings.h"
#include "scene/invalidation.h"
#include "scene/tf_presets.h"

using namespace amrvk;
using session::Setting;
using session::SettingKind;

namespace {

// A value of `st` other than its default, as the command line gives it (a Choice's request, "auto",
// is no value a session holds).
std::string exampleText(const Setting& st) {
    if (st.kind == SettingKind::Choice) {
        const std::string def = session::settingDefault(st);
        for (std::string_view c : session::settingChoices(st))
            if (c != def && c != st.request) return std::string(c);
    }
    if (st.kind == SettingKind::Text) return st.option == "--grid" ? "16" : "example";
    if (st.kind == SettingKind::Flag) return session::settingDefault(st) == "true" ? "false" : "true";
    const double v = std::isinf(st.hi) ? st.lo + 2.5 : st.lo + (st.hi - st.lo) * 0.25;
    return std::to_string(st.kind == SettingKind::Integer ? std::round(v) : v);
}

}  // namespace

TEST(SettingTable, EachRowsInvalidationIsTheRenderersRuleForAnEditOfIt) {
    ASSERT_GE(session::settingTable().size(), 34u);
    for (const Setting& st : session::settingTable()) {
        SCOPED_TRACE(std::string(st.option));
        if (st.kind == SettingKind::Compound) continue;  // each front end's parser (tests/python/test_setting_table.py)
        const session::Session before;
        session::Session after = before;
        session::setSettingFromText(st, after, exampleText(st), st.option);
        if (st.section == "structure") {
            EXPECT_FALSE(after.structure == before.structure);
            EXPECT_EQ(st.invalidates.bits, scene::ChangeSet(scene::Change::Structure).bits);
            continue;
        }
        if (st.key == "tfColors") {  // the albedo the renderer gets (picture::asRendered)
            EXPECT_NE(after.tfColors, before.tfColors);
            EXPECT_EQ(st.invalidates.bits, scene::ChangeSet(scene::Change::TransferFunction).bits);
            continue;
        }
        const scene::ChangeSet changes = scene::settingsChanges(before.settings, after.settings);
        EXPECT_EQ(changes.bits, st.invalidates.bits)
            << "an edit of one setting changes one thing, or (spp, the legend) "
               "nothing the renderer holds: "
            << scene::describe(changes);
        if (st.invalidates.empty()) {
            EXPECT_NE(session::sessionJson(after), session::sessionJson(before));
        }
    }
}

TEST(SettingTable, DefaultsLieWithinTheLimitsAndAValueJustOutsideIsRefused) {
    for (const Setting& st : session::settingTable()) {
        SCOPED_TRACE(std::string(st.option));
        EXPECT_FALSE(st.help.empty());
        if (st.kind == SettingKind::Compound) {  // names and help; each front end parses the values
            EXPECT_FALSE(st.valueName.empty());
            EXPECT_EQ(session::settingDefault(st), "");
            continue;
        }
        EXPECT_EQ(std::string(st.keyword), [&] {
            std::string k(st.option.substr(2));
            for (char& c : k) c = c == '-' ? '_' : c;
            return k;
        }());
        session::Session s;
        if (st.kind == SettingKind::Choice) {
            EXPECT_EQ(session::settingChoiceError(st, session::settingDefault(st)), "");
            EXPECT_EQ(session::settingChoiceError(st, "nonsense"),
                      "'nonsense' is not one of " + std::string(st.choices));
            EXPECT_THROW(session::setSettingFromText(st, s, "nonsense", st.option), Error);
            continue;
        }
        if (st.kind == SettingKind::Text) {
            EXPECT_EQ(session::settingTextError(st, session::settingDefault(st)), "");
            continue;
        }
        if (st.kind == SettingKind::Flag) continue;
        EXPECT_EQ(session::settingRangeError(st, st.number(s)), "");
        EXPECT_FALSE(st.valueName.empty());
        const double below = st.loOpen ? st.lo : st.lo - 1;
        const std::string why = session::settingRangeError(st, below);
        EXPECT_EQ(why, formatDouble(below) + " is outside " + session::settingLimits(st));
        try {
            session::setSettingFromText(st, s, formatDouble(below), "X");
            ADD_FAILURE() << "accepted " << below;
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()), "X: " + why);
        }
        if (st.kind == SettingKind::Integer) {
            EXPECT_NE(session::settingRangeError(st, st.lo + 0.5).find("is not a whole number"), std::string::npos);
        }
    }
}

// What the front ends' own parsers meet: a Choice's request ("auto") is refused by a session with its
// reason, and 0 samples per pixel is a session's "no limit" but no value on the command line.
TEST(SettingTable, ARequestAndZeroAreNamedWhereTheyAreNoValue) {
    const Setting& traversal = session::settingForOption("--traversal");
    EXPECT_EQ(traversal.request, "auto");
    EXPECT_EQ(session::settingChoiceError(traversal, "auto"), "");  // the command line and Python take it
    session::Session s;
    try {
        session::setSettingFromText(traversal, s, "auto", "f.json.structure.traversal");
        ADD_FAILURE() << "a session took the request auto";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("f.json.structure.traversal: 'auto' asks to probe"), std::string::npos)
            << e.what();
    }
    const Setting& spp = session::settingForOption("--spp");
    EXPECT_FALSE(spp.zero.empty());
    EXPECT_EQ(session::settingRangeError(spp, 0), "0 is outside [1, 16777216]");
    session::Session withZero;
    withZero.input = "/data/x";
    withZero.tf = scene::TfChannels::split(scene::makePreset("ramp", 0.0f, 1.0f));
    withZero.spp = 0;
    const std::string text = session::sessionJson(withZero);
    EXPECT_EQ(session::parseSession(text, "z.json").spp, 0u);  // the viewer's "run on"
    // A grid's words, without a front end's name.
    const Setting& grid = session::settingForOption("--grid");
    EXPECT_EQ(session::settingTextError(grid, "12x10x8"), "");
    EXPECT_EQ(session::settingTextError(grid, "0"), "macrocells must be in [1, 4096] (got 0)");
    EXPECT_EQ(session::settingTextError(grid, "8x8"), "expected auto, N or NxMxK (got '8x8')");
}
