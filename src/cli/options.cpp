#include "cli/options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "accel/range_grid.h"
#include "core/error.h"
#include "gpu/shader_library.h"
#include "scene/transfer_function.h"

namespace amrvk::cli {

namespace {

constexpr int kMaxImageSide = 16384;

constexpr size_t kHelpWidth = 100;  // characters per help line

// Breaks `text` into lines of at most `width` characters at spaces (longer words stay whole).
std::string wrapText(const std::string& text, size_t width) {
    std::string out, line;
    std::istringstream words(text);
    for (std::string word; words >> word;) {
        if (!line.empty() && line.size() + 1 + word.size() > width) {
            out += line + "\n";
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
    }
    return out + line;
}

// amrvk's help: usage, description, then per group "--name VALUES   help (check; default: X)".
class HelpFormatter : public CLI::Formatter {
public:
    HelpFormatter() {
        label("Usage", "usage");
        label("OPTIONS", "options");
        label("Positionals", "arguments");
        column_width(34);
    }
    std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override {
        const std::string help = make_usage(app, name) + "\n" + make_description(app) + make_positionals(app) +
                                 make_groups(app, mode) + "\n";
        return CLI::detail::find_and_replace(help, "\n\n\n", "\n\n");  // one blank line between groups
    }
    std::string make_option_opts(const CLI::Option* opt) const override {
        if (opt->get_type_size() == 0) return "";
        const std::string type = opt->get_type_name();
        return " " + type.substr(0, type.find(':'));  // checks go into the description
    }
    std::string make_option_desc(const CLI::Option* opt) const override {
        std::vector<std::string> notes;
        const std::string type = opt->get_type_name();
        for (size_t at = type.find(':'); at != std::string::npos;) {
            const size_t next = type.find(':', at + 1);
            notes.push_back(type.substr(at + 1, next == std::string::npos ? next : next - at - 1));
            at = next;
        }
        if (opt->get_required()) notes.push_back("required");
        if (opt->get_type_size() > 0 && opt->get_expected_max() > 1) notes.push_back("repeatable");
        if (!opt->get_default_str().empty()) notes.push_back("default: " + opt->get_default_str());
        std::string desc = opt->get_description();
        for (size_t i = 0; i < notes.size(); ++i) desc += (i == 0 ? " (" : "; ") + notes[i];
        return wrapText(notes.empty() ? desc : desc + ")", kHelpWidth - get_column_width());
    }
};

std::optional<double> parseNumber(const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || !end || *end != '\0' || std::isnan(v)) return std::nullopt;
    return v;
}

// Integers, also written as an exact exponent form (1e6).
std::optional<int64_t> parseInteger(const std::string& text) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (!text.empty() && end && *end == '\0' && errno == 0) return v;
    const std::optional<double> d = parseNumber(text);
    if (d && std::abs(*d) < 9.0e18 && *d == std::trunc(*d)) return int64_t(*d);
    return std::nullopt;
}

// "WxH" with 1 <= W, H <= kMaxImageSide, or nullopt.
std::optional<std::pair<int, int>> parseImageSize(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, tail = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &tail) != 3 || (x != 'x' && x != 'X')) return std::nullopt;
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide) return std::nullopt;
    return std::make_pair(w, h);
}

std::string vecText(glm::dvec3 v) { return strCat(v.x, " ", v.y, " ", v.z); }

glm::dvec3 vec3At(const double* v) { return {v[0], v[1], v[2]}; }

// An option that takes an enum by name: the parser throws the domain's one-line error.
template <typename Parse>
CLI::Option* addChoice(CLI::App& app, const std::string& name, const std::string& choices, Parse parse,
                       const std::string& defaultName, const std::string& help) {
    return app.add_option_function<std::string>(name, parse, help)->type_name(choices)->default_str(defaultName);
}

}  // namespace

void setUpCommand(CLI::App& app) {
    app.formatter(std::make_shared<HelpFormatter>());
    app.option_defaults()->group("options");
    app.set_help_flag("-h,--help", "show this help and exit");
    app.allow_extras();  // reported by parseCommandLine in amrvk's words
}

bool parseCommandLine(CLI::App& app, std::vector<std::string> args) {
    const std::string see = " (see " + app.get_name() + " --help)";
    std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last first
    try {
        app.parse(args);
    } catch (const CLI::CallForHelp&) {
        std::fputs(app.help().c_str(), stdout);
        return false;
    } catch (const CLI::ValidationError& e) {
        throw Error(e.what());
    } catch (const CLI::ParseError& e) {
        throw Error(e.what() + see);
    }
    for (const std::string& extra : app.remaining()) {
        const bool option = extra.size() > 1 && extra[0] == '-' && !parseNumber(extra);
        AMRVK_CHECK(!option, "unknown option '", extra.substr(0, extra.find('=')), "'", see);
    }
    AMRVK_CHECK(app.remaining().empty(), "unexpected argument '", app.remaining().front(), "'", see);
    return true;
}

