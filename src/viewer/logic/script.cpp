#include "viewer/logic/script.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include "accel/range_grid.h"
#include "amr/model.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/strings.h"
#include "scene/cut_away.h"
#include "scene/render_settings.h"
#include "scene/tf_colors.h"
#include "scene/tf_presets.h"
#include "scene/transfer_function.h"
#include "session/camera_path.h"

namespace amrvk::viewer {

namespace {

// Argument count and which arguments are numbers, per action.
struct Signature {
    size_t count;
    std::vector<size_t> numbers;
};

const std::map<std::string, Signature>& signatures() {
    static const std::map<std::string, Signature> table = {{"orbit", {2, {0, 1}}},
                                                           {"pan", {2, {0, 1}}},
                                                           {"zoom", {1, {0}}},
                                                           {"tf-preset", {1, {}}},
                                                           {"tf-range", {2, {0, 1}}},
                                                           {"density", {1, {0}}},
                                                           {"mode", {1, {}}},
                                                           {"traversal", {1, {}}},
                                                           {"sampler", {1, {}}},
                                                           {"backend", {1, {}}},
                                                           {"grid", {1, {}}},
                                                           {"edit-shader", {3, {}}},
                                                           {"reload", {0, {}}},
                                                           {"screenshot", {1, {}}},
                                                           {"capture-window", {1, {}}},
                                                           {"save-session", {1, {}}},
                                                           {"quit", {0, {}}},
                                                           {"scale", {1, {}}},
                                                           {"log-floor", {1, {0}}},
                                                           {"load-session", {1, {}}},
                                                           {"crop", {6, {0, 1, 2, 3, 4, 5}}},
                                                           {"clip", {6, {0, 1, 2, 3, 4, 5}}},
                                                           {"cut-off", {0, {}}},
                                                           {"legend", {1, {}}},
                                                           {"tf-colors", {1, {}}},
                                                           {"step", {1, {0}}},
                                                           {"play", {0, {}}},
                                                           {"pause", {0, {}}},
                                                           {"series-fps", {1, {0}}},
                                                           {"keyframe-add", {1, {0}}},
                                                           {"keyframe-delete", {1, {0}}},
                                                           {"keyframe-move", {2, {0, 1}}},
                                                           {"path-frame", {1, {0}}},
                                                           {"path-play", {0, {}}},
                                                           {"path-stop", {0, {}}},
                                                           {"path-fps", {1, {0}}}};
    return table;
}

bool parseNumber(const std::string& s, double& out) {
    const char* end = s.data() + s.size();
    auto [ptr, ec] = std::from_chars(s.data(), end, out);
    return ec == std::errc() && ptr == end && std::isfinite(out);
}

// Splits a line into words; "..." groups words, \" and \\ escape inside quotes.
std::vector<std::string> words(const std::string& line, const std::string& where) {
    std::vector<std::string> out;
    size_t i = 0;
    while (i < line.size()) {
        if (std::isspace(static_cast<unsigned char>(line[i]))) {
            ++i;
            continue;
        }
        if (line[i] == '#') break;
        std::string w;
        if (line[i] == '"') {
            ++i;
            bool closed = false;
            while (i < line.size()) {
                if (line[i] == '\\' && i + 1 < line.size() && (line[i + 1] == '"' || line[i + 1] == '\\')) {
                    w += line[i + 1];
                    i += 2;
                } else if (line[i] == '"') {
                    closed = true;
                    ++i;
                    break;
                } else {
                    w += line[i++];
                }
            }
            AMRVK_CHECK(closed, where, ": unterminated quote");
        } else {
            while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) w += line[i++];
        }
        out.push_back(w);
    }
    return out;
}

// The values of an action that can be checked without the viewer (names, ranges, image types).
void checkValues(const ScriptAction& a) {
    const std::string& n = a.name;
    auto imageType = [&](std::initializer_list<const char*> types) {
        const std::string ext = std::filesystem::path(a.args[0]).extension().string();
        for (const char* t : types)
            if (ext == t) return;
        AMRVK_CHECK(false, "'", a.args[0], "': unknown image type (use ", join(std::vector<std::string>(types.begin(), types.end()), ", "), ")");
    };
    if (n == "mode") scene::parseMode(a.args[0]);
    else if (n == "traversal") scene::parseTraversal(a.args[0]);
    else if (n == "sampler") scene::parseSampler(a.args[0]);
    else if (n == "backend") scene::parseBackend(a.args[0]);
    else if (n == "grid") accel::parseGridDims(a.args[0], amr::Box3l{glm::i64vec3(0), glm::i64vec3(1)});
    else if (n == "tf-preset") scene::builtInChannels(a.args[0]);
    else if (n == "tf-range") AMRVK_CHECK(a.number(0) < a.number(1), "LO ", a.args[0], " must be below HI ", a.args[1]);
    else if (n == "density") AMRVK_CHECK(a.number(0) >= 0, "density ", a.args[0], " must be >= 0");
    else if (n == "scale") amr::parseFieldScale(a.args[0]);
    else if (n == "log-floor") AMRVK_CHECK(a.number(0) >= 0, "log floor ", a.args[0], " must be >= 0 (0: the field's smallest positive value)");
    else if (n == "screenshot") imageType({".png", ".exr", ".pfm"});
    else if (n == "capture-window") imageType({".png"});
    else if (n == "save-session" || n == "load-session") AMRVK_CHECK(!a.args[0].empty(), "empty file name");
    else if (n == "crop") {
        scene::CutAway c;
        c.crop = scene::CropBox{{a.number(0), a.number(1), a.number(2)}, {a.number(3), a.number(4), a.number(5)}};
        scene::validateCutAway(c);
    } else if (n == "clip") {
        scene::CutAway c;
        c.clips.push_back({{a.number(0), a.number(1), a.number(2)}, {a.number(3), a.number(4), a.number(5)}});
        scene::validateCutAway(c);
    }
    else if (n == "legend") AMRVK_CHECK(a.args[0] == "on" || a.args[0] == "off", "'", a.args[0], "': expected on or off");
    else if (n == "tf-colors") scene::parseTfColors(a.args[0], "tf-colors");
    else if (n == "step")
        AMRVK_CHECK(a.number(0) >= 0 && a.number(0) == std::floor(a.number(0)), "step ", a.args[0],
                    " must be a whole number >= 0");
    else if (n == "series-fps")
        AMRVK_CHECK(a.number(0) > 0 && a.number(0) <= 120, "series-fps ", a.args[0], " is outside (0, 120]");
    else if (n == "keyframe-add" || n == "keyframe-delete" || n == "keyframe-move" || n == "path-frame")
        for (size_t i = 0; i < a.args.size(); ++i) pathFrameArgument(a, i);
    else if (n == "path-fps")
        AMRVK_CHECK(a.number(0) > 0 && a.number(0) <= session::kMaxPathFps, "fps ", a.args[0], " is outside (0, ",
                    session::kMaxPathFps, "]");
    else if (n == "edit-shader") {
        AMRVK_CHECK(!a.args[0].empty() && std::filesystem::path(a.args[0]).is_relative(), "'", a.args[0],
                    "' must be a path relative to --shader-dir");
        AMRVK_CHECK(!a.args[1].empty(), "the text to find is empty");
    }
}

}  // namespace

