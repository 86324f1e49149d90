#include "session/setting_table.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "core/error.h"
#include "core/strings.h"
#include "scene/limits.h"

namespace amrvk::session {

namespace {

// A number kept in the Session where `at` says (a generic lambda: one accessor for both).
template <typename At>
Setting numeric(Setting s, At at) {
    s.number = [at](const Session& x) { return double(at(x)); };
    s.setNumber = [at](Session& x, double v) { at(x) = std::remove_cvref_t<decltype(at(x))>(v); };
    return s;
}

// A name of an enum kept where `at` says: `parse` reads it (throwing its one-line error), `nameOf`
// writes it.
template <typename At, typename Parse, typename NameOf>
Setting named(Setting s, At at, Parse parse, NameOf nameOf) {
    s.name = [at, nameOf](const Session& x) { return std::string(nameOf(at(x))); };
    s.setName = [at, parse](Session& x, const std::string& v) { at(x) = parse(v); };
    return s;
}

#define AT(member) \
    [](auto& x) -> auto& { return x.member; }

// How the picture is made: the estimator and its options.
std::vector<Setting> methodRows() {
    using scene::Change;
    using K = SettingKind;
    return {
        named({.option = "--mode",
               .keyword = "mode",
               .section = "render",
               .key = "mode",
               .kind = K::Choice,
               .choices = "ae|ss|ms|dvr",
               .help = "absorption+emission, single or multiple scattering, or the ray-marching baseline (biased "
                       "by --dt)",
               .invalidates = Change::Mode},
              AT(settings.mode), scene::parseMode, scene::modeName),
        numeric({.option = "--dt",
                 .keyword = "dt",
                 .section = "render",
                 .key = "dvrStep",
                 .kind = K::Number,
                 .unit = "finest cell widths",
                 .lo = 0,
                 .hi = 64,
                 .loOpen = true,
                 .valueName = "F",
                 .help = "dvr: step as a fraction of the finest cell width at the sample",
                 .invalidates = Change::DvrOptions},
                AT(settings.dvrStep)),
        numeric({.option = "--dvr-shading",
                 .keyword = "dvr_shading",
                 .section = "render",
                 .key = "dvrShading",
                 .kind = K::Flag,
                 .help = "dvr: gradient shading by the first --light-dir (else a headlight)",
                 .invalidates = Change::DvrOptions},
                AT(settings.dvrShading)),
        named({.option = "--transmittance",
               .keyword = "transmittance",
               .section = "render",
               .key = "transmittance",
               .kind = K::Choice,
               .choices = "ratio|ubrm",
               .help = "ss and ms: the shadow rays' transmittance estimator, ratio tracking or unbiased ray "
                       "marching (Kettunen et al. 2021); both unbiased (docs/benchmarks.md)",
               .invalidates = Change::Medium},
              AT(settings.transmittance), scene::parseTransmittance, scene::transmittanceName),
        named({.option = "--control-extinction",
               .keyword = "control_extinction",
               .section = "render",
               .key = "controlExtinction",
               .kind = K::Choice,
               .choices = "none|minorant",
               .help = "ae, ss and ms: none, or track only the extinction above each macrocell's least "
                       "(minorant): free flight by decomposition tracking, ratio-tracked shadows by residual "
                       "ratio tracking; unbiased, grid-dda and grid-bvh over data whose cells fill their bounds",
               .invalidates = Change::Control},
              AT(settings.controlExtinction), scene::parseControlExtinction, scene::controlExtinctionName),
    };
}

// The structures.
std::vector<Setting> structureRows() {
    using scene::Change;
    using K = SettingKind;
    return {
        numeric({.option = "--kd-leaves",
                 .keyword = "kd_leaves",
                 .section = "structure",
                 .key = "kdLeaves",
                 .kind = K::Integer,
                 .unit = "leaves",
                 .lo = 1,
                 .hi = scene::kMaxKdLeaves,
                 .valueName = "N",
                 .help = "kdtree: leaves of the kd-tree, rebuilt per TF (at most one per cell)",
                 .invalidates = Change::Structure},
                AT(structure.kdLeaves)),
        [] {
            Setting s{.option = "--dense-max-mib",
                      .keyword = "dense_max_mib",
                      .section = "structure",
                      .key = "denseMaxMiB",
                      .kind = K::Integer,
                      .unit = "MiB",
                      .lo = 1,
                      .hi = scene::kMaxDenseMiB,
                      .valueName = "MIB",
                      .help = "dense sampler: largest dense grid to build",
                      .invalidates = Change::Structure};
            s.number = [](const Session& x) { return double(x.structure.denseMaxBytes >> 20); };
            s.setNumber = [](Session& x, double v) { x.structure.denseMaxBytes = uint64_t(v) << 20; };
            return s;
        }(),
    };
}

// The camera, the random seed and the medium.
std::vector<Setting> viewAndMediumRows() {
    using scene::Change;
    using K = SettingKind;
    constexpr double kInf = INFINITY;
    return {
        numeric({.option = "--fov",
                 .keyword = "fov",
                 .section = "camera",
                 .key = "fovY",
                 .kind = K::Number,
                 .unit = "degrees",
                 .lo = 0,
                 .hi = scene::kMaxFovDegrees,
                 .loOpen = true,
                 .hiOpen = true,
                 .valueName = "DEG",
                 .help = "vertical field of view in degrees",
                 .invalidates = Change::Camera},
                AT(settings.camera.fovYDegrees)),
        numeric({.option = "--seed",
                 .keyword = "seed",
                 .section = "render",
                 .key = "seed",
                 .kind = K::Integer,
                 .lo = 0,
                 .hi = UINT32_MAX,
                 .valueName = "S",
                 .help = "random seed",
                 .invalidates = Change::Seed},
                AT(settings.seed)),
        // The medium.
        numeric({.option = "--density-scale",
                 .keyword = "density_scale",
                 .section = "render",
                 .key = "densityScale",
                 .kind = K::Number,
                 .lo = 0,
                 .hi = kInf,
                 .hiOpen = true,
                 .valueName = "S",
                 .help = "multiplies extinction",
                 .invalidates = Change::Medium},
                AT(settings.densityScale)),
        numeric({.option = "--g",
                 .keyword = "g",
                 .section = "render",
                 .key = "g",
                 .kind = K::Number,
                 .lo = -1,
                 .hi = 1,
                 .valueName = "G",
                 .help = "Henyey-Greenstein asymmetry, clamped to +-0.999",
                 .invalidates = Change::Medium},
                AT(settings.g)),
    };
}

std::vector<Setting> makeTable() {
    std::vector<Setting> all = methodRows();
    for (auto rows : {structureRows(), viewAndMediumRows()}) all.insert(all.end(), rows.begin(), rows.end());
    return all;
}
#undef AT

std::string bound(double v) { return std::isinf(v) ? (v < 0 ? "-inf" : "inf") : formatDouble(v); }

}  // namespace

const std::vector<Setting>& settingTable() {
    static const std::vector<Setting> kTable = makeTable();
    return kTable;
}

const Setting& settingForOption(std::string_view option) {
    for (const Setting& s : settingTable())
        if (s.option == option) return s;
    AMRVK_CHECK(false, "internal: no setting ", option, " in the table");
    throw;  // unreachable
}

std::string settingLimits(const Setting& s) {
    return strCat(s.loOpen ? "(" : "[", bound(s.lo), ", ", bound(s.hi), s.hiOpen ? ")" : "]");
}

std::string settingRangeError(const Setting& s, double v) {
    if (s.kind != SettingKind::Number && s.kind != SettingKind::Integer) return "";
    if (!std::isfinite(v)) return strCat(formatDouble(v), " is not a finite number");
    const bool inside = std::isfinite(v) && (s.loOpen ? v > s.lo : v >= s.lo) && (s.hiOpen ? v < s.hi : v <= s.hi);
    if (s.kind == SettingKind::Integer && std::isfinite(v) && v != std::floor(v))
        return strCat(formatDouble(v), " is not a whole number in ", settingLimits(s));
    return inside ? "" : strCat(formatDouble(v), " is outside ", settingLimits(s));
}

void checkSetting(const Setting& s, double v, std::string_view name) {
    const std::string why = settingRangeError(s, v);
    AMRVK_CHECK(why.empty(), name, ": ", why);
}

std::vector<std::string_view> settingChoices(const Setting& s) {
    std::vector<std::string_view> out;
    for (size_t at = 0; at <= s.choices.size();) {
        const size_t bar = std::min(s.choices.find('|', at), s.choices.size());
        out.push_back(s.choices.substr(at, bar - at));
        at = bar + 1;
    }
    return out;
}

std::string settingChoiceError(const Setting& s, std::string_view value) {
    const std::vector<std::string_view> choices = settingChoices(s);
    if (std::find(choices.begin(), choices.end(), value) != choices.end()) return "";
    return strCat("'", value, "' is not one of ", s.choices);
}

void setSettingChoice(const Setting& s, Session& session, const std::string& value, std::string_view name) {
    const std::string why = settingChoiceError(s, value);
    AMRVK_CHECK(why.empty(), name, ": ", why);
    s.setName(session, value);
}

std::optional<double> numberInText(const std::string& text, std::string& why) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || !end || *end != '\0') {
        why = "'" + text + "' is not a number";
        return std::nullopt;
    }
    return v;
}

std::string settingDefault(const Setting& s) {
    static const Session kStart;
    if (s.kind == SettingKind::Choice) return s.name(kStart);
    if (s.kind == SettingKind::Flag) return s.number(kStart) != 0 ? "true" : "false";
    return formatDouble(s.number(kStart));
}

void setSettingFromText(const Setting& s, Session& session, const std::string& text, std::string_view name) {
    if (s.kind == SettingKind::Choice) {
        setSettingChoice(s, session, text, name);
        return;
    }
    if (s.kind == SettingKind::Flag) {
        AMRVK_CHECK(text == "true" || text == "false", name, ": '", text, "' is not true or false");
        s.setNumber(session, text == "true" ? 1 : 0);
        return;
    }
    std::string why;
    const std::optional<double> v = numberInText(text, why);
    AMRVK_CHECK(v, name, ": ", why);
    checkSetting(s, *v, name);
    s.setNumber(session, *v);
}

void copySetting(const Setting& s, const Session& from, Session& to) {
    if (s.kind == SettingKind::Choice)
        s.setName(to, s.name(from));
    else
        s.setNumber(to, s.number(from));
}

}  // namespace amrvk::session
