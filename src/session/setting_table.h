#pragma once
// The picture settings that the command line, the session file and the Python module all take,
// declared once: their names in each, kind, unit, limits, help text and what an edit of one
// invalidates. The CLI options (cli/options.cpp, addSetting), the session keys (session.cpp,
// settingKey) and the Python keywords and properties (python/renderer_keywords.cpp,
// python/py_renderer.cpp) are made from this table; each front end refuses a value outside the
// limits with settingRangeError's words after its own name for the setting. Defaults are the
// Session's own (scene::RenderSettings, scene::StructureConfig): stated there and nowhere else.
// Compound settings (camera, lights, cut-aways, image size, the TF) are rows too: their names in
// each front end, help and invalidation are declared here; each front end parses their parts itself,
// and tests check that every option, key and keyword a front end takes is a row's.
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
    Number,    // a finite double in [lo, hi] (open ends where loOpen / hiOpen)
    Integer,   // a whole number in [lo, hi]
    Choice,    // one of `choices` ("ae|ss|ms|dvr"), parsed by the setting's own parser
    Flag,      // true or false (a CLI flag)
    Text,      // a string, checked by `check`
    Compound,  // several values (a vector, a list of lights): names and help here, parsed by each front end
};

struct Setting {
    std::string_view option;   // command line: "--density-scale"
    std::string_view keyword;  // Python: Renderer(density_scale=...) ("" where Python has none; a
                               // Compound's may list several: "width|height")
    std::string_view section;  // session file: the section ("render"; "" for a key at the top) ...
    std::string_view key;      // ... and its key ("densityScale"; a Compound's may list several, or "")
    SettingKind kind;
    std::string_view unit;  // what the value counts ("" for a pure number or a name)
    double lo = 0, hi = 0;  // Number, Integer
    bool loOpen = false, hiOpen = false;
    std::string_view choices;    // Choice: the values, '|'-separated, as --help shows them
    std::string_view valueName;  // --help's placeholder: "S", "DEG", "N"
    std::string_view help;       // --help's text (the limits and the default are added from the fields)
    scene::ChangeSet invalidates;  // what an edit of it redoes (scene/invalidation.h; none: spp, legend)
    // Integer: what 0 means where a session (and the viewer) takes it outside [lo, hi] ("no limit");
    // empty: 0 is refused like any value outside.
    std::string_view zero;
    // Choice: a choice the command line and Python take that a session never holds, resolved by the
    // picture description ("auto": probe and choose); it is the last of `choices`.
    std::string_view request;
    // Python's Renderer has a property of `keyword` made from this row (false where a property of its
    // own reads or edits it: r.spp is the image's count, r.legend an object, r.tf_colors the TF's).
    bool pythonProperty = true;
    // Text: "" when the text is a value of the setting, else why not (no name: the front end adds it).
    std::function<std::string(const std::string&)> check;
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
// Whether a row's '|'-separated list (`keyword` or `key`) holds `name`.
bool listHolds(std::string_view list, std::string_view name);
// The row whose Python keyword list holds `keyword`, or null.
const Setting* settingForKeyword(std::string_view keyword);
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
// Sets Choice or Text `s` in `session` to `value`, or throws "<name>: <settingTextError>".
void setSettingName(const Setting& s, Session& session, const std::string& value, std::string_view name);
// `text` as a number (strtod, the whole text), or nullopt with `why` = "'x' is not a number": the
// command line's words for any numeric option.
std::optional<double> numberInText(const std::string& text, std::string& why);
// "" when `text` is a value of Text or Choice `s`, else why not (settingChoiceError's, or `check`'s).
std::string settingTextError(const Setting& s, const std::string& text);
// The value a Session starts with, as --help shows it ("1", "ms", "off"; "" for a Compound).
std::string settingDefault(const Setting& s);
// Sets `s` in `session` from text as the command line gives it (a number, or a choice's name),
// checked as above (`name`: the front end's name of the setting, for the error).
void setSettingFromText(const Setting& s, Session& session, const std::string& text, std::string_view name);

// Sets `s` in `to` to its value in `from` (nothing else of `to` changes).
void copySetting(const Setting& s, const Session& from, Session& to);

}  // namespace amrvk::session