uint32_t pathFrameArgument(const ScriptAction& a, size_t i) {
    const double f = a.number(i);
    AMRVK_CHECK(f >= 0 && f < session::kMaxPathFrames && f == std::floor(f), "frame ", a.args[i],
                " is not a whole number in [0, ", session::kMaxPathFrames - 1, "]");
    return uint32_t(f);
}

double ScriptAction::number(size_t i) const {
    double v = 0;
    AMRVK_CHECK(i < args.size() && parseNumber(args[i], v), where, ": argument ", i + 1, " of ", name,
                " is not a number");
    return v;
}

std::vector<ScriptAction> parseScript(const std::string& text, const std::string& fileName) {
    std::vector<ScriptAction> out;
    std::istringstream in(text);
    std::string line;
    for (size_t lineNo = 1; std::getline(in, line); ++lineNo) {
        const std::string where = fileName + ":" + std::to_string(lineNo);
        std::vector<std::string> w = words(line, where);
        if (w.empty()) continue;
        AMRVK_CHECK(w.size() >= 2, where, ": expected FRAME ACTION [ARGS...]");
        double frame = 0;
        AMRVK_CHECK(parseNumber(w[0], frame) && frame >= 0 && frame == std::floor(frame) && frame < 1e15, where,
                    ": frame '", w[0], "' is not a whole number >= 0");
        ScriptAction a;
        a.frame = uint64_t(frame);
        a.name = w[1];
        a.args.assign(w.begin() + 2, w.end());
        a.where = where;
        auto sig = signatures().find(a.name);
        if (sig == signatures().end()) {
            std::string known;
            for (const auto& entry : signatures()) known += (known.empty() ? "" : ", ") + entry.first;
            AMRVK_CHECK(false, where, ": unknown action '", a.name, "' (actions: ", known, ")");
        }
        AMRVK_CHECK(a.args.size() == sig->second.count, where, ": ", a.name, " takes ", sig->second.count,
                    " argument(s), not ", a.args.size());
        for (size_t k : sig->second.numbers) a.number(k);
        try {
            checkValues(a);
        } catch (const Error& e) {
            throw Error(where + ": " + a.name + ": " + e.what());
        }
        AMRVK_CHECK(out.empty() || a.frame >= out.back().frame, where, ": frame ", a.frame, " comes before frame ",
                    out.back().frame, " of the line above");
        out.push_back(std::move(a));
    }
    return out;
}

