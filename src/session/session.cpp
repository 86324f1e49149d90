#include "session/session.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/file_io.h"
#include "core/json_text.h"
#include "scene/limits.h"

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace amrvk::session {

namespace {

constexpr int kVersion = 2;  // 2: "tfColors" (absent in version 1, whose colours were linear)

Json vec3(glm::dvec3 v) { return Json::array({v.x, v.y, v.z}); }

// Reads members with one-line errors naming the file and the key path.
class Reader {
public:
    Reader(const Json& j, std::string where) : mJ(j), mWhere(std::move(where)) {}

    bool has(const char* key) const { return mJ.is_object() && mJ.contains(key); }
    Reader child(const char* key) const {
        AMRVK_CHECK(has(key), mWhere, ": missing \"", key, "\"");
        return Reader(mJ.at(key), mWhere + "." + key);
    }
    double number(const char* key) const {
        const Json& v = member(key);
        AMRVK_CHECK(v.is_number(), mWhere, ".", key, ": expected a number, found ", v.type_name());
        const double d = v.get<double>();
        AMRVK_CHECK(std::isfinite(d), mWhere, ".", key, ": ", d, " is not finite");
        return d;
    }
    double number(const char* key, double fallback) const { return has(key) ? number(key) : fallback; }
    std::string text(const char* key) const {
        const Json& v = member(key);
        AMRVK_CHECK(v.is_string(), mWhere, ".", key, ": expected a string, found ", v.type_name());
        return v.get<std::string>();
    }
    std::string text(const char* key, const std::string& fallback) const { return has(key) ? text(key) : fallback; }
    bool flag(const char* key, bool fallback) const {
        if (!has(key)) return fallback;
        const Json& v = member(key);
        AMRVK_CHECK(v.is_boolean(), mWhere, ".", key, ": expected true or false, found ", v.type_name());
        return v.get<bool>();
    }
    glm::dvec3 vector(const char* key) const {
        const Json& v = member(key);
        AMRVK_CHECK(v.is_array() && v.size() == 3, mWhere, ".", key, ": expected an array of 3 numbers");
        glm::dvec3 out;
        for (int a = 0; a < 3; ++a) {
            AMRVK_CHECK(v[size_t(a)].is_number(), mWhere, ".", key, "[", a, "]: expected a number");
            out[a] = v[size_t(a)].get<double>();
            AMRVK_CHECK(std::isfinite(out[a]), mWhere, ".", key, "[", a, "]: ", out[a], " is not finite");
        }
        return out;
    }
    int64_t integer(const char* key, int64_t lo, int64_t hi) const {
        const double d = number(key);
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", d);
        AMRVK_CHECK(d == std::floor(d) && d >= double(lo) && d <= double(hi), mWhere, ".", key, ": ", text,
                    " is not an integer in [", lo, ", ", hi, "]");
        return int64_t(d);
    }
    // A name read with `parse` (an enum's spelling); its error names the file and the key.
    template <typename Parse>
    auto named(const char* key, const std::string& fallback, Parse parse) const {
        const std::string value = text(key, fallback);
        try {
            return parse(value);
        } catch (const Error& e) {
            throw Error(mWhere + "." + key + ": " + e.what());
        }
    }
    const Json& json() const { return mJ; }
    const std::string& where() const { return mWhere; }

private:
    const Json& member(const char* key) const {
        AMRVK_CHECK(has(key), mWhere, ": missing \"", key, "\"");
        return mJ.at(key);
    }
    const Json& mJ;
    std::string mWhere;
};

}  // namespace

std::string sessionJson(const Session& s) {
    const scene::RenderSettings& r = s.settings;
    Json j;
    j["amrvk"] = "session";
    j["version"] = kVersion;
    j["input"] = s.input;
    j["read"] = {{"format", s.read.format}, {"nan", s.read.nanPolicy == amr::NanPolicy::Drop ? "drop" : "reject"}};
    if (s.read.rawDims != glm::ivec3(0))
        j["read"]["dims"] = Json::array({s.read.rawDims.x, s.read.rawDims.y, s.read.rawDims.z});
    if (!s.read.rawType.empty()) j["read"]["type"] = s.read.rawType;
    if (s.read.rawThreshold != 0.0) j["read"]["threshold"] = s.read.rawThreshold;
    if (s.read.scale != amr::FieldScale::Linear) j["read"]["scale"] = amr::fieldScaleName(s.read.scale);
    if (s.read.logFloor != 0.0) j["read"]["logFloor"] = s.read.logFloor;
    j["field"] = s.field;
    j["camera"] = {{"eye", vec3(r.camera.eye)},
                   {"target", vec3(r.camera.target)},
                   {"up", vec3(r.camera.up)},
                   {"fovY", r.camera.fovYDegrees}};
    j["image"] = {{"width", r.width}, {"height", r.height}};
    j["render"] = {{"mode", scene::modeName(r.mode)}, {"spp", s.spp},          {"seed", r.seed},
                   {"densityScale", r.densityScale},   {"g", r.g},              {"ambient", vec3(r.ambient)},
                   {"dvrStep", r.dvrStep},             {"dvrShading", r.dvrShading}};
    if (r.background) j["render"]["background"] = vec3(*r.background);
    j["lights"] = Json::array();
    for (const scene::Light& L : r.lights)
        j["lights"].push_back(L.point ? Json{{"type", "point"}, {"position", vec3(L.posOrDir)}, {"intensity", vec3(L.radiance)}}
                                      : Json{{"type", "directional"}, {"direction", vec3(L.posOrDir)},
                                             {"radiance", vec3(L.radiance)}});
    if (!r.cut.empty()) {
        j["cut"] = Json::object();
        if (r.cut.crop) j["cut"]["crop"] = {{"lo", vec3(r.cut.crop->lo)}, {"hi", vec3(r.cut.crop->hi)}};
        if (!r.cut.clips.empty()) {
            j["cut"]["clip"] = Json::array();
            for (const scene::ClipPlane& c : r.cut.clips)
                j["cut"]["clip"].push_back({{"point", vec3(c.point)}, {"normal", vec3(c.normal)}});
        }
    }
    j["structure"] = {{"traversal", scene::traversalName(s.structure.traversal)},
                      {"sampler", scene::samplerName(s.structure.sampler)},
                      {"backend", scene::backendName(s.structure.backend)},
                      {"grid", s.structure.grid},
                      {"kdLeaves", s.structure.kdLeaves},
                      {"denseMaxMiB", s.structure.denseMaxBytes >> 20}};
    j["transferFunction"] = Json::parse(scene::paraViewPresetJson(s.tf)).at(0);
    j["tfColors"] = scene::tfColorsName(s.tfColors);
    if (!(s.legend == Legend{}))
        j["legend"] = {{"show", s.legend.show},
                       {"place", legendPlaceName(s.legend.place)},
                       {"title", s.legend.title},
                       {"units", s.legend.units},
                       {"font", s.legend.font}};
    return j.dump(2) + "\n";
}

namespace {

// The session file's JSON document: depth checked before parsing, a parse error on one line.
Json parseDocument(const std::string& text, const std::string& file) {
    checkJsonDepth(text, file);
    try {
        return Json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        std::string msg = e.what();
        for (char& c : msg)
            if (c == '\n') c = ' ';
        AMRVK_CHECK(false, file, ": not a session (malformed JSON: ", msg, ")");
    }
    return {};
}

// "read": how the input is read (format, NaN policy, raw layout, scale).
void readReadOptions(const Reader& r, amr::ReadOptions& read) {
    read.format = r.text("format", "auto");
    read.nanPolicy = r.named("nan", "reject", [](const std::string& v) { return amr::parseNanPolicy(v); });
    if (r.has("dims")) {
        const glm::dvec3 d = r.vector("dims");
        for (int a = 0; a < 3; ++a) {
            AMRVK_CHECK(d[a] >= 1 && d[a] <= (1 << 20) && d[a] == std::floor(d[a]), r.where(), ".dims[", a,
                        "]: ", d[a], " is not an integer in [1, 2^20]");
            read.rawDims[a] = int(d[a]);
        }
    }
    read.rawType = r.text("type", "");
    read.rawThreshold = r.number("threshold", 0.0);
    AMRVK_CHECK(read.rawThreshold >= 0, r.where(), ".threshold: must be >= 0");
    read.scale = r.named("scale", "linear", [](const std::string& v) { return amr::parseFieldScale(v); });
    read.logFloor = r.number("logFloor", 0.0);
    AMRVK_CHECK(read.logFloor >= 0 && std::isfinite(read.logFloor), r.where(), ".logFloor: must be >= 0");
}

// "camera" and "image" (both required).
void readView(const Reader& top, scene::RenderSettings& rs) {
    const Reader cam = top.child("camera");
    rs.camera.eye = cam.vector("eye");
    rs.camera.target = cam.vector("target");
    rs.camera.up = cam.vector("up");
    rs.camera.fovYDegrees = cam.number("fovY", 40.0);
    AMRVK_CHECK(scene::validFov(rs.camera.fovYDegrees), cam.where(), ".fovY: ", rs.camera.fovYDegrees,
                " is outside (0, ", scene::kMaxFovDegrees, ")");
    const Reader image = top.child("image");
    rs.width = int(image.integer("width", 1, scene::kMaxImageSide));
    rs.height = int(image.integer("height", 1, scene::kMaxImageSide));
}

// "render": mode, samples, seed, medium and dvr options (every key optional).
void readRender(const Reader& r, Session& s) {
    scene::RenderSettings& rs = s.settings;
    rs.mode = r.named("mode", "ms", scene::parseMode);
    s.spp = uint32_t(r.has("spp") ? r.integer("spp", 0, scene::kMaxSpp) : 64);
    rs.seed = uint32_t(r.has("seed") ? r.integer("seed", 0, UINT32_MAX) : 1);
    rs.densityScale = r.number("densityScale", 1.0);
    AMRVK_CHECK(rs.densityScale >= 0, r.where(), ".densityScale: ", rs.densityScale, " must be >= 0");
    rs.g = r.number("g", 0.0);
    AMRVK_CHECK(rs.g >= -1 && rs.g <= 1, r.where(), ".g: ", rs.g, " is outside [-1, 1]");
    if (r.has("ambient")) rs.ambient = r.vector("ambient");
    if (r.has("background")) rs.background = r.vector("background");
    for (const char* key : {"ambient", "background"})
        if (r.has(key)) AMRVK_CHECK(glm::all(glm::greaterThanEqual(r.vector(key), glm::dvec3(0.0))), r.where(), ".",
                                    key, ": radiance must be >= 0");
    rs.dvrStep = r.number("dvrStep", 0.5);
    AMRVK_CHECK(rs.dvrStep > 0 && rs.dvrStep <= 64, r.where(), ".dvrStep: ", rs.dvrStep, " is outside (0, 64]");
    rs.dvrShading = r.flag("dvrShading", false);
}

// "lights": an array of directional and point lights.
std::vector<scene::Light> readLights(const Json& lights, const std::string& where) {
    AMRVK_CHECK(lights.is_array(), where, ": expected an array");
    std::vector<scene::Light> out;
    for (size_t i = 0; i < lights.size(); ++i) {
        const Reader L(lights[i], where + "[" + std::to_string(i) + "]");
        const std::string type = L.text("type");
        scene::Light light;
        if (type == "directional") {
            light.posOrDir = L.vector("direction");
            light.radiance = L.vector("radiance");
            AMRVK_CHECK(glm::length(light.posOrDir) > 0, L.where(), ".direction: must not be zero");
        } else {
            AMRVK_CHECK(type == "point", L.where(), ".type: '", type, "' (expected directional or point)");
            light.point = true;
            light.posOrDir = L.vector("position");
            light.radiance = L.vector("intensity");
        }
        AMRVK_CHECK(glm::all(glm::greaterThanEqual(light.radiance, glm::dvec3(0.0))), L.where(),
                    ": radiance must be >= 0");
        out.push_back(light);
    }
    return out;
}

// "cut": the crop box and clip planes, validated as the CLI validates them.
scene::CutAway readCut(const Reader& cut) {
    scene::CutAway c;
    if (cut.has("crop")) {
        const Reader crop = cut.child("crop");
        c.crop = scene::CropBox{crop.vector("lo"), crop.vector("hi")};
    }
    if (cut.has("clip")) {
        const Json& clips = cut.json().at("clip");
        AMRVK_CHECK(clips.is_array(), cut.where(), ".clip: expected an array");
        AMRVK_CHECK(clips.size() <= shared::kMaxClipPlanes, cut.where(), ".clip: at most ", shared::kMaxClipPlanes,
                    " planes (got ", clips.size(), ")");
        for (size_t i = 0; i < clips.size(); ++i) {
            const Reader p(clips[i], cut.where() + ".clip[" + std::to_string(i) + "]");
            c.clips.push_back({p.vector("point"), p.vector("normal")});
        }
    }
    try {
        scene::validateCutAway(c);
    } catch (const Error& e) {
        throw Error(cut.where() + ": " + e.what());
    }
    return c;
}

// "structure": the traversal, sampler and back-end with their parameters, validated.
void readStructure(const Reader& st, scene::StructureConfig& structure) {
    structure.traversal = st.named("traversal", "grid-dda", scene::parseTraversal);
    structure.sampler = st.named("sampler", "ext-brick", scene::parseSampler);
    structure.backend = st.named("backend", "auto", scene::parseBackend);
    structure.grid = st.text("grid", "auto");
    if (st.has("kdLeaves")) structure.kdLeaves = uint32_t(st.integer("kdLeaves", 1, scene::kMaxKdLeaves));
    if (st.has("denseMaxMiB")) structure.denseMaxBytes = uint64_t(st.integer("denseMaxMiB", 1, scene::kMaxDenseMiB)) << 20;
    try {
        structure.validate();
    } catch (const Error& e) {
        throw Error(st.where() + ": " + e.what());
    }
}

// "legend": whether and how the colour legend is drawn.
Legend readLegend(const Reader& L) {
    AMRVK_CHECK(L.json().is_object(), L.where(), ": expected an object");
    Legend legend;
    legend.show = L.flag("show", false);
    legend.place = L.named("place", "side", parseLegendPlace);
    legend.title = L.text("title", "");
    legend.units = L.text("units", "");
    legend.font = L.text("font", "");
    return legend;
}

}  // namespace

Session parseSession(const std::string& text, const fs::path& path) {
    const std::string file = path.string();
    const Json doc = parseDocument(text, file);
    const Reader top(doc, file);
    AMRVK_CHECK(doc.is_object() && top.text("amrvk", "") == "session", file,
                ": not an amrvk session (expected \"amrvk\": \"session\")");
    const int64_t version = top.integer("version", 1, 1 << 20);
    AMRVK_CHECK(version == 1 || version == kVersion, file, ": session version ", version,
                " (this amrvk reads versions 1 and ", kVersion, ")");

    Session s;
    s.input = top.text("input");
    AMRVK_CHECK(!s.input.empty(), file, ".input: empty");
    if (fs::path(s.input).is_relative()) s.input = (path.parent_path() / s.input).lexically_normal().string();
    if (top.has("read")) readReadOptions(top.child("read"), s.read);
    s.field = top.text("field", "");
    readView(top, s.settings);
    // Every render.* key is optional, so the object is too.
    const Json noRender = Json::object();
    readRender(top.has("render") ? top.child("render") : Reader(noRender, file + ".render"), s);
    if (top.has("lights")) s.settings.lights = readLights(doc.at("lights"), file + ".lights");
    if (top.has("cut")) s.settings.cut = readCut(top.child("cut"));
    if (top.has("structure")) readStructure(top.child("structure"), s.structure);
    // One ParaView preset object, read by the same code as preset files.
    s.tf = scene::parseParaViewPreset(top.child("transferFunction").json().dump(), file + ".transferFunction");
    // Version 1 knew only linear colours; a later file without the key means the default.
    s.tfColors = top.named("tfColors", version == 1 ? "linear" : "srgb",
                           [](std::string_view t) { return scene::parseTfColors(t); });
    if (top.has("legend")) s.legend = readLegend(top.child("legend"));
    return s;
}

void saveSession(const fs::path& path, const Session& s) { writeFileAtomic(path, sessionJson(s)); }

Session loadSession(const fs::path& path) {
    std::error_code ec;
    AMRVK_CHECK(fs::is_regular_file(path, ec), path.string(), ": no such session file");
    return parseSession(readTextFile(path), path);
}

}  // namespace amrvk::session