CLI::Validator integerIn(int64_t lo, int64_t hi) {
    const std::string interval = hi == std::numeric_limits<int64_t>::max() ? strCat("[", lo, ", inf)")
                                                                           : strCat("[", lo, ", ", hi, "]");
    return CLI::Validator(
        [lo, hi, interval](std::string& text) -> std::string {
            const std::optional<int64_t> v = parseInteger(text);
            if (!v) return "'" + text + "' is not an integer";
            if (*v < lo || *v > hi) return strCat(*v, " is outside ", interval);
            text = std::to_string(*v);  // 1e6 -> 1000000 for the conversion that follows
            return {};
        },
        "in " + interval);
}

CLI::Validator numberIn(double lo, double hi, Open open) {
    const bool openLo = open == Open::Low || open == Open::Both, openHi = open == Open::High || open == Open::Both;
    const std::string interval = strCat(openLo ? "(" : "[", lo, ", ", hi, openHi ? ")" : "]");
    return CLI::Validator(
        [=](std::string& text) -> std::string {
            const std::optional<double> v = parseNumber(text);
            if (!v) return "'" + text + "' is not a number";
            if (*v < lo || *v > hi || (openLo && *v == lo) || (openHi && *v == hi))
                return text + " is outside " + interval;
            return {};
        },
        "in " + interval);
}

CLI::Validator finiteNumber() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            const std::optional<double> v = parseNumber(text);
            return v && std::isfinite(*v) ? std::string() : "'" + text + "' is not a finite number";
        },
        "");
}

void addReadOptions(CLI::App& app, amr::ReadOptions& ro, bool multiField) {
    const std::string group = "input";
    app.add_option("--format", ro.format, "input format (auto: detected from names and magic bytes)")
        ->type_name("auto|exabrick|amrex|enzo|chombo|raw")
        ->default_str(ro.format)
        ->group(group);
    if (multiField) {
        app.add_option("--field", ro.fields, "field to load; repeat for more")
            ->type_name("NAME")
            ->allow_extra_args(false)
            ->default_str("all")
            ->group(group);
    } else {
        app.add_option_function<std::string>(
               "--field", [&ro](const std::string& f) { ro.fields = {f}; }, "field to use")
            ->type_name("NAME")
            ->default_str("the first")
            ->group(group);
    }
    addChoice(
        app, "--nan", "reject|drop", [&ro](const std::string& p) { ro.nanPolicy = amr::parseNanPolicy(p); },
        ro.nanPolicy == amr::NanPolicy::Reject ? "reject" : "drop",
        "NaN/Inf values are an error, or their cells are removed")
        ->group(group);
    app.add_option_function<std::array<int, 3>>(
           "--dims", [&ro](const std::array<int, 3>& d) { ro.rawDims = {d[0], d[1], d[2]}; },
           "raw volumes: voxels per axis (else from a name like v_64x64x64_uint8.raw)")
        ->type_name("NX NY NZ")
        ->transform(integerIn(1, 1 << 20))
        ->group(group);
    app.add_option("--type", ro.rawType, "raw volumes: voxel type (else from the name)")
        ->type_name("uint8|uint16|float32|float64")
        ->group(group);
    app.add_option("--threshold", ro.rawThreshold, "raw volumes: merge a block into one cell when max - min <= T")
        ->type_name("T")
        ->check(numberIn(0, std::numeric_limits<double>::infinity(), Open::High))
        ->default_str(strCat(ro.rawThreshold))
        ->group(group);
}

void addFieldOption(CLI::App& app, std::string& field) {
    app.add_option("--field", field, "field of every input that does not name one (input:field)")
        ->type_name("NAME")
        ->default_str("the first")
        ->group("input");
}

void addModeOptions(CLI::App& app, scene::RenderSettings& rs) {
    addChoice(
        app, "--mode", "ae|ss|ms|dvr", [&rs](const std::string& m) { rs.mode = scene::parseMode(m); },
        scene::modeName(rs.mode),
        "absorption+emission, single or multiple scattering (unbiased), or the ray-marching baseline dvr "
        "(biased by --dt)")
        ->group("picture");
    app.add_option("--dt", rs.dvrStep, "dvr: step as a fraction of the finest cell width at the sample")
        ->type_name("DT")
        ->check(numberIn(0, 64, Open::Low))
        ->default_str(strCat(rs.dvrStep))
        ->group("picture");
    app.add_flag("--dvr-shading", rs.dvrShading, "dvr: gradient shading by the first --light-dir (else a headlight)")
        ->group("picture");
}

