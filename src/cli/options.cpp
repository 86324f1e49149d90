#include "cli/options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>

#include "core/checked_size.h"
#include "core/error.h"
#include "core/strings.h"
#include "scene/limits.h"
#include "session/setting_table.h"

namespace amrvk::cli {

CLI::Validator interval(double lo, double hi, bool openLo, bool openHi) {
    auto bound = [](double v) {
        if (std::isinf(v)) return std::string(v < 0 ? "-inf" : "inf");
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.10g", v);
        return std::string(buf);
    };
    const std::string text = (openLo ? "(" : "[") + bound(lo) + ", " + bound(hi) + (openHi ? ")" : "]");
    return CLI::Validator(
        [=](std::string& s) -> std::string {
            std::string why;
            const std::optional<double> parsed = session::numberInText(s, why);
            if (!parsed) return why;
            const double v = *parsed;
            if (!std::isfinite(v)) return "'" + s + "' is not a finite number";
            const bool inside = (openLo ? v > lo : v >= lo) && (openHi ? v < hi : v <= hi);
            return inside ? std::string() : s + " is outside " + text;  // as session::settingRangeError words it
        },
        text);
}

// (options.h) Whether `name` is an option of `app` and was given on the command line.
bool given(const CLI::App& app, const std::string& name) {
    const CLI::Option* o = app.get_option_no_throw(name);
    return o && o->count() > 0;
}

namespace {

const CLI::Validator kFinite = interval(-INFINITY, INFINITY, true, true).description("FINITE");  // any finite number

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

// amrvk's help: "usage:", the description, then "  --name VALUES   help (check; default: X)", the
// checks CLI11 appends to the type name moved into the description, wrapped to kHelpWidth.
class HelpFormatter : public CLI::Formatter {
public:
    HelpFormatter() {
        label("Usage", "usage");
        label("OPTIONS", "options");
        label("Positionals", "arguments");
        column_width(34);
    }
    std::string make_help(const CLI::App* app, std::string name, CLI::AppFormatMode mode) const override {
        const std::string help = make_usage(app, name) + "\n" + wrapText(app->get_description(), kHelpWidth) + "\n" +
                                 make_positionals(app) + make_groups(app, mode) + "\n";
        return CLI::detail::find_and_replace(help, "\n\n\n",
                                             "\n\n");  // one blank line between groups
    }
    std::string make_option_opts(const CLI::Option* opt) const override {
        if (opt->get_type_size() == 0) return "";
        const std::string type = opt->get_type_name();
        return " " + type.substr(0, type.find(':'));
    }
    std::string make_option_desc(const CLI::Option* opt) const override {
        std::vector<std::string> notes;
        const std::string type = opt->get_type_name();
        for (size_t at = type.find(':'); at != std::string::npos;) {
            const size_t next = type.find(':', at + 1);
            std::string note = type.substr(at + 1, next == std::string::npos ? next : next - at - 1);
            if (note.size() > 4 && note.compare(note.size() - 4, 4, " x 2") != 0 &&
                note.find(" x ") != std::string::npos)
                note = note.substr(0, note.find(" x "));  // "[1, 9] x 3": the count is in the type name
            const std::string shown = type.substr(0, type.find(':'));
            if (note == "FILE" || note == "DIR") note = "must exist";
            if (note.front() == '{' && shown.find('|') == std::string::npos)
                note = "one of " + CLI::detail::find_and_replace(note.substr(1, note.size() - 2), ",", ", ");
            if (note.front() != '{' && note != "FINITE") notes.push_back(note);  // else the type name lists the choices
            at = next;
        }
        if (opt->get_required()) notes.push_back("required");
        if (!opt->get_default_str().empty()) notes.push_back("default: " + opt->get_default_str());
        std::string desc = opt->get_description();
        for (size_t i = 0; i < notes.size(); ++i) desc += (i == 0 ? " (" : "; ") + notes[i];
        return wrapText(notes.empty() ? desc : desc + ")", kHelpWidth - get_column_width());
    }
};

glm::dvec3 vec3At(const std::vector<double>& v, size_t at) { return {v[at], v[at + 1], v[at + 2]}; }

// Lights given as repeated 6-number options.
void addLights(std::vector<scene::Light>& out, const std::vector<double>& values, bool point, const char* option) {
    for (size_t i = 0; i + 5 < values.size(); i += 6) {
        scene::Light L{point, vec3At(values, i), vec3At(values, i + 3)};
        AMRVK_CHECK(glm::all(glm::greaterThanEqual(L.radiance, glm::dvec3(0.0))), option, ": radiance ", L.radiance.x,
                    " ", L.radiance.y, " ", L.radiance.z, " must be >= 0");
        AMRVK_CHECK(point || glm::length(L.posOrDir) > 0, option, ": the direction 0 0 0 points nowhere");
        out.push_back(L);
    }
}

// A setting of session::settingTable(), registered from its row: help, limits, choices, the
// Session's default; kept as text (or a flag) in `a` until applySettingTable.
void addSetting(CLI::App& app, PictureArgs& a, std::string_view option) {
    const session::Setting& st = session::settingForOption(option);
    AMRVK_CHECK(st.kind != session::SettingKind::Compound, "internal: ", option, " is a compound (addCompound)");
    const std::string name(option);
    if (st.kind == session::SettingKind::Flag) {
        app.add_flag(name, a.flags[name], std::string(st.help));
        return;
    }
    std::string& value = a.settings[name] = session::settingDefault(st);
    CLI::Option* o = app.add_option(name, value, std::string(st.help))->capture_default_str();
    if (st.kind == session::SettingKind::Choice || st.kind == session::SettingKind::Text) {
        const bool choice = st.kind == session::SettingKind::Choice;
        o->check(CLI::Validator([&st](std::string& text) { return session::settingTextError(st, text); },
                                choice ? "{" + std::string(st.choices) + "}" : "TEXT"))
            ->type_name(std::string(choice && st.valueName.empty() ? st.choices : st.valueName));
        return;
    }
    o->check(CLI::Validator(
                 [&st](std::string& text) -> std::string {
                     std::string why;
                     const std::optional<double> v = session::numberInText(text, why);
                     return v ? session::settingRangeError(st, *v) : why;
                 },
                 session::settingLimits(st)))
        ->type_name(std::string(st.valueName));
}

// A compound setting of session::settingTable() (several values, parsed here): its help and value
// names from the row, bound to `target`.
template <typename T>
CLI::Option* addCompound(CLI::App& app, std::string_view option, T& target) {
    const session::Setting& st = session::settingForOption(option);
    AMRVK_CHECK(st.kind == session::SettingKind::Compound, "internal: ", option, " is not a compound");
    return app.add_option(std::string(option), target, std::string(st.help))->type_name(std::string(st.valueName));
}

}  // namespace

void applySettingTable(const CLI::App& app, const PictureArgs& a, session::Session& s, bool all) {
    for (const session::Setting& st : session::settingTable()) {
        const std::string name(st.option);
        // Only the rows addSetting registered: bench's --sub-majorants is a list of its own.
        const bool registered = a.settings.count(name) > 0 || a.flags.count(name) > 0;
        if (st.kind == session::SettingKind::Compound || !registered || !(all || given(app, name))) continue;
        if (!st.request.empty() && a.settings.at(name) == st.request) continue;  // the description resolves it
        if (st.kind == session::SettingKind::Flag)
            st.setNumber(s, a.flags.at(name) ? 1 : 0);
        else
            session::setSettingFromText(st, s, a.settings.at(name), st.option);
    }
}

void addReadOptions(CLI::App& app, ReadArgs& a, bool multiField) {
    app.add_option("--format", a.format, "input format (default: detected from names and magic bytes)")
        ->check(CLI::IsMember({"auto", "exabrick", "amrex", "enzo", "chombo", "carpet", "ramses", "raw"}))
        ->type_name("auto|exabrick|amrex|enzo|chombo|carpet|ramses|raw");
    CLI::Option* field =
        app.add_option("--field", a.fields,
                       multiField ? "field to load (repeatable; default: every field)"
                                  : "field to use (default: the density-like one, density, dens, rho or gas_density in "
                                    "any case, else the first)")
            ->type_name("NAME");
    if (multiField)
        field->take_all();
    else
        field->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::Throw);
    app.add_option("--nan", a.nan, "NaN/Inf values: reject = an error, drop = their cells are removed")
        ->check(CLI::IsMember({"reject", "drop"}))
        ->capture_default_str()
        ->type_name("reject|drop");
    app.add_option("--scale", a.scale,
                   "field values as they are (linear) or log10 of each cell's value, before reconstruction as yt "
                   "takes it (log): the TF, its range, the histogram and info then work on the logs; auto: log where "
                   "every value is positive and the largest is at least 100 times the smallest (the field shown "
                   "decides), else linear")
        ->check(CLI::IsMember({"auto", "linear", "log"}))
        ->capture_default_str()
        ->type_name("auto|linear|log");
    app.add_option("--log-floor", a.logFloor,
                   "--scale log: values below V (and every value <= 0) become log10(V) (default: the field's smallest "
                   "positive value)")
        ->check(interval(0, INFINITY, false, true))
        ->type_name("V");
    app.add_option("--dims", a.dims, "raw volumes: voxels per axis (else from a name like v_64x64x64_uint8.raw)")
        ->expected(3)
        ->check(interval(1, amr::kMaxRawDim))
        ->type_name("NX NY NZ");
    app.add_option("--type", a.type, "raw volumes: voxel type")
        ->check(CLI::IsMember({"uint8", "uint16", "float32", "float64"}))
        ->type_name("uint8|uint16|float32|float64");
    app.add_option("--threshold", a.threshold, "raw volumes: merge a block into one cell when max - min <= T")
        ->check(interval(0, INFINITY, false, true))
        ->capture_default_str()
        ->type_name("T");
}