void checkScript(const std::vector<ScriptAction>& actions, const ScriptContext& context) {
    scene::StructureConfig structure = context.structure;
    for (const ScriptAction& a : actions) {
        try {
            if (a.name == "traversal") structure.traversal = scene::parseTraversal(a.args[0]);
            if (a.name == "sampler") structure.sampler = scene::parseSampler(a.args[0]);
            if (a.name == "backend") structure.backend = scene::parseBackend(a.args[0]);
            if (a.name == "grid") structure.grid = a.args[0];
            if (a.name == "traversal" || a.name == "sampler") structure.validate();
            if (a.name == "edit-shader") confinedShaderPath(context.shaderDir, a.args[0]);
        } catch (const Error& e) {
            throw Error(a.where + ": " + a.name + ": " + e.what());
        }
    }
}

std::filesystem::path confinedShaderPath(const std::filesystem::path& dir, const std::string& file) {
    namespace fs = std::filesystem;
    AMRVK_CHECK(!dir.empty(), "edit-shader needs --shader-dir");
    AMRVK_CHECK(!file.empty() && fs::path(file).is_relative(), "'", file,
                "' must be a path relative to --shader-dir");
    // The source root as gpu::shaderSourceRoot finds it (session stays Vulkan-free).
    const fs::path root = fs::is_directory(dir / "passes") ? dir : dir / "..";
    std::error_code ec;
    const fs::path canonicalRoot = fs::canonical(root, ec);
    AMRVK_CHECK(!ec, dir.string(), ": cannot resolve the shader directory (", ec.message(), ")");
    const fs::path target = fs::canonical(dir / file, ec);
    AMRVK_CHECK(!ec, (dir / file).string(), ": no such shader file");
    const auto [rootEnd, _] = std::mismatch(canonicalRoot.begin(), canonicalRoot.end(), target.begin(), target.end());
    AMRVK_CHECK(rootEnd == canonicalRoot.end(), "'", file, "' leads outside the shader sources ",
                canonicalRoot.string(), " (to ", target.string(), ")");
    AMRVK_CHECK(fs::is_regular_file(target, ec), target.string(), ": not a regular file");
    return target;
}

std::vector<ScriptAction> loadScript(const std::filesystem::path& path) {
    std::error_code ec;
    AMRVK_CHECK(std::filesystem::is_regular_file(path, ec), path.string(), ": no such script file");
    return parseScript(readTextFile(path), path.string());
}

}  // namespace amrvk::viewer