CLI::Option* addImageOptions(CLI::App& app, scene::RenderSettings& rs) {
    CLI::Option* size = app.add_option_function<std::string>(
                               "--size",
                               [&rs](const std::string& text) {
                                   std::tie(rs.width, rs.height) = parseImageSize(text).value();
                               },
                               "image size in pixels")
                            ->type_name("WxH")
                            ->check(CLI::Validator(
                                [](std::string& text) {
                                    return parseImageSize(text) ? std::string()
                                                                : strCat("'", text, "' is not WxH with 1 <= W, H <= ",
                                                                         kMaxImageSide);
                                },
                                ""))
                            ->default_str(strCat(rs.width, "x", rs.height))
                            ->group("picture");
    app.add_option("--seed", rs.seed, "random seed")
        ->type_name("S")
        ->transform(integerIn(0, std::numeric_limits<uint32_t>::max()))
        ->default_str(strCat(rs.seed))
        ->group("picture");
    return size;
}

void addLightingOptions(CLI::App& app, scene::RenderSettings& rs) {
    const std::string group = "medium and lights";
    app.add_option("--density-scale", rs.densityScale, "multiplies extinction (TF alpha per finest cell width)")
        ->type_name("S")
        ->check(numberIn(0, std::numeric_limits<double>::infinity(), Open::High))
        ->default_str(strCat(rs.densityScale))
        ->group(group);
    app.add_option("--g", rs.g, "Henyey-Greenstein asymmetry (used clamped to [-0.999, 0.999])")
        ->type_name("G")
        ->check(numberIn(-1, 1))
        ->default_str(strCat(rs.g))
        ->group(group);
    app.add_option_function<std::array<double, 3>>(
           "--ambient", [&rs](const std::array<double, 3>& v) { rs.ambient = vec3At(v.data()); },
           "uniform environment radiance")
        ->type_name("R G B")
        ->check(finiteNumber())
        ->default_str(vecText(rs.ambient))
        ->group(group);
    app.add_option_function<std::array<double, 3>>(
           "--background", [&rs](const std::array<double, 3>& v) { rs.background = vec3At(v.data()); },
           "radiance seen by primary rays that escape")
        ->type_name("R G B")
        ->check(finiteNumber())
        ->default_str("the ambient")
        ->group(group);
    for (const bool point : {false, true}) {
        app.add_option_function<std::vector<std::array<double, 6>>>(
               point ? "--light-point" : "--light-dir",
               [&rs, point](const std::vector<std::array<double, 6>>& lights) {
                   for (const auto& v : lights) rs.lights.push_back({point, vec3At(&v[0]), vec3At(&v[3])});
               },
               point ? "point light at X Y Z (world) with intensity R G B"
                     : "directional light towards X Y Z (world) with radiance R G B")
            ->type_name("X Y Z R G B")
            ->check(finiteNumber())
            ->allow_extra_args(false)
            ->group(group);
    }
}

std::optional<scene::Camera> CameraChoice::explicitCamera() const {
    if (!eyeTargetUp) return std::nullopt;
    scene::Camera c;
    c.eye = (*eyeTargetUp)[0];
    c.target = (*eyeTargetUp)[1];
    c.up = (*eyeTargetUp)[2];
    c.fovYDegrees = fovDegrees;
    return c;
}

scene::Camera CameraChoice::cameraFor(glm::dvec3 worldLo, glm::dvec3 worldHi) const {
    return explicitCamera().value_or(scene::defaultCamera(worldLo, worldHi, fovDegrees));
}

void addCameraOptions(CLI::App& app, CameraChoice& camera) {
    app.add_option_function<std::array<double, 9>>(
           "--camera",
           [&camera](const std::array<double, 9>& v) {
               camera.eyeTargetUp = {vec3At(&v[0]), vec3At(&v[3]), vec3At(&v[6])};
           },
           "eye, target and up in world space")
        ->type_name("EX EY EZ TX TY TZ UX UY UZ")
        ->check(finiteNumber())
        ->default_str("a three-quarter view of the data")
        ->group("camera");
    app.add_option("--fov", camera.fovDegrees, "vertical field of view in degrees")
        ->type_name("DEG")
        ->check(numberIn(0, 180, Open::Both))
        ->default_str(strCat(camera.fovDegrees))
        ->group("camera");
}