amr::ReadOptions readOptions(const ReadArgs& a) {
    amr::ReadOptions ro;
    ro.format = a.format;
    ro.fields = a.fields;
    ro.nanPolicy = amr::parseNanPolicy(a.nan);
    ro.scale = amr::parseFieldScale(a.scale);
    ro.logFloor = a.logFloor;
    if (a.dims.size() == 3) ro.rawDims = glm::ivec3(a.dims[0], a.dims[1], a.dims[2]);
    ro.rawType = a.type;
    ro.rawThreshold = a.threshold;
    return ro;
}

void addDeviceOptions(CLI::App& app, DeviceArgs& a) {
    app.add_option("--device", a.context.device, "Vulkan device by index or name part (default: a discrete GPU, else any)")
        ->type_name("INDEX|NAME");
    app.add_option("--shader-dir", a.shaderDir,
                   "load shaders from DIR (.spv, or .comp compiled in process) instead of the "
                   "embedded ones")
        ->check(CLI::ExistingDirectory)
        ->type_name("DIR");
    app.add_flag("--validation", a.context.validation, "enable the Vulkan validation layer");
    app.add_option("--gpu-timeout", a.context.gpuTimeoutSeconds,
                   "seconds one GPU submission may run before amrvk ends with an error naming the work (a runaway "
                   "shader loop cannot be cancelled); 0 = adaptive: path tracing, the staged data-parallel "
                   "pass and the majorants past 32 x their measured pace (at least 10 s; a small first probe "
                   "measures it) end once they made no progress for 10 s (the majorants at once), other work "
                   "after 600 s")
        ->check(interval(0, 1e6))
        ->capture_default_str()
        ->type_name("S");
    app.add_option("--samples-per-invocation", a.context.samplesPerInvocation,
                   "samples per pixel one GPU thread takes per dispatch of whole samples (the same "
                   "image; fewer dispatches and accumulation writes); 0 = auto: 8 on CPU devices, 1 on GPUs")
        ->check(interval(0, 64))
        ->capture_default_str()
        ->type_name("N");
    app.add_flag("--path-regeneration", a.context.pathRegeneration,
                 "path regeneration: a workgroup's samples are a pool its GPU threads take one at a time, so a "
                 "thread whose path ended takes the next instead of waiting for the longest (the same image; on "
                 "lavapipe the lanes' use rose, the paths per second did not: docs/benchmarks.md)");
}

