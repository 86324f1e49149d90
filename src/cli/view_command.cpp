// amrvk view: the interactive viewer (viewer/viewer_app.h), with every read and render option of
// amrvk render plus automation for scripts and tests.
#include <cstdio>

#include "amr/readers.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "cli/ranks.h"
#include "cli/view_ranks.h"
#include "core/error.h"
#include "core/file_io.h"
#include "session/legend_image.h"
#include "session/picture_description.h"
#include "session/series.h"
#include "viewer/logic/script.h"
#include "viewer/logic/series_player.h"
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

// The viewer's automation and window options.
struct ViewAutomationArgs {
    bool headless = false;
    int64_t frames = 0;
    std::string screenshot, script, saveSession, stats, state, window;
    double budgetMs = 50;
};

void addViewAutomationOptions(CLI::App& app, ViewAutomationArgs& a) {
    app.add_flag("--headless", a.headless, "no window (no display needed): for --script, --frames, --screenshot");
    app.add_option("--frames", a.frames, "stop after N frames (default: when the window closes; --headless needs it)")
        ->check(interval(1, 1e12))
        ->type_name("N");
    app.add_option("--screenshot", a.screenshot,
                   "at exit, save the picture on screen without the UI: the estimate, or the preview while the "
                   "estimate is grainier (.png .exr .pfm)")
        ->type_name("FILE");
    app.add_option("--script", a.script, "frame-numbered actions (docs/viewer.md)")
        ->check(CLI::ExistingFile)
        ->type_name("FILE");
    app.add_option("--save-session", a.saveSession,
                   "at exit, save the state as a session file (amrvk render --session)")
        ->type_name("FILE");
    app.add_option("--stats", a.stats, "at exit, write frame times and times to the first full sample as JSON")
        ->type_name("FILE");
    app.add_option("--state-file", a.state,
                   "after every frame, rewrite FILE with the live state as JSON, one member a line: frame, "
                   "samples, camera, layout, the panel's widgets, input taken (for programs and tests that "
                   "drive the window; docs/viewer.md)")
        ->type_name("FILE");
    app.add_option("--frame-budget-ms", a.budgetMs,
                   "target frame time; the path tracer gets what the UI and display leave of it")
        ->check(interval(1, 10000))
        ->capture_default_str()
        ->type_name("MS");
    app.add_option("--window", a.window, "window size (default: --size)")->type_name("WxH");
}

// The options of a time series and of MPI (several inputs; mpirun).
struct ViewSeriesArgs {
    std::string range = "union";
    std::string distribute = "samples";
    double fps = 4;
    double aheadMib = 1024;
};

void addViewSeriesOptions(CLI::App& app, ViewSeriesArgs& a) {
    app.add_option("--distribute", a.distribute,
                   "under mpirun: samples (every rank holds the data and traces a share of each pass); data-parallel "
                   "viewing is not built yet (render --distribute data renders it in batch)")
        ->check(CLI::IsMember({"samples", "data"}))
        ->capture_default_str();
    app.add_option("--series-range", a.range,
                   "a time series: one TF over the first output's field range, or the union of every output's (a "
                   "reading pass first), as amrvk render --series-range")
        ->check(CLI::IsMember({"first", "union"}))
        ->capture_default_str()
        ->type_name("first|union");
    app.add_option("--series-fps", a.fps, "a time series: steps per second while playing (space)")
        ->check(interval(0, viewer::kSeriesMaxFps, true))
        ->capture_default_str()
        ->type_name("F");
    app.add_option("--series-ahead-mib", a.aheadMib,
                   "a time series: host memory for the steps next to the shown one, read ahead beside the event loop "
                   "(0: none)")
        ->check(interval(0, 1 << 24))
        ->capture_default_str()
        ->type_name("MIB");
}

// One TF for the whole series, as amrvk render fixes a series' (--series-range): one scale (the
// first output decides an auto scale for all), and a fitted preset laid over every output's pooled
// distribution (union) or the first output's (first, as it is read); a given --tf-range or a
// session's TF as they are.
void fixSeriesTf(const std::vector<std::string>& series, const std::string& range, session::PictureDescription& d) {
    d.session.read.scale = session::seriesScale(series, d.session.read, d.session.field);
    if (d.tfRange || !d.tfSource || session::parseSeriesRange(range) == session::SeriesRange::First) return;
    std::string field = d.session.field;
    session::SeriesStatistics pooled = session::seriesStatistics(series, d.session.read, field);
    d.session.field = field;
    d.dataPercentiles = pooled.percentiles;
    if (!pooled.volumes.empty()) d.dataHistogram = pooled.volumes;
}

}  // namespace