void addStructureOptions(CLI::App& app, scene::StructureConfig& config, bool* autoTraversal) {
    const std::string group = "structures";
    addChoice(
        app, "--traversal",
        std::string("grid-dda|grid-bvh|abr|brick|ext-brick|kdtree") + (autoTraversal ? "|auto" : ""),
        [&config, autoTraversal](const std::string& t) {
            if (autoTraversal && t == "auto") *autoTraversal = true;
            else config.traversal = scene::parseTraversal(t);
        },
        scene::traversalName(config.traversal),
        std::string("majorant traversal: macrocell DDA, BVH over non-empty macrocells, ABRs, brick bounds, brick "
                    "domains, or the TF-specific kd-tree") +
            (autoTraversal ? "; auto: probe every combination briefly and take the most efficient traversal, "
                             "sampler, back-end and grid (those given explicitly stay fixed)"
                           : ""))
        ->group(group);
    addChoice(
        app, "--sampler", "ext-brick|abr|dense",
        [&config](const std::string& s) { config.sampler = scene::parseSampler(s); },
        scene::samplerName(config.sampler),
        "sample reconstruction: brick domains, ABRs, or dense = the field resampled to the finest uniform grid "
        "(trilinear; the cost floor; needs a grid traversal)")
        ->group(group);
    addChoice(
        app, "--backend", "sw|rq|auto", [&config](const std::string& b) { config.backend = scene::parseBackend(b); },
        scene::backendName(config.backend),
        "box hierarchies: software BVH, VK_KHR_ray_query, or rq where the device has it")
        ->group(group);
}

void addGridOption(CLI::App& app, std::string& grid) {
    // accel::parseGridDims throws its own one-line error ("--grid 'big': expected auto, N or
    // NxMxK"), which leaves the parser as it is; any box checks the syntax.
    const CLI::Validator syntax(
        [](std::string& text) {
            accel::parseGridDims(text, amr::Box3l{glm::i64vec3(0), glm::i64vec3(4096)});
            return std::string();
        },
        "");
    app.add_option("--grid", grid, "macrocell grid of grid-dda and grid-bvh (auto: 128 on the longest axis)")
        ->type_name("auto|N|NxMxK")
        ->check(syntax)
        ->default_str(grid)
        ->group("structures");
}

void addStructureSizeOptions(CLI::App& app, scene::StructureConfig& config) {
    const std::string group = "structures";
    addGridOption(app, config.grid);
    app.add_option("--kd-leaves", config.kdLeaves, "kdtree: leaves of the kd-tree, rebuilt per TF")
        ->type_name("N")
        ->transform(integerIn(1, int64_t(1) << 24))
        ->default_str(strCat(config.kdLeaves))
        ->group(group);
    app.add_option_function<uint64_t>(
           "--dense-max-mib", [&config](uint64_t mib) { config.denseMaxBytes = mib << 20; },
           "dense: largest dense grid to build")
        ->type_name("MIB")
        ->transform(integerIn(1, int64_t(1) << 20))
        ->default_str(strCat(config.denseMaxBytes >> 20))
        ->group(group);
}

void addTfRangeOption(CLI::App& app, std::optional<std::pair<float, float>>& range) {
    app.add_option_function<std::array<double, 2>>(
           "--tf-range",
           [&range](const std::array<double, 2>& v) {
               if (v[0] > v[1]) throw CLI::ValidationError("--tf-range", strCat("LO ", v[0], " is above HI ", v[1]));
               range = std::make_pair(float(v[0]), float(v[1]));
           },
           "map the TF's node range onto [LO, HI]")
        ->type_name("LO HI")
        ->check(finiteNumber())
        ->default_str("the field's range")
        ->group("transfer function");
}

void addTransferFunctionOptions(CLI::App& app, TfChoice& tf) {
    std::string presets;
    for (const std::string& p : scene::presetNames()) presets += (presets.empty() ? "" : ", ") + p;
    app.add_option("--tf", tf.spec, "transfer function: ParaView preset JSON, .xf file, or a preset (" + presets + ")")
        ->type_name("FILE|PRESET")
        ->default_str(tf.spec)
        ->group("transfer function");
    app.add_option("--tf-preset", tf.preset, "preset name inside a ParaView JSON file")
        ->type_name("NAME")
        ->default_str("the first")
        ->group("transfer function");
    addTfRangeOption(app, tf.range);
}

void addDeviceOptions(CLI::App& app, gpu::ContextOptions& co) {
    app.add_option("--device", co.device, "Vulkan device by index or name part (see amrvk devices)")
        ->type_name("INDEX|NAME")
        ->default_str("the first discrete GPU, else any")
        ->group("device");
    app.add_option_function<std::string>(
           "--shader-dir", [](const std::string& dir) { gpu::setShaderDirectory(dir); },
           "load shaders (.spv or .comp) from DIR instead of the embedded ones")
        ->type_name("DIR")
        ->group("device");
    app.add_flag("--validation", co.validation, "enable the Vulkan validation layer (also AMRVK_VALIDATION=1)")
        ->group("device");
}

}  // namespace amrvk::cli