namespace {

// addPictureOptions' groups, each registering its options in --help's order.

// Where the picture starts: a saved session and the transfer function.
void addStartOptions(CLI::App& app, PictureArgs& a) {
    app.add_option("--session", a.session,
                   "start from a session file (the viewer's 'save session'); options given too "
                   "override it")
        ->check(CLI::ExistingFile)
        ->type_name("FILE");
    addCompound(app, "--tf", a.tf)->capture_default_str();
    addCompound(app, "--tf-preset", a.tfPreset);
}

// How the picture is made: the estimator, its majorant traversal, sampler and back-end, and the
// samples per pixel.
void addMethodOptions(CLI::App& app, PictureArgs& a) {
    for (const char* option : {"--mode", "--dt", "--dvr-shading", "--transmittance", "--control-extinction",
                               "--traversal", "--sampler", "--backend", "--spp"})
        addSetting(app, a, option);
}

// The colour legend drawn into PNG images.
void addLegendOptions(CLI::App& app, PictureArgs& a) {
    for (const char* option : {"--legend", "--legend-place", "--legend-title", "--legend-units", "--legend-font"})
        addSetting(app, a, option);
}

// The TF's value range and what its colours mean (bench too: its references are keyed by them).
void addTfRangeOption(CLI::App& app, PictureArgs& a) {
    addCompound(app, "--tf-range", a.tfRange)->expected(2)->check(kFinite);
    addSetting(app, a, "--tf-colors");
}

// The structures' sizes: macrocell grid, kd-tree leaves, sub-majorants (not for bench, whose
// --sub-majorants is a list of matrix rows), dense grid.
void addStructureOptions(CLI::App& app, PictureArgs& a, bool subset) {
    addSetting(app, a, "--grid");
    addSetting(app, a, "--kd-leaves");
    if (!subset) addSetting(app, a, "--sub-majorants");
    addSetting(app, a, "--dense-max-mib");
}

// The image and its camera, and the random seed.
void addViewOptions(CLI::App& app, PictureArgs& a) {
    addCompound(app, "--size", a.size)->capture_default_str();
    addCompound(app, "--camera", a.camera)->expected(9)->check(kFinite);
    addSetting(app, a, "--fov");
    addSetting(app, a, "--seed");
}

// The medium's scale and phase function, and its lighting.
void addMediumOptions(CLI::App& app, PictureArgs& a) {
    addSetting(app, a, "--density-scale");
    addSetting(app, a, "--g");
    addCompound(app, "--ambient", a.ambient)->expected(3)->check(interval(0, INFINITY, false, true));
    addCompound(app, "--background", a.background)->expected(3)->check(interval(0, INFINITY, false, true));
    addCompound(app, "--light-dir", a.lightDir)->expected(6)->take_all()->check(kFinite);
    addCompound(app, "--light-point", a.lightPoint)->expected(6)->take_all()->check(kFinite);
}

// Cut-aways: a crop box and clip planes.
void addCutAwayOptions(CLI::App& app, PictureArgs& a) {
    addCompound(app, "--crop", a.crop)->expected(6)->check(kFinite);
    addCompound(app, "--clip", a.clip)->expected(6)->take_all()->check(kFinite);
}

}  // namespace

