// amrvk view: the interactive viewer (viewer/viewer_app.h), with every read and render option of
// amrvk render plus automation for scripts and tests.
#include <cstdio>

#include "amr/readers.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "core/file_io.h"
#include "session/legend_image.h"
#include "session/picture_description.h"
#include "viewer/logic/script.h"
#include "viewer/viewer_app.h"

namespace amrvk::cli {

namespace {

const char* kViewHelp =
    "The interactive viewer: turn the data around (left drag orbits, right drag or the wheel "
    "zooms, middle or "
    "shift drag pans; arrow keys, +/-, R resets), edit the transfer function over the field's "
    "histogram, "
    "switch mode, structures and lights, and watch the path-traced picture converge. It renders a "
    "small "
    "preview while you interact and refines at full resolution when you stop, within a time budget "
    "per "
    "frame, so the window stays responsive on slow devices. Sessions saved here render the same "
    "with "
    "amrvk render --session. --headless runs with no window (no display needed), for scripts and "
    "tests.";

}  // namespace

int runView(const std::vector<std::string>& argv) {
    CLI::App app(kViewHelp, "amrvk view");
    setUpCommand(app);
    std::string input;
    ReadArgs read;
    PictureArgs pic;
    DeviceArgs dev;
    viewer::ViewerOptions vo;
    std::string screenshot, script, stats, state, saveSession;
    int64_t frames = 0;
    double budgetMs = 50;
    std::string window;
    app.add_option("input", input, "the data set (as amrvk render; optional with --session)")->type_name("INPUT");
    addReadOptions(app, read, false);
    addPictureOptions(app, pic);
    app.get_option("--spp")->description("stop accumulating at N samples per pixel (default: run on)")->default_str("");
    addDeviceOptions(app, dev);
    app.add_flag("--headless", vo.headless, "no window (no display needed): for --script, --frames, --screenshot");
    app.add_option("--frames", frames, "stop after N frames (default: when the window closes; --headless needs it)")
        ->check(interval(1, 1e12))
        ->type_name("N");
    app.add_option("--screenshot", screenshot, "at exit, save the accumulated image without the UI (.png .exr .pfm)")
        ->type_name("FILE");
    app.add_option("--script", script, "frame-numbered actions (docs/viewer.md)")
        ->check(CLI::ExistingFile)
        ->type_name("FILE");
    app.add_option("--save-session", saveSession, "at exit, save the state as a session file (amrvk render --session)")
        ->type_name("FILE");
    app.add_option("--stats", stats, "at exit, write frame times and times to the first full sample as JSON")
        ->type_name("FILE");
    app.add_option("--state-file", state,
                   "after every frame, rewrite FILE with the live state as JSON, one member a line: frame, "
                   "samples, camera, layout, the panel's widgets, input taken (for programs and tests that "
                   "drive the window; docs/viewer.md)")
        ->type_name("FILE");
    app.add_option("--frame-budget-ms", budgetMs,
                   "target frame time; the path tracer gets what the UI and display leave of it")
        ->check(interval(1, 10000))
        ->capture_default_str()
        ->type_name("MS");
    app.add_option("--window", window, "window size (default: --size)")->type_name("WxH");
    if (!parseCommandLine(app, argv)) return 0;

    AMRVK_CHECK(!vo.headless || frames > 0 || !script.empty(),
                "--headless needs --frames N or a --script that quits (it has no window to close)");
    if (!screenshot.empty()) {
        const std::string ext = std::filesystem::path(screenshot).extension().string();
        AMRVK_CHECK(ext == ".png" || ext == ".exr" || ext == ".pfm", "--screenshot ", screenshot,
                    ": unknown image type (use .png, .exr or .pfm)");
    }
    // Every output checked before any work: writable, distinct, none of them an input.
    const std::vector<NamedPath> outputs = {
        {"--screenshot", screenshot}, {"--save-session", saveSession}, {"--stats", stats}, {"--state-file", state}};
    std::vector<NamedPath> inputs = pictureInputs(app, input, pic, {{"--script", script}});
    // Saving the session back where it came from is the ordinary Save (it was read whole before the
    // window opens and is written atomically): --save-session may name the --session file, which
    // every other output is still checked against.
    std::error_code same;
    const bool saveBack =
        !saveSession.empty() && app.count("--session") && std::filesystem::equivalent(saveSession, pic.session, same);
    const std::vector<NamedPath> others = {outputs[0], outputs[2], outputs[3]};
    auto checkAgainst = [&](std::vector<NamedPath> sources) {
        if (!saveBack) return checkOutputs(outputs, sources);
        checkOutputs(others, sources);
        std::erase_if(sources,
                      [&](const NamedPath& in) { return std::filesystem::equivalent(in.path, pic.session, same); });
        checkOutputs(outputs, sources);
    };
    checkAgainst(inputs);
    vo.start = describePicture(app, input, read, pic);
    // A PNG screenshot with the legend needs its font: checked before anything is read.
    if (vo.start.session.legend.show && std::filesystem::path(screenshot).extension() == ".png")
        session::openLegendFont(vo.start.session.legend);
    AMRVK_CHECK(vo.start.fit != session::StructureFit::Probe,
                "--traversal auto is for amrvk render (the viewer switches structures live)");
    if (!app.count("--spp") && app.count("--session") == 0) vo.start.session.spp = 0;  // run on
    // Checked before anything is read: a bad script line is one line naming it (the viewer checks
    // what needs its structures and shader directory again before frame 0).
    if (!script.empty()) viewer::loadScript(script);
    // Read before a window opens: a bad data set is one line, not a window that closes.
    std::shared_ptr<const scene::Volume> volume = session::loadVolume(vo.start.session);
    checkAgainst(inputFilesRead());  // and none is a file the data set was read from
    vo.frames = uint64_t(frames);
    vo.screenshot = screenshot;
    vo.script = script;
    vo.statsJson = stats;
    vo.stateJson = state;
    vo.saveSession = saveSession;
    vo.shaderDir = dev.shaderDir;
    vo.context = dev.context;
    vo.frameBudgetSeconds = budgetMs * 1e-3;
    if (!window.empty()) parseSize("--window", window, vo.windowWidth, vo.windowHeight);
    return viewer::runViewer(vo, std::move(volume));
}

}  // namespace amrvk::cli
