#include "session/setting_table.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "accel/range_grid.h"
#include "core/error.h"
#include "core/strings.h"
#include "scene/limits.h"
#include "scene/structure_config.h"
#include "scene/tf_colors.h"
#include "session/legend.h"

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

// A string kept where `at` says, checked by `check` ("" or why not).
template <typename At>
Setting text(Setting s, At at, std::function<std::string(const std::string&)> check) {
    s.check = std::move(check);
    s.name = [at](const Session& x) { return std::string(at(x)); };
    s.setName = [at](Session& x, const std::string& v) { at(x) = v; };
    return s;
}

// A compound setting's row: names, help and invalidation (each front end parses its parts).
Setting compound(Setting s) {
    s.kind = SettingKind::Compound;
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

// The samples per pixel.
Setting sppRow() {
    return numeric({.option = "--spp",
                    .keyword = "spp",
                    .section = "render",
                    .key = "spp",
                    .kind = SettingKind::Integer,
                    .unit = "samples per pixel",
                    .lo = 1,
                    .hi = scene::kMaxSpp,
                    .valueName = "N",
                    .help = "samples per pixel",
                    .invalidates = {},
                    .zero = "no limit: the viewer accumulates until stopped (render and Python take 64)",
                    .pythonProperty = false},  // r.spp: the samples the image holds
                   AT(spp));
}

// The structure's combination: traversal, sampler, back-end.
std::vector<Setting> combinationRows() {
    using scene::Change;
    using K = SettingKind;
    return {
        named(
            {.option = "--traversal",
             .keyword = "traversal",
             .section = "structure",
             .key = "traversal",
             .kind = K::Choice,
             .choices = "grid-dda|grid-bvh|abr|brick|domain|kdtree|auto",
             .help = "majorant traversal: macrocell DDA, BVH over non-empty macrocells, ABRs, brick bounds, brick "
                     "domains, the TF-specific kd-tree; auto = probe each traversal and sampler briefly, predict "
                     "the other combinations from their counts, and take the most efficient (options given "
                     "explicitly stay fixed; --json lists the probes); not given: grid-dda, or domain where the "
                     "data leave the grid mostly empty",
             .invalidates = Change::Structure,
             .request = "auto"},
            AT(structure.traversal),
            [](const std::string& v) {
                AMRVK_CHECK(v != "auto",
                            "'auto' asks to probe every traversal: the command line and Python "
                            "take it; a session holds the traversal chosen");
                return scene::parseTraversal(v);
            },
            scene::traversalName),
        named({.option = "--sampler",
               .keyword = "sampler",
               .section = "structure",
               .key = "sampler",
               .kind = K::Choice,
               .choices = "ext-brick|abr|grid|dense",
               .help = "sample reconstruction: BVH over brick domains, BVH over ABRs, grid = per-macrocell brick "
                       "lists (--grid; no tree descent, ext-brick's values), or dense = the field resampled to the "
                       "finest uniform grid (trilinear, a grid traversal only; the cost floor)",
               .invalidates = Change::Structure},
              AT(structure.sampler), scene::parseSampler, scene::samplerName),
        named({.option = "--backend",
               .keyword = "backend",
               .section = "structure",
               .key = "backend",
               .kind = K::Choice,
               .choices = "sw|rq|auto",
               .help = "box hierarchies: software BVH or VK_KHR_ray_query; auto = sw, which was measured faster on "
                       "CPU devices (rq is not measured faster on a GPU yet); the choice and its reason go to stderr "
                       "and --json",
               .invalidates = Change::Structure},
              AT(structure.backend), scene::parseBackend, scene::backendName),
    };
}

// The structures' sizes.
std::vector<Setting> structureRows() {
    using scene::Change;
    using K = SettingKind;
    return {
        text({.option = "--grid",
              .keyword = "grid",
              .section = "structure",
              .key = "grid",
              .kind = K::Text,
              .valueName = "auto|N|NxMxK",
              .help = "macrocell grid of grid-dda, grid-bvh and the grid sampler (auto: 128 on the longest axis, "
                      "fewer for small data: at most 2 macrocells per leaf cell)",
              .invalidates = Change::Structure},
             AT(structure.grid), accel::gridTextError),
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
        named(
            {.option = "--sub-majorants",
             .keyword = "sub_majorants",
             .section = "structure",
             .key = "subMajorants",
             .kind = K::Choice,
             .choices = "off|2|4|8|16",
             .valueName = "off|N",
             .help = "grid-dda, grid-bvh: split each macrocell that the TF makes loose (a narrow TF peak in its "
                     "value range) into at most N^3 sub-boxes with majorants of their own, rebuilt per TF, so "
                     "that collisions they decide skip their lookup (the same picture, fewer lookups; nothing is "
                     "built where the TF has no narrow peak; docs/benchmarks.md)",
             .invalidates = Change::Structure},
            AT(structure.subMajorants), [](const std::string& v) { return scene::parseSubMajorants(v, "value"); },
            [](uint32_t n) { return scene::subMajorantsName(n); }),
    };
}

// The transfer function and what its colours mean.
std::vector<Setting> tfRows() {
    using scene::Change;
    using K = SettingKind;
    return {
        compound({.option = "--tf",
                  .keyword = "tf",
                  .key = "transferFunction",
                  .valueName = "FILE|PRESET",
                  .help = "transfer function: ParaView preset JSON, .xf, or a preset fitted to the data: layers "
                          "(eight semi-transparent layers over the field's range, each as opaque as the space its "
                          "values fill allows: about 0.15 optical depth per layer across the data); ramp, grey, "
                          "constant, empty over the field's range; spiky (alpha-1 peaks at the 75th, 90th and 97th "
                          "percentiles of the cell values) and foggy (alpha 0 up to the median value, rising to 0.05 "
                          "at the maximum) over the field's percentiles by cell count",
                  .invalidates = Change::TransferFunction}),
        compound({.option = "--tf-preset",
                  .key = "transferFunction",
                  .valueName = "NAME",
                  .help = "preset name inside a ParaView JSON file (default: the first)",
                  .invalidates = Change::TransferFunction}),
        compound({.option = "--tf-range",
                  .keyword = "tf_range",
                  .valueName = "LO HI",
                  .help = "map the TF's node range onto [LO, HI]; presets then ignore the data and take their "
                          "range-fixed shape over [LO, HI] (spiky: one alpha-1 peak at the middle, 1% half width; "
                          "foggy: alpha 0.05 -> 0.2 everywhere). Default: presets fitted to the data (--tf)",
                  .invalidates = Change::TransferFunction}),
        named(
            {.option = "--tf-colors",
             .keyword = "tf_colors",
             .key = "tfColors",
             .kind = K::Choice,
             .choices = "srgb|linear",
             .help = "what the TF's colours mean: srgb, display colours as ParaView, matplotlib and yt mean them "
                     "(decoded to linear albedo, the colour map interpolated as given), or linear albedo as given "
                     "(amrvk before sessions of version 2)",
             .invalidates = Change::TransferFunction,
             .pythonProperty = false},  // r.tf_colors re-applies the TF's colours
            AT(tfColors), [](const std::string& v) { return scene::parseTfColors(v, "value"); }, scene::tfColorsName),
    };
}

// The colour legend drawn into PNG images: not part of the rendering.
std::vector<Setting> legendRows() {
    using K = SettingKind;
    Setting show = numeric({.option = "--legend",
                            .keyword = "legend",
                            .section = "legend",
                            .key = "show",
                            .kind = K::Flag,
                            .help = "draw a colour legend into the PNG (render -o, the viewer's screenshots): the "
                                    "TF's colour bar with its opacity, ticks (decades for --scale log), the field's "
                                    "name and its units; the viewer shows it over the picture",
                            .invalidates = {},
                            .pythonProperty = false},  // r.legend: the whole legend as an object
                           AT(legend.show));
    auto textRow = [](std::string_view option, std::string_view keyword, std::string_view key, std::string_view value,
                      std::string_view help, auto at, std::function<std::string(const std::string&)> check) {
        return text({.option = option,
                     .keyword = keyword,
                     .section = "legend",
                     .key = key,
                     .kind = K::Text,
                     .valueName = value,
                     .help = help,
                     .invalidates = {},
                     .pythonProperty = false},
                    at, std::move(check));
    };
    return {
        show,
        named(
            {.option = "--legend-place",
             .keyword = "legend_place",
             .section = "legend",
             .key = "place",
             .kind = K::Choice,
             .choices = "side|overlay",
             .help = "side: in a strip right of the picture (the PNG gets wider, no data hidden); overlay: over "
                     "the picture's lower right corner on a backdrop",
             .invalidates = {},
             .pythonProperty = false},
            AT(legend.place), [](const std::string& v) { return parseLegendPlace(v); }, legendPlaceName),
        textRow("--legend-title", "legend_title", "title", "TEXT", "the legend's title (default: the field's name)",
                AT(legend.title), legendTextError),
        textRow("--legend-units", "legend_units", "units", "TEXT",
                "units shown under the title, e.g. 'g/cm^3' (default: the field's own, as amrvk info says, e.g. "
                "Enzo's and RAMSES's 'code units (1 = X g/cm^3)'; none where the data do not say)",
                AT(legend.units), legendTextError),
        textRow("--legend-font", "legend_font", "font", "FILE",
                "TrueType/OpenType font of the legend's text (default: Debian's "
                "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf)",
                AT(legend.font), [](const std::string&) { return std::string(); }),
    };
}

// The image, the camera and the random seed.
std::vector<Setting> viewRows() {
    using scene::Change;
    using K = SettingKind;
    static const std::string kSizeHelp = strCat("image size, 1..", scene::kMaxImageSide, " per side");
    return {
        compound({.option = "--size",
                  .keyword = "width|height",
                  .section = "image",
                  .key = "width|height",
                  .unit = "pixels",
                  .valueName = "WxH",
                  .help = kSizeHelp,
                  .invalidates = Change::ImageSize}),
        compound({.option = "--camera",
                  .keyword = "camera",
                  .section = "camera",
                  .key = "eye|target|up",
                  .valueName = "EX EY EZ TX TY TZ UX UY UZ",
                  .help = "eye, target and up in world space (default: a three-quarter view)",
                  .invalidates = Change::Camera}),
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
    };
}

// The medium and its lighting, the cut-aways.
std::vector<Setting> mediumRows() {
    using scene::Change;
    using K = SettingKind;
    constexpr double kInf = INFINITY;
    return {
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
        compound({.option = "--ambient",
                  .keyword = "ambient",
                  .section = "render",
                  .key = "ambient",
                  .valueName = "R G B",
                  .help = "uniform environment radiance (default 1 1 1)",
                  .invalidates = Change::Lighting}),
        compound({.option = "--background",
                  .keyword = "background",
                  .section = "render",
                  .key = "background",
                  .valueName = "R G B",
                  .help = "radiance seen by primary rays that escape (default 0 0 0: the data, lit by the ambient, "
                          "on black)",
                  .invalidates = Change::Lighting}),
        compound({.option = "--light-dir",
                  .keyword = "lights",
                  .key = "lights",
                  .valueName = "X Y Z R G B",
                  .help = "directional light towards X Y Z (world) with radiance R G B (repeatable)",
                  .invalidates = Change::Lighting}),
        compound({.option = "--light-point",
                  .keyword = "lights",
                  .key = "lights",
                  .valueName = "X Y Z R G B",
                  .help = "point light at X Y Z (world) with intensity R G B (repeatable)",
                  .invalidates = Change::Lighting}),
        compound({.option = "--crop",
                  .keyword = "crop",
                  .section = "cut",
                  .key = "crop",
                  .valueName = "X0 Y0 Z0 X1 Y1 Z1",
                  .help = "cut-away: keep only the medium inside the box X0 Y0 Z0 .. X1 Y1 Z1 (world space); the "
                          "rest is empty, the field inside is reconstructed as before (docs/cut-aways.md)",
                  .invalidates = Change::Medium}),
        compound({.option = "--clip",
                  .keyword = "clip",
                  .section = "cut",
                  .key = "clip",
                  .valueName = "PX PY PZ NX NY NZ",
                  .help = "cut-away: remove the half-space in front of the plane through PX PY PZ with normal NX NY "
                          "NZ (world space; the side the normal points to is removed; repeatable, at most 4)",
                  .invalidates = Change::Medium}),
    };
}

std::vector<Setting> makeTable() {
    std::vector<Setting> all = tfRows();
    for (auto rows : {methodRows(), combinationRows(), std::vector<Setting>{sppRow()}, legendRows(), structureRows(),
                      viewRows(), mediumRows()})
        all.insert(all.end(), rows.begin(), rows.end());
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

bool listHolds(std::string_view list, std::string_view name) {
    for (size_t at = 0; at <= list.size();) {
        const size_t bar = std::min(list.find('|', at), list.size());
        if (list.substr(at, bar - at) == name) return !name.empty();
        at = bar + 1;
    }
    return false;
}

const Setting* settingForKeyword(std::string_view keyword) {
    for (const Setting& s : settingTable())
        if (listHolds(s.keyword, keyword)) return &s;
    return nullptr;
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

std::string settingTextError(const Setting& s, const std::string& text) {
    if (s.kind == SettingKind::Choice) return settingChoiceError(s, text);
    return s.kind == SettingKind::Text && s.check ? s.check(text) : "";
}

void setSettingName(const Setting& s, Session& session, const std::string& value, std::string_view name) {
    const std::string why = settingTextError(s, value);
    AMRVK_CHECK(why.empty(), name, ": ", why);
    try {
        s.setName(session, value);
    } catch (const Error& e) {  // a request no session holds ("auto")
        throw Error(strCat(name, ": ", e.what()));
    }
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
    if (s.kind == SettingKind::Compound) return "";
    if (s.kind == SettingKind::Choice || s.kind == SettingKind::Text) return s.name(kStart);
    if (s.kind == SettingKind::Flag) return s.number(kStart) != 0 ? "true" : "false";
    return formatDouble(s.number(kStart));
}

void setSettingFromText(const Setting& s, Session& session, const std::string& text, std::string_view name) {
    AMRVK_CHECK(s.kind != SettingKind::Compound, "internal: ", s.option, " is parsed by its front end");
    if (s.kind == SettingKind::Choice || s.kind == SettingKind::Text) {
        setSettingName(s, session, text, name);
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
    AMRVK_CHECK(s.kind != SettingKind::Compound, "internal: ", s.option, " is copied by its front end");
    if (s.kind == SettingKind::Choice || s.kind == SettingKind::Text)
        s.setName(to, s.name(from));
    else
        s.setNumber(to, s.number(from));
}

}  // namespace amrvk::session