void addPictureOptions(CLI::App& app, PictureArgs& a, bool subset) {
    if (!subset) {
        addStartOptions(app, a);
        addMethodOptions(app, a);
        addLegendOptions(app, a);
    }
    addTfRangeOption(app, a);
    addStructureOptions(app, a, subset);
    addViewOptions(app, a);
    addMediumOptions(app, a);
    addCutAwayOptions(app, a);
}

void addSeriesOptions(CLI::App& app, SeriesArgs& a) {
    app.add_option("--series-range", a.range,
                   "several inputs: one TF over the first output's field range, or the union of every output's "
                   "(a reading pass first); layers, spiky and foggy fitted to the first output's distribution or "
                   "to all of them pooled, other presets in their range-fixed shape (one input: fitted to its data "
                   "as a single picture); --tf-range overrides both")
        ->check(CLI::IsMember({"first", "union"}))
        ->capture_default_str()
        ->type_name("first|union");
    app.add_option("--orbit", a.orbit,
                   "the camera turns DEG degrees about the data's centre (around its up vector) over the frames; "
                   "frame k of N at k*DEG/N")
        ->check(kFinite)
        ->type_name("DEG");
    app.add_option("--frames", a.frames, "a turntable: N frames of one input (with --orbit, e.g. --frames 120 --orbit 360)")
        ->check(interval(1, 100000))
        ->type_name("N");
    app.add_option("--fps", a.fps, "-o MOVIE.mp4: frames per second")
        ->check(interval(0, 1000, true))
        ->capture_default_str()
        ->type_name("F");
    app.add_option("--frames-dir", a.framesDir,
                   "-o MOVIE.mp4: keep the frames in DIR (DIR/frame_0000.png ...; else they go to MOVIE.mp4.frames/ "
                   "and are removed once the movie is written)")
        ->type_name("DIR");
}

void parseSize(const std::string& option, const std::string& text, int& width, int& height) {
    int a = 0, b = 0;
    char x = 0, tail = 0;
    const int n = std::sscanf(text.c_str(), "%d%c%d%c", &a, &x, &b, &tail);
    AMRVK_CHECK(n == 3 && (x == 'x' || x == 'X') && a > 0 && b > 0 && a <= scene::kMaxImageSide &&
                    b <= scene::kMaxImageSide,
                option, " '", text, "': expected WxH with 1 <= W, H <= ", scene::kMaxImageSide);
    // Host side: the float RGBA image, its readback copy and the 8-bit output (36 bytes a pixel).
    checkAllocation(uint64_t(a) * uint64_t(b) * 36, strCat(option, " ", text, ": the image"));
    width = a;
    height = b;
}

