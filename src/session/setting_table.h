#pragma once
// The picture settings that the command line, the session file and the Python module all take,
// declared once: their names in each, kind, unit, limits, help text and what an edit of one
// invalidates. The CLI options (cli/options.cpp, addSetting), the session keys (session.cpp,
// settingKey) and the Python keywords and properties (python/renderer_keywords.cpp,
// python/py_renderer.cpp) are made from this table; each front end refuses a value outside the
// limits with settingRangeError's words after its own name for the setting. Defaults are the
// Session's own (scene::RenderSettings, scene::StructureConfig): stated there and nowhere else.
// Adding a setting: a row here, and the code that uses its value (docs/architecture.md).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/invalidation.h"
#include "session/session.h"

namespace amrvk::session {

enum class SettingKind : uint8_t {
    Number,   // a finite double in [lo, hi] (open ends where loOpen / hiOpen)
    Integer,  // a whole number in [lo, hi]
    Choice,   // one of `choices` ("ae|ss|ms|dvr"), parsed by the setting's own parser
    Flag,     // true or false (a CLI flag)
};

struct Setting {
    std::string_view option;   // command line: "--density-scale"
    std::string_view keyword;  // Python: Renderer(density_scale=...) and the property r.density_scale
    std::string_view section;  // session file: the section ("render") ...
    std::string_view key;      // ... and its key ("densityScale")
    SettingKind kind;
    std::string_view unit;  // what the value counts ("" for a pure number or a name)
    double lo = 0, hi = 0;  // Number, Integer
    bool loOpen = false, hiOpen = false;
    std::string_view choices;    // Choice: the values, '|'-separated, as --help shows them
    std::string_view valueName;  // --help's placeholder: "S", "DEG", "N"
    std::string_view help;       // --help's text (the limits and the default are added from the fields)
    scene::Change invalidates;   // what an edit of it redoes (scene/invalidation.h)
    // The value in a session: a number (Number, Integer, Flag as 0 or 1) or a name (Choice).
    std::function<double(const Session&)> number;
    std::function<void(Session&, double)> setNumber;
    std::function<std::string(const Session&)> name;
    std::function<void(Session&, const std::string&)> setName;  // throws the parser's one-line error
};

// Every setting, in --help's order within each group.
const std::vector<Setting>& settingTable();
// The setting of command-line option `option` ("--g"); an internal error when there is none.
const Setting& settingForOption(std::string_view option);
// "[0, inf)", "(0, 180)", "[1, 16777215]": a Number's or Integer's limits as every front end writes them.
std::string settingLimits(const Setting& s);
// "" when `v` is a value of `s`; else why not, the same words everywhere ("-1 is outside [0, inf)",
// "2.5 is not a whole number in [1, 16777215]", "nan is not a finite number"). A front end puts its own name of `s`
// first.
std::string settingRangeError(const Setting& s, double v);
// Throws "<name>: <settingRangeError>" unless `v` is a value of `s`.
void checkSetting(const Setting& s, double v, std::string_view name);
// A Choice's values, in the order of `choices` ("ae|ss|ms|dvr" -> ae, ss, ms, dvr).
std::vector<std::string_view> settingChoices(const Setting& s);
// A Choice's words: "" when `value` is one of its choices, else "'pt' is not one of ae|ss|ms|dvr".
std::string settingChoiceError(const Setting& s, std::string_view value);
// Sets Choice `s` in `session` to `value`, or throws "<name>: <settingChoiceError>".
void setSettingChoice(const Setting& s, Session& session, const std::string& value, std::string_view name);
// `text` as a number (strtod, the whole text), or nullopt with `why` = "'x' is not a number": the
// command line's words for any numeric option.
std::optional<double> numberInText(const std::string& text, std::string& why);
// The value a Session starts with, as --help shows it ("1", "ms", "off").
std::string settingDefault(const Setting& s);
// Sets `s` in `session` from text as the command line gives it (a number, or a choice's name),
// checked as above (`name`: the front end's name of the setting, for the error).
void setSettingFromText(const Setting& s, Session& session, const std::string& text, std::string_view name);

// Sets `s` in `to` to its value in `from` (nothing else of `to` changes).
void copySetting(const Setting& s, const Session& from, Session& to);

}  // namespace amrvk::session
