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

using namespace amrvk;
using session::Setting;
using session::SettingKind;

namespace {

// A value of `st` other than its default, as the command line gives it.
std::string exampleText(const Setting& st) {
    if (st.kind == SettingKind::Choice) {
        const std::string def = session::settingDefault(st);
        const std::string first(st.choices.substr(0, st.choices.find('|')));
        if (first != def) return first;
        const size_t at = st.choices.find('|') + 1;
        return std::string(st.choices.substr(at, st.choices.find('|', at) - at));
    }
    if (st.kind == SettingKind::Flag) return session::settingDefault(st) == "true" ? "false" : "true";
    const double v = std::isinf(st.hi) ? st.lo + 2.5 : st.lo + (st.hi - st.lo) * 0.25;
    return std::to_string(st.kind == SettingKind::Integer ? std::round(v) : v);
}

}  // namespace

TEST(SettingTable, EachRowsInvalidationIsTheRenderersRuleForAnEditOfIt) {
    ASSERT_GE(session::settingTable().size(), 10u);
    for (const Setting& st : session::settingTable()) {
        SCOPED_TRACE(std::string(st.option));
        const session::Session before;
        session::Session after = before;
        session::setSettingFromText(st, after, exampleText(st), st.option);
        if (st.section == "structure") {
            EXPECT_FALSE(after.structure == before.structure);
            EXPECT_EQ(st.invalidates, scene::Change::Structure);
            continue;
        }
        const scene::ChangeSet changes = scene::settingsChanges(before.settings, after.settings);
        EXPECT_TRUE(changes.has(st.invalidates)) << scene::describe(changes);
        EXPECT_EQ(changes.bits, scene::ChangeSet(st.invalidates).bits) << "an edit of one setting changes one thing";
    }
}

TEST(SettingTable, DefaultsLieWithinTheLimitsAndAValueJustOutsideIsRefused) {
    for (const Setting& st : session::settingTable()) {
        SCOPED_TRACE(std::string(st.option));
        EXPECT_FALSE(st.help.empty());
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