scene::RenderSettings pictureSettings(const CLI::App& app, const PictureArgs& a, scene::RenderSettings s) {
    const bool all = !given(app, "--session");
    auto use = [&](const char* name) { return (all && app.get_option_no_throw(name)) || given(app, name); };
    if (use("--size")) parseSize("--size", a.size, s.width, s.height);
    if (given(app, "--ambient")) s.ambient = vec3At(a.ambient, 0);
    if (given(app, "--background")) s.background = vec3At(a.background, 0);
    if (given(app, "--light-dir") || given(app, "--light-point")) {
        s.lights.clear();
        addLights(s.lights, a.lightDir, false, "--light-dir");
        addLights(s.lights, a.lightPoint, true, "--light-point");
        AMRVK_CHECK(s.lights.size() <= 8, "at most 8 lights (got ", s.lights.size(), ")");
    }
    if (given(app, "--camera")) {
        s.camera.eye = vec3At(a.camera, 0);
        s.camera.target = vec3At(a.camera, 3);
        s.camera.up = vec3At(a.camera, 6);
        AMRVK_CHECK(glm::length(s.camera.eye - s.camera.target) > 0, "--camera: eye and target coincide");
        AMRVK_CHECK(glm::length(glm::cross(s.camera.target - s.camera.eye, s.camera.up)) > 0,
                    "--camera: the up vector is parallel to the view direction");
    }
    if (given(app, "--crop")) s.cut.crop = scene::CropBox{vec3At(a.crop, 0), vec3At(a.crop, 3)};
    if (given(app, "--clip")) {
        s.cut.clips.clear();
        for (size_t i = 0; i + 6 <= a.clip.size(); i += 6) s.cut.clips.push_back({vec3At(a.clip, i), vec3At(a.clip, i + 3)});
    }
    scene::validateCutAway(s.cut);
    return s;
}

session::PictureDescription describePicture(const CLI::App& app, const std::string& input, const ReadArgs& read,
                                            const PictureArgs& a) {
    session::PictureDescription d;
    const bool fromSession = given(app, "--session");
    if (fromSession) d.session = session::loadSession(a.session);
    session::Session& s = d.session;
    if (!input.empty()) s.input = input;
    AMRVK_CHECK(!s.input.empty(), "no input data set (give one, or --session FILE)");
    const bool all = !fromSession;
    auto use = [&](const char* name) { return all || given(app, name); };
    if (use("--format")) s.read.format = read.format;
    if (use("--nan")) s.read.nanPolicy = amr::parseNanPolicy(read.nan);
    if (use("--scale")) s.read.scale = amr::parseFieldScale(read.scale);
    if (use("--log-floor")) s.read.logFloor = read.logFloor;
    if (given(app, "--dims")) s.read.rawDims = glm::ivec3(read.dims[0], read.dims[1], read.dims[2]);
    if (given(app, "--type")) s.read.rawType = read.type;
    if (use("--threshold")) s.read.rawThreshold = read.threshold;
    if (given(app, "--field")) s.field = read.fields.front();
    s.settings = pictureSettings(app, a, fromSession ? s.settings : session::Session{}.settings);
    applySettingTable(app, a, s, all);
    // The TF: the session's unless --tf or --tf-preset is given; --tf-range maps either.
    if (!fromSession || given(app, "--tf") || given(app, "--tf-preset"))
        d.tfSource = session::TfSource{.name = a.tf, .preset = a.tfPreset};
    if (given(app, "--tf-range")) d.tfRange = std::make_pair(float(a.tfRange[0]), float(a.tfRange[1]));
    d.fitCamera = !fromSession && !given(app, "--camera");
    const bool autoTraversal =
        given(app, "--traversal") && a.settings.at("--traversal") == session::settingForOption("--traversal").request;
    d.fit = autoTraversal                                   ? session::StructureFit::Probe
            : !given(app, "--traversal") && !fromSession ? session::StructureFit::Data
                                                            : session::StructureFit::None;
    for (const session::Setting& st : session::settingTable())
        if (st.section == "structure" && given(app, std::string(st.option))) d.given.insert(std::string(st.key));
    if (!autoTraversal) s.structure.validate();
    return d;
}