int runView(const std::vector<std::string>& argv) {
    CLI::App app(kViewHelp, "amrvk view");
    setUpCommand(app);
    std::vector<std::string> inputArgs;  // one data set, or a series: several, or a glob pattern
    ViewSeriesArgs seriesArgs;
    ReadArgs read;
    PictureArgs pic;
    DeviceArgs dev;
    viewer::ViewerOptions vo;
    ViewAutomationArgs va;
    app.add_option("input", inputArgs,
                   "the data set (as amrvk render; optional with --session), or a time series: several data sets or "
                   "a quoted glob pattern ('out_*.cells'), in natural order, stepped with a time slider")
        ->type_name("INPUT...");
    addReadOptions(app, read, false);
    addPictureOptions(app, pic);
    app.get_option("--spp")->description("stop accumulating at N samples per pixel (default: run on)")->default_str("");
    addDeviceOptions(app, dev);
    addViewAutomationOptions(app, va);
    addViewSeriesOptions(app, seriesArgs);
    if (!parseCommandLine(app, argv)) return 0;
    // Under mpirun every rank runs this command: rank 0 the viewer, the others follow it
    // (viewRanks, cli/view_ranks.cpp); errors agreed and reported once.
    return runOnRanks("view", [&](mpi::World* world) -> int {
        AMRVK_CHECK(world || !given(app, "--distribute"),
                "--distribute: only under an MPI launcher (mpirun -n N amrvk view ...; docs/mpi.md)");
        AMRVK_CHECK(seriesArgs.distribute == "samples",
                    "--distribute data: the viewer runs sample-parallel only (every rank holds the whole data); "
                    "data-parallel pictures are rendered in batch: mpirun -n N amrvk render --distribute data");
        const std::vector<std::string> series = inputArgs.empty() ? inputArgs : session::expandInputs(inputArgs);
        const std::string input = series.empty() ? std::string() : series.front();
        AMRVK_CHECK(series.size() > 1 || (!given(app, "--series-range") && !given(app, "--series-fps") &&
                                          !given(app, "--series-ahead-mib")),
                    "--series-range, --series-fps and --series-ahead-mib are for a time series (several inputs or a "
                    "pattern)");

        AMRVK_CHECK(!va.headless || va.frames > 0 || !va.script.empty(),
                    "--headless needs --frames N or a --script that quits (it has no window to close)");
        if (!va.screenshot.empty()) {
            const std::string ext = std::filesystem::path(va.screenshot).extension().string();
            AMRVK_CHECK(ext == ".png" || ext == ".exr" || ext == ".pfm", "--screenshot ", va.screenshot,
                        ": unknown image type (use .png, .exr or .pfm)");
        }
        // Every output checked before any work: writable, distinct, none of them an input.
        const std::vector<NamedPath> outputs = {{"--screenshot", va.screenshot},
                                                {"--save-session", va.saveSession},
                                                {"--stats", va.stats},
                                                {"--state-file", va.state}};
        std::vector<NamedPath> inputs = pictureInputs(app, input, pic, {{"--script", va.script}});
        for (size_t k = 1; k < series.size(); ++k) inputs.push_back({"input", series[k]});
        // Saving the session back where it came from is the ordinary Save (it was read whole before the
        // window opens and is written atomically): --save-session may name the --session file, which
        // every other output is still checked against.
        std::error_code same;
        const bool saveBack = !va.saveSession.empty() && app.count("--session") &&
                              std::filesystem::equivalent(va.saveSession, pic.session, same);
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
        if (series.size() > 1) fixSeriesTf(series, seriesArgs.range, vo.start);
        vo.series = series.size() > 1 ? series : std::vector<std::string>{};
        vo.seriesAheadBytes = uint64_t(seriesArgs.aheadMib * double(1 << 20));
        vo.seriesFps = seriesArgs.fps;
        // A PNG screenshot with the legend needs its font: checked before anything is read.
        if (vo.start.session.legend.show && std::filesystem::path(va.screenshot).extension() == ".png")
            session::openLegendFont(vo.start.session.legend);
        AMRVK_CHECK(vo.start.fit != session::StructureFit::Probe,
                    "--traversal auto is for amrvk render (the viewer switches structures live)");
        if (!app.count("--spp") && app.count("--session") == 0) vo.start.session.spp = 0;  // run on
        // Checked before anything is read: a bad script line is one line naming it (the viewer checks
        // what needs its structures and shader directory again before frame 0).
        if (!va.script.empty()) viewer::loadScript(va.script);
        // Read before a window opens: a bad data set is one line, not a window that closes.
        std::shared_ptr<const scene::Volume> volume = session::loadVolume(vo.start.session);
        checkAgainst(inputFilesRead());  // and none is a file the data set was read from
        vo.headless = va.headless;
        vo.frames = uint64_t(va.frames);
        vo.screenshot = va.screenshot;
        vo.script = va.script;
        vo.statsJson = va.stats;
        vo.stateJson = va.state;
        vo.saveSession = va.saveSession;
        vo.shaderDir = dev.shaderDir;
        vo.context = dev.context;
        vo.frameBudgetSeconds = va.budgetMs * 1e-3;
        if (!va.window.empty()) parseSize("--window", va.window, vo.windowWidth, vo.windowHeight);
        if (world) return viewOnRanks(*world, vo, std::move(volume));
        return viewer::runViewer(vo, std::move(volume));
    });
}

}  // namespace amrvk::cli
