#pragma once
// Every command-line option of amrvk, declared once (name, default, range, help) with CLI11 and
// shared by the commands that take it: read options (info, convert, render, view, bench), the
// picture options (render and view, most of them bench too), device options. Values are checked
// where they are declared (ranges, finite numbers, names), so every command reports a bad value
// in the same one line.
#include <CLI/CLI.hpp>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "amr/readers.h"
#include "core/file_io.h"
#include "gpu/context.h"
#include "session/picture_description.h"

namespace amrvk::cli {

// A finite number in [lo, hi] (open ends where asked); the message names the value and the
// interval, e.g. "0 is outside [1, 16777216]" (session::settingRangeError's words) or "'x' is not a
// number". CLI11 reads "nan" and "inf" as numbers; these checks do not let them through.
CLI::Validator interval(double lo, double hi, bool openLo = false, bool openHi = false);

struct ReadArgs {
    std::string format = "auto";
    std::vector<std::string> fields;
    std::string nan = "reject";
    std::vector<int> dims;
    std::string type;
    double threshold = 0;
    std::string scale = "auto";
    double logFloor = 0;
};
// --format, --field (repeatable where multiField), --nan, --scale, --log-floor, --dims, --type,
// --threshold.
void addReadOptions(CLI::App& app, ReadArgs& a, bool multiField);
amr::ReadOptions readOptions(const ReadArgs& a);

struct DeviceArgs {
    gpu::ContextOptions context;  // --device, --validation, --gpu-timeout, --samples-per-invocation
    std::string shaderDir;
};
// --device, --shader-dir, --validation, --gpu-timeout, --samples-per-invocation.
void addDeviceOptions(CLI::App& app, DeviceArgs& a);

// The options that make a picture (render, view; bench takes a subset).
struct PictureArgs {
    std::string session;
    // The settings of session::settingTable() registered here (addSetting), by option: the text
    // given (or the Session's default), and the flags.
    std::map<std::string, std::string, std::less<>> settings;
    std::map<std::string, bool, std::less<>> flags;
    // The table's compound settings, parsed here (pictureSettings, describePicture).
    std::string tf = "layers", tfPreset;
    std::vector<double> tfRange;
    std::string size = "512x512";
    std::vector<double> camera;
    std::vector<double> ambient, background, lightDir, lightPoint;
    std::vector<double> crop, clip;  // --crop X0 Y0 Z0 X1 Y1 Z1, --clip PX PY PZ NX NY NZ (repeatable)
};
// Every picture option; bench passes subset = true to leave out what it sets per run (mode, TF,
// structure, spp, session, dt, dvr shading).
void addPictureOptions(CLI::App& app, PictureArgs& a, bool subset = false);

// A time series, turntable or movie of `amrvk render` (docs/movies.md).
struct SeriesArgs {
    std::string range = "union";
    double orbit = 0;     // degrees over the series
    int64_t frames = 0;   // frames of one input
    double fps = 24;
    std::string framesDir;
};
// --series-range, --orbit, --frames, --fps, --frames-dir.
void addSeriesOptions(CLI::App& app, SeriesArgs& a);

// Lights, ambient, background, camera vectors, cut-away and image size from the options given on
// the command line, on top of `base` (a session's settings or the defaults); camera only when
// --camera was given. The table's settings (mode, fov, seed, medium, ...) are applySettingTable's.
scene::RenderSettings pictureSettings(const CLI::App& app, const PictureArgs& a, scene::RenderSettings base);
// The settings of session::settingTable() that `app` registered, into `s`: each one given on the
// command line, or (`all`) every one, its default included.
void applySettingTable(const CLI::App& app, const PictureArgs& a, session::Session& s, bool all);

// "WxH" with 1 <= W, H <= 16384.
void parseSize(const std::string& option, const std::string& text, int& width, int& height);

// The picture a render or view describes (input: the data set argument, empty when none):
// --session FILE when given, then every option given explicitly on top of it; without a session
// the options' defaults, with what the defaults leave open fitted to the data once it is read
// (session::resolvePicture): the TF over the field's range (unless --tf-range), the default
// camera (unless --camera), the traversal (unless --traversal; --traversal auto probes).
session::PictureDescription describePicture(const CLI::App& app, const std::string& input, const ReadArgs& read,
                                            const PictureArgs& a);

// The files a picture command reads, by the option that names them: the input, --session, --tf
// (when a file), --legend-font and extra (e.g. --script), for checkOutputs before any work.
std::vector<NamedPath> pictureInputs(const CLI::App& app, const std::string& input, const PictureArgs& a,
                                     std::vector<NamedPath> extra = {});

// Whether `name` is an option of `app` and was given on the command line.
bool given(const CLI::App& app, const std::string& name);

// amrvk's help layout (usage, wrapped descriptions with their checks and defaults), the "options"
// group and -h,--help; every command calls it right after making its App.
void setUpCommand(CLI::App& app);

// Parses argv (after the subcommand) into `app`; --help prints the help and returns false (the
// command then exits 0). Errors throw CLI::ParseError, which main prints as one line.
bool parseCommandLine(CLI::App& app, const std::vector<std::string>& argv);

// What an error thrown by a command says, as one line (main prints "amrvk COMMAND: error: " before
// it): CLI11's parse errors naming the option and value, "out of memory", or the message.
std::string errorText(std::exception_ptr error, const std::string& command);

}  // namespace amrvk::cli