std::vector<NamedPath> pictureInputs(const CLI::App& app, const std::string& input, const PictureArgs& a,
                                     std::vector<NamedPath> extra) {
    std::vector<NamedPath> in = std::move(extra);
    if (!input.empty()) in.push_back({"input", input});
    if (given(app, "--session")) in.push_back({"--session", a.session});
    std::error_code ec;
    if (given(app, "--tf") && std::filesystem::exists(a.tf, ec)) in.push_back({"--tf", a.tf});
    if (given(app, "--legend-font")) {
        // Said before the outputs are checked against it ("-o lies inside the input --legend-font").
        const std::string& font = a.settings.at("--legend-font");
        AMRVK_CHECK(!std::filesystem::is_directory(font, ec), "--legend-font ", font,
                    ": not a font file (a directory)");
        in.push_back({"--legend-font", font});
    }
    return in;
}

void setUpCommand(CLI::App& app) {
    app.formatter(std::make_shared<HelpFormatter>());
    app.option_defaults()->group("options");
    app.set_help_flag("-h,--help", "show this help and exit");
}

bool parseCommandLine(CLI::App& app, const std::vector<std::string>& argv) {
    std::vector<std::string> reversed(argv.rbegin(),
                                      argv.rend());  // CLI11 takes them back to front
    try {
        app.parse(reversed);
    } catch (const CLI::CallForHelp&) {
        std::fputs(app.help().c_str(), stdout);
        return false;
    }
    return true;
}

namespace {

// CLI11's messages in amrvk's form: one line naming the option and the value (the argument
// elided: searched without std::regex, which recursed per character and overflowed the stack on
// an argument of 40,000 characters).
std::string parseErrorLine(const CLI::ParseError& e, const std::string& command) {
    std::string m = e.what();
    const std::string help = " (see amrvk " + command + " --help)";
    if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
        // "The following argument was not expected: X" or "...arguments were not expected: [X, Y]".
        std::string arg;
        if (const size_t at = m.find("expected:"); at != std::string::npos) {
            size_t start = m.find_first_not_of(" [", at + 9);
            if (start != std::string::npos) arg = m.substr(start, m.find_first_of(",] \t\n", start) - start);
        }
        if (arg.empty()) arg = m;
        return arg.rfind("-", 0) == 0 ? "unknown option '" + elide(arg) + "' for 'amrvk " + command + "'" + help
                                      : "unexpected argument '" + elide(arg) + "'" + help;
    }
    // "OPT: N required TYPE ... missing"
    if (m.find(" missing") != std::string::npos) {
        const size_t colon = m.find(": ");
        const size_t req = m.find(" required ");
        if (colon != std::string::npos && req != std::string::npos && colon < req &&
            m.find_first_of(" \t", 0) == colon + 1 && req > colon + 2 &&
            m.find_first_not_of("0123456789", colon + 2) == req) {
            const std::string n = m.substr(colon + 2, req - colon - 2);
            const size_t typeStart = req + 10;
            const std::string type = m.substr(typeStart, m.find_first_of(": \t", typeStart) - typeStart);
            return elide(m.substr(0, colon)) + ": expects " + (n == "1" ? "a value" : n + " values") + " (" + type +
                   ")" + help;
        }
    }
    // "Could not convert: OPT = VALUE"
    if (const size_t at = m.find("Could not convert: "); at != std::string::npos) {
        const size_t start = at + 19, space = m.find(' ', start);
        if (space != std::string::npos && space > start && m.compare(space, 3, " = ") == 0)
            return elide(m.substr(start, space - start)) + ": '" + elide(m.substr(space + 3)) + "' is not a number";
    }
    for (char& c : m)
        if (c == '\n' || c == '\r') c = ' ';
    return elide(m, 300) + help;
}
}  // namespace

// Always one line: messages of other exceptions than amrvk::Error (HDF5, the standard library, the
// command-line parser) may quote file contents or arguments too.
std::string errorText(std::exception_ptr error, const std::string& command) {
    try {
        std::rethrow_exception(error);
    } catch (const CLI::ParseError& e) {
        return oneLineMessage(parseErrorLine(e, command));
    } catch (const std::bad_alloc&) {
        return "out of memory";
    } catch (const std::exception& e) {
        return oneLineMessage(e.what());
    } catch (...) {
        return "unknown error";
    }
}

}  // namespace amrvk::cli
