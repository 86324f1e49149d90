// The viewer's frame-numbered script actions (viewer/logic/script.h), each at its frame; errors name the line.

#include <cmath>
#include <cstdio>

#include "amr/readers.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"
#include "gpu/shader_compiler.h"
#include "scene/tf_presets.h"
#include "viewer/logic/script.h"
#include "viewer/viewer_app_impl.h"
#include "viewer/window.h"

namespace amrvk::viewer {

void ViewerApp::runScript() {
    while (!mQuit && mScriptAt < mScript.size() && mScript[mScriptAt].frame <= mFrame) {
        const ScriptAction& a = mScript[mScriptAt++];
        try {
            runAction(a);
        } catch (const gpu::ShaderCompileError&) {
            throw;  // names its file and line
        } catch (const Error& e) {
            throw Error(a.where + ": " + a.name + ": " + e.what());
        }
        std::fprintf(stderr, "amrvk view: frame %llu: %s\n", (unsigned long long)mFrame,
                     oneLineMessage(a.name).c_str());
    }
}

void ViewerApp::runAction(const ScriptAction& a) {
    const std::string& n = a.name;
    scene::Camera& camera = mState.settings.camera;
    const double height = double(mState.settings.height);
    scene::StructureConfig structure = mState.structure;
    if (n == "orbit" || n == "pan" || n == "zoom") {
        scene::Camera moved = camera;
        if (n == "orbit")
            mOrbit.orbit(moved, a.number(0), a.number(1), height);
        else if (n == "pan")
            mOrbit.pan(moved, a.number(0), a.number(1), height);
        else
            mOrbit.zoom(moved, a.number(0));
        // A move the camera cannot take fails here, on its script line, not at the next frame as
        // a --camera error (pan 1e300 1e300: the eye and target round to one point, or overflow).
        const glm::dvec3 forward = moved.target - moved.eye;
        const auto finite = [](glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
        AMRVK_CHECK(finite(moved.eye) && finite(moved.target), "the camera leaves the range of finite numbers");
        AMRVK_CHECK(glm::length(forward) > 0, "eye and target coincide");
        camera = moved;
    } else if (n == "tf-preset" || n == "tf-range") {
        TfEditor editor(mState.tf);
        if (n == "tf-preset")
            editor.setPreset(scene::builtInChannels(a.args[0]));
        else
            editor.setRange(float(a.number(0)), float(a.number(1)));
        mTfHistory.push(mState.tf);
        setTransferFunction();
    } else if (n == "density") {
        scene::RenderSettings s = mState.settings;
        s.densityScale = a.number(0);
        scene::validateSettings(s);
        mState.settings = s;
    } else if (n == "crop" || n == "clip" || n == "cut-off") {
        scene::RenderSettings s = mState.settings;
        if (n == "cut-off") {
            s.cut = {};
        } else {
            const glm::dvec3 u(a.number(0), a.number(1), a.number(2)), v(a.number(3), a.number(4), a.number(5));
            if (n == "crop")
                s.cut.crop = scene::CropBox{u, v};
            else
                s.cut.clips.push_back({u, v});
        }
        scene::validateSettings(s);
        mState.settings = s;
    } else if (n == "mode") {
        mState.settings.mode = scene::parseMode(a.args[0]);
    } else if (n == "scale" || n == "log-floor") {
        amr::ReadOptions read = mState.read;
        if (n == "scale")
            read.scale = amr::parseFieldScale(a.args[0]);
        else
            read.logFloor = a.number(0);
        setReadScale(read);
    } else if (n == "traversal" || n == "sampler" || n == "backend" || n == "grid") {
        if (n == "traversal") structure.traversal = scene::parseTraversal(a.args[0]);
        if (n == "sampler") structure.sampler = scene::parseSampler(a.args[0]);
        if (n == "backend") structure.backend = scene::parseBackend(a.args[0]);
        if (n == "grid") structure.grid = a.args[0];
        if (!(structure == mState.structure)) setStructure(structure);
    } else if (n == "edit-shader") {
        const fs::path file = confinedShaderPath(mOpt.shaderDir, a.args[0]);
        std::string text = readTextFile(file);
        const size_t at = text.find(a.args[1]);
        AMRVK_CHECK(at != std::string::npos, "'", a.args[1], "' not found in ", file.string());
        text.replace(at, a.args[1].size(), a.args[2]);
        writeFileAtomic(file, text);
    } else if (n == "reload") {
        reloadShaders();
    } else if (n == "screenshot") {
        screenshot(a.args[0]);
    } else if (n == "save-session") {
        saveSessionFile(a.args[0]);
    } else if (n == "load-session") {
        loadSessionFile(a.args[0]);
    } else if (n == "legend") {
        mState.legend.show = a.args[0] == "on";
    } else if (n == "tf-colors") {
        mState.tfColors = scene::parseTfColors(a.args[0], "tf-colors");
        setTransferFunction();
    } else if (n == "step" || n == "play" || n == "pause" || n == "series-fps") {
        AMRVK_CHECK(mPlayer, "'", n, "' needs a time series (several inputs or a pattern)");
        if (n == "step") showStep(size_t(a.number(0)));
        if (n == "play" || n == "pause") mPlayer->setPlaying(n == "play");
        if (n == "series-fps") mPlayer->setFps(a.number(0));
    } else if (n == "capture-window") {
        if (mWindow) mCapturePath = a.args[0];
    } else if (n == "quit") {
        mQuit = true;
    } else if (n.starts_with("keyframe-") || n.starts_with("path-")) {
        runPathAction(a);
    } else {
        AMRVK_CHECK(false, "the viewer has no action '", n, "'");
    }
}

}  // namespace amrvk::viewer
