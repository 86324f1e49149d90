#include "session/session.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/file_io.h"
#include "core/json_text.h"
#include "core/strings.h"
#include "scene/limits.h"
#include "scene/tf_files.h"
#include "session/setting_table.h"

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace amrvk::session {

namespace {

// 2: "tfColors" (absent in version 1, whose colours were linear); 3: read.scale defaults to auto and
// render.background to black (absent in versions 1-2: linear and the ambient).
constexpr int kVersion = 3;

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
        for (int digits = 15; digits <= 17; ++digits) {  // the shortest text that reads back as d
            std::snprintf(text, sizeof text, "%.*g", digits, d);
            if (std::strtod(text, nullptr) == d) break;
        }
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
    // Refuses a member not in `keys`: a typo, or a setting of a newer amrvk, is never silently
    // dropped (the picture would differ from the one the file describes).
    void onlyKeys(std::initializer_list<const char*> keys) const { onlyKeys(std::vector<const char*>(keys)); }
    void onlyKeys(const std::vector<const char*>& keys) const {
        if (!mJ.is_object()) return;
        for (const auto& item : mJ.items()) {
            bool known = false;
            for (const char* k : keys) known = known || item.key() == k;
            std::string list;
            for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
            AMRVK_CHECK(known, mWhere, ".", item.key(), ": unknown key (this amrvk reads session version ", kVersion,
                        "; keys here: ", list, ")");
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

// One key of a session section, stated once: the same entry writes it and reads it back, with
// the fallback a file without it gets and the values it may take.
struct Key {
    const char* name;
    std::function<void(const Session&, Json&)> write;   // sets j[name], or leaves it out
    std::function<void(const Reader&, Session&)> read;  // from the section's reader
};

// A section: a JSON object of keys, then a check over the whole section.
struct Section {
    const char* name;
    bool required;
    std::vector<Key> keys;
    std::function<bool(const Session&)> written = [](const Session&) { return true; };
    std::function<void(Session&)> check = [](Session&) {};
};

// Where a key lives in a Session, as a generic lambda so one accessor serves writing (const) and
// reading: AT(settings.g) is [](auto& s) -> auto& { return s.settings.g; }.
#define AT(member) [](auto& s) -> auto& { return s.member; }

// Numbers: the interval from lo to hi, closed unless `openLo` / `openHi`.
struct Domain {
    double lo, hi;
    bool openLo = false, openHi = false;
    bool holds(double v) const { return (openLo ? v > lo : v >= lo) && (openHi ? v < hi : v <= hi); }
    std::string describe(double v) const {
        if (std::isinf(hi)) return strCat(formatDouble(v), " must be ", openLo ? "> " : ">= ", lo);
        return strCat(formatDouble(v), " is outside ", openLo ? "(" : "[", lo, ", ", hi, openHi ? ")" : "]");
    }
};
constexpr double kInf = std::numeric_limits<double>::infinity();

// Left out of the file when at the fallback (what a file without the key means anyway).
enum class Write { Always, UnlessFallback };

// A key left out of a file means what a Session starts with (the front ends' defaults), stated
// there and nowhere else.
const Session& defaults() {
    static const Session kDefaults;
    return kDefaults;
}

template <typename At>
Key numberKey(const char* name, At at, Domain domain, Write w = Write::Always) {
    const double fallback = at(defaults());
    return {name,
            [=](const Session& s, Json& j) {
                if (w == Write::Always || at(s) != fallback) j[name] = at(s);
            },
            [=](const Reader& r, Session& s) {
                const double v = r.number(name, fallback);
                AMRVK_CHECK(domain.holds(v), r.where(), ".", name, ": ", domain.describe(v));
                at(s) = v;
            }};
}

// An integer in [lo, hi]; `required`: a file must state it.
template <typename At>
Key integerKey(const char* name, At at, int64_t lo, int64_t hi, bool required = false) {
    const int64_t fallback = int64_t(at(defaults()));
    return {name, [=](const Session& s, Json& j) { j[name] = at(s); },
            [=](const Reader& r, Session& s) {
                using T = std::remove_reference_t<decltype(at(s))>;
                at(s) = T(required || r.has(name) ? r.integer(name, lo, hi) : fallback);
            }};
}

template <typename At>
Key textKey(const char* name, At at, Write w = Write::Always) {
    const std::string fallback = at(defaults());
    return {name,
            [=](const Session& s, Json& j) {
                if (w == Write::Always || at(s) != fallback) j[name] = at(s);
            },
            [=](const Reader& r, Session& s) { at(s) = r.text(name, fallback); }};
}

// A name of an enum: `parse` reads it (its error names the key), `nameOf` writes it; absent:
// `fallback`, by default the Session's own.
template <typename At, typename Parse, typename NameOf>
Key enumKey(const char* name, At at, Parse parse, NameOf nameOf, Write w = Write::Always,
            const char* fallback = nullptr) {
    if (!fallback) fallback = nameOf(at(defaults()));
    return {name,
            [=](const Session& s, Json& j) {
                if (w == Write::Always || nameOf(at(s)) != std::string_view(fallback)) j[name] = nameOf(at(s));
            },
            [=](const Reader& r, Session& s) { at(s) = r.named(name, fallback, parse); }};
}

// The key of a setting of settingTable() (session/setting_table.h): written as its kind, read with
// the table's check (the words every front end uses after its own name), absent: the Session's own.
Key settingKey(std::string_view option) {
    const Setting& st = settingForOption(option);
    const char* name = st.key.data();  // the table's keys are string literals
    return {name,
            [&st, name](const Session& s, Json& j) {
                switch (st.kind) {
                    case SettingKind::Choice:
                    case SettingKind::Text:
                        j[name] = st.name(s);
                        return;
                    case SettingKind::Compound:
                        AMRVK_CHECK(false, "internal: ", st.option, " has keys of its own");
                        return;
                    case SettingKind::Flag:
                        j[name] = st.number(s) != 0;
                        return;
                    case SettingKind::Integer:
                        j[name] = int64_t(st.number(s));
                        return;
                    case SettingKind::Number:
                        j[name] = st.number(s);
                        return;
                }
            },
            [&st, name](const Reader& r, Session& s) {
                if (!r.has(name)) {
                    copySetting(st, defaults(), s);
                    return;
                }
                if (st.kind == SettingKind::Choice || st.kind == SettingKind::Text) {
                    setSettingName(st, s, r.text(name), strCat(r.where(), ".", name));
                } else if (st.kind == SettingKind::Flag) {
                    st.setNumber(s, r.flag(name, false) ? 1 : 0);
                } else {
                    const double v = r.number(name);
                    if (!(v == 0 && !st.zero.empty()))
                        checkSetting(st, v, strCat(r.where(), ".", name));  // 0: no limit
                    st.setNumber(s, v);
                }
            }};
}

// Three finite numbers; `nonNegative`: a radiance.
glm::dvec3 readVector(const Reader& r, const char* name, bool nonNegative) {
    const glm::dvec3 v = r.vector(name);
    AMRVK_CHECK(!nonNegative || glm::all(glm::greaterThanEqual(v, glm::dvec3(0.0))), r.where(), ".", name,
                ": radiance must be >= 0");
    return v;
}

// `required`: a file must state it, else absent keeps the default.
template <typename At>
Key vectorKey(const char* name, At at, bool required, bool nonNegative = false) {
    return {name, [=](const Session& s, Json& j) { j[name] = vec3(at(s)); },
            [=](const Reader& r, Session& s) {
                if (required || r.has(name)) at(s) = readVector(r, name, nonNegative);
            }};
}

// The keys of every object section, in file order.
const std::vector<Section>& sections() {
    static const std::vector<Section> kSections = {
        {"read",
         false,
         {textKey("format", AT(read.format)),
          enumKey("nan", AT(read.nanPolicy), amr::parseNanPolicy, amr::nanPolicyName),
          {"dims",
           [](const Session& s, Json& j) {
               if (s.read.rawDims != glm::ivec3(0))
                   j["dims"] = Json::array({s.read.rawDims.x, s.read.rawDims.y, s.read.rawDims.z});
           },
           [](const Reader& r, Session& s) {
               if (!r.has("dims")) return;
               const glm::dvec3 d = r.vector("dims");
               for (int a = 0; a < 3; ++a) {
                   AMRVK_CHECK(d[a] >= 1 && d[a] <= amr::kMaxRawDim && d[a] == std::floor(d[a]), r.where(),
                               ".dims[", a, "]: ", formatDouble(d[a]), " is not an integer in [1, ", amr::kMaxRawDim, "]");
                   s.read.rawDims[a] = int(d[a]);
               }
           }},
          textKey("type", AT(read.rawType), Write::UnlessFallback),
          numberKey("threshold", AT(read.rawThreshold), {0, kInf}, Write::UnlessFallback),
          enumKey("scale", AT(read.scale), amr::parseFieldScale, amr::fieldScaleName, Write::UnlessFallback),
          numberKey("logFloor", AT(read.logFloor), {0, kInf}, Write::UnlessFallback)}},
        {"camera",
         true,
         {vectorKey("eye", AT(settings.camera.eye), true), vectorKey("target", AT(settings.camera.target), true),
          vectorKey("up", AT(settings.camera.up), true),
          // scene::validFov's open interval
          settingKey("--fov")}},
        {"image",
         true,
         {integerKey("width", AT(settings.width), 1, scene::kMaxImageSide, true),
          integerKey("height", AT(settings.height), 1, scene::kMaxImageSide, true)}},
        {"render",
         false,
         {settingKey("--mode"),
          settingKey("--spp"),
          settingKey("--seed"),
          settingKey("--density-scale"),
          settingKey("--g"),
          vectorKey("ambient", AT(settings.ambient), false, true),
          {"background",  // three radiances, or "ambient": what escaping rays see (the default: black)
           [](const Session& s, Json& j) {
               j["background"] = s.settings.background ? vec3(*s.settings.background) : Json("ambient");
           },
           [](const Reader& r, Session& s) {
               if (!r.has("background")) return;
               if (r.json().at("background") == "ambient")
                   s.settings.background.reset();
               else
                   s.settings.background = readVector(r, "background", true);
           }},
          settingKey("--dt"),
          settingKey("--dvr-shading"),
          settingKey("--transmittance"),
          settingKey("--control-extinction")}},
        {"structure",
         false,
         {settingKey("--traversal"), settingKey("--sampler"), settingKey("--backend"), settingKey("--grid"),
          settingKey("--kd-leaves"), settingKey("--sub-majorants"), settingKey("--dense-max-mib")},
         [](const Session&) { return true; },
         [](Session& s) { s.structure.validate(); }},
        {"legend",
         false,
         {settingKey("--legend"), settingKey("--legend-place"), settingKey("--legend-title"),
          settingKey("--legend-units"), settingKey("--legend-font")},
         [](const Session& s) { return !(s.legend == Legend{}); }},
    };
    return kSections;
}
#undef AT

const Section& sectionNamed(std::string_view name) {
    for (const Section& sec : sections())
        if (sec.name == name) return sec;
    AMRVK_CHECK(false, "internal: no session section '", name, "'");
    throw;  // unreachable
}

void writeSection(const Section& sec, const Session& s, Json& j) {
    if (!sec.written(s)) return;
    Json& out = j[sec.name] = Json::object();
    for (const Key& k : sec.keys) k.write(s, out);
}

// A missing optional section reads as an empty one: every key at its fallback.
void readSection(const Section& sec, const Reader& top, Session& s) {
    static const Json kEmpty = Json::object();
    if (!sec.required && !top.has(sec.name)) {
        const Reader none(kEmpty, top.where() + "." + sec.name);
        for (const Key& k : sec.keys) k.read(none, s);
    } else {
        const Reader r = top.child(sec.name);
        AMRVK_CHECK(r.json().is_object(), r.where(), ": expected an object, found ", r.json().type_name());
        std::vector<const char*> names;
        for (const Key& k : sec.keys) names.push_back(k.name);
        r.onlyKeys(names);  // a key of no entry (a typo, a newer amrvk's) is refused, never dropped
        for (const Key& k : sec.keys) k.read(r, s);
    }
    try {
        sec.check(s);
    } catch (const Error& e) {
        throw Error(top.where() + "." + sec.name + ": " + e.what());
    }
}

Json lightsJson(const std::vector<scene::Light>& lights) {
    Json out = Json::array();
    for (const scene::Light& L : lights)
        out.push_back(L.point ? Json{{"type", "point"}, {"position", vec3(L.posOrDir)}, {"intensity", vec3(L.radiance)}}
                              : Json{{"type", "directional"}, {"direction", vec3(L.posOrDir)},
                                     {"radiance", vec3(L.radiance)}});
    return out;
}

Json cutJson(const scene::CutAway& cut) {
    Json out = Json::object();
    if (cut.crop) out["crop"] = {{"lo", vec3(cut.crop->lo)}, {"hi", vec3(cut.crop->hi)}};
    if (!cut.clips.empty()) {
        out["clip"] = Json::array();
        for (const scene::ClipPlane& c : cut.clips) out["clip"].push_back({{"point", vec3(c.point)}, {"normal", vec3(c.normal)}});
    }
    return out;
}

// "cameraPath": the fps and each keyframe's frame and camera, the camera with the keys of the
// session's own "camera" (the same table entries write them).
Json cameraPathJson(const CameraPath& path) {
    Json keys = Json::array();
    for (const Keyframe& k : path.keyframes()) {
        Session holder;
        holder.settings.camera = k.camera;
        Json key = {{"frame", k.frame}};
        writeSection(sectionNamed("camera"), holder, key);
        keys.push_back(std::move(key));
    }
    return {{"fps", path.fps()}, {"keyframes", std::move(keys)}};
}

}  // namespace

std::string sessionJson(const Session& s) {
    Json j;
    j["amrvk"] = "session";
    j["version"] = kVersion;
    j["input"] = s.input;
    writeSection(sectionNamed("read"), s, j);
    j["field"] = s.field;
    for (const char* name : {"camera", "image", "render"}) writeSection(sectionNamed(name), s, j);
    j["lights"] = lightsJson(s.settings.lights);
    if (!s.settings.cut.empty()) j["cut"] = cutJson(s.settings.cut);
    writeSection(sectionNamed("structure"), s, j);
    j["transferFunction"] = Json::parse(scene::paraViewPresetJson(s.tf)).at(0);
    settingKey("--tf-colors").write(s, j);
    writeSection(sectionNamed("legend"), s, j);
    if (!s.cameraPath.empty()) j["cameraPath"] = cameraPathJson(s.cameraPath);  // absent: the file as before
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

// "lights": an array of directional and point lights.
std::vector<scene::Light> readLights(const Json& lights, const std::string& where) {
    AMRVK_CHECK(lights.is_array(), where, ": expected an array");
    std::vector<scene::Light> out;
    for (size_t i = 0; i < lights.size(); ++i) {
        const Reader L(lights[i], where + "[" + std::to_string(i) + "]");
        const std::string type = L.text("type");
        scene::Light light;
        if (type == "directional") {
            L.onlyKeys({"type", "direction", "radiance"});
            light.posOrDir = L.vector("direction");
            light.radiance = L.vector("radiance");
            AMRVK_CHECK(glm::length(light.posOrDir) > 0, L.where(), ".direction: must not be zero");
        } else {
            AMRVK_CHECK(type == "point", L.where(), ".type: '", type, "' (expected directional or point)");
            light.point = true;
            L.onlyKeys({"type", "position", "intensity"});
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
    // Not an object (5, [], "x"): refused, not read as no cut-away (issue 52, point 9).
    AMRVK_CHECK(cut.json().is_object(), cut.where(), ": expected an object with \"crop\" and/or \"clip\"");
    cut.onlyKeys({"crop", "clip"});
    scene::CutAway c;
    if (cut.has("crop")) {
        const Reader crop = cut.child("crop");
        crop.onlyKeys({"lo", "hi"});
        c.crop = scene::CropBox{crop.vector("lo"), crop.vector("hi")};
    }
    if (cut.has("clip")) {
        const Json& clips = cut.json().at("clip");
        AMRVK_CHECK(clips.is_array(), cut.where(), ".clip: expected an array");
        AMRVK_CHECK(clips.size() <= shared::kMaxClipPlanes, cut.where(), ".clip: at most ", shared::kMaxClipPlanes,
                    " planes (got ", clips.size(), ")");
        for (size_t i = 0; i < clips.size(); ++i) {
            const Reader p(clips[i], cut.where() + ".clip[" + std::to_string(i) + "]");
            p.onlyKeys({"point", "normal"});
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

// "cameraPath": every value checked, each keyframe's camera read by the session camera's own keys.
CameraPath readCameraPath(const Reader& r) {
    AMRVK_CHECK(r.json().is_object(), r.where(), ": expected an object with \"fps\" and \"keyframes\"");
    r.onlyKeys({"fps", "keyframes"});
    CameraPath path;
    if (r.has("fps")) {
        const double fps = r.number("fps");
        AMRVK_CHECK(fps > 0 && fps <= kMaxPathFps, r.where(), ".fps: ", formatDouble(fps), " is outside (0, ",
                    kMaxPathFps, "]");
        path.setFps(fps);
    }
    const Reader keys = r.child("keyframes");
    AMRVK_CHECK(keys.json().is_array(), keys.where(), ": expected an array, found ", keys.json().type_name());
    AMRVK_CHECK(!keys.json().empty(), keys.where(), ": no keyframes (leave \"cameraPath\" out for no path)");
    AMRVK_CHECK(keys.json().size() <= kMaxKeyframes, keys.where(), ": at most ", kMaxKeyframes, " keyframes (got ",
                keys.json().size(), ")");
    for (size_t i = 0; i < keys.json().size(); ++i) {
        const Reader k(keys.json()[i], keys.where() + "[" + std::to_string(i) + "]");
        AMRVK_CHECK(k.json().is_object(), k.where(), ": expected an object with \"frame\" and \"camera\"");
        k.onlyKeys({"frame", "camera"});
        const auto frame = uint32_t(k.integer("frame", 0, kMaxPathFrames - 1));
        AMRVK_CHECK(!path.hasKeyframe(frame), k.where(), ".frame: ", frame,
                    " is another keyframe's frame (one keyframe a frame)");
        Session holder;
        readSection(sectionNamed("camera"), k, holder);
        try {
            path.add(frame, holder.settings.camera);
        } catch (const Error& e) {
            throw Error(k.where() + ".camera: " + e.what());
        }
    }
    return path;
}

}  // namespace

Session parseSession(const std::string& text, const fs::path& path) {
    const std::string file = path.string();
    const Json doc = parseDocument(text, file);
    const Reader top(doc, file);
    AMRVK_CHECK(doc.is_object() && top.text("amrvk", "") == "session", file,
                ": not an amrvk session (expected \"amrvk\": \"session\")");
    const int64_t version = top.integer("version", 1, 1 << 20);
    AMRVK_CHECK(version >= 1 && version <= kVersion, file, ": session version ", version,
                " (this amrvk reads versions 1 to ", kVersion, ")");
    top.onlyKeys({"amrvk", "version", "input", "read", "field", "camera", "image", "render", "lights", "cut",
                  "structure", "transferFunction", "tfColors", "legend", "cameraPath"});

    Session s;
    s.input = top.text("input");
    AMRVK_CHECK(!s.input.empty(), file, ".input: empty");
    if (fs::path(s.input).is_relative()) s.input = (path.parent_path() / s.input).lexically_normal().string();
    s.field = top.text("field", "");
    for (const Section& sec : sections()) readSection(sec, top, s);
    if (version < 3) {  // what a missing key meant then: linear values, the ambient behind
        if (!(top.has("read") && top.child("read").has("scale"))) s.read.scale = amr::FieldScale::Linear;
        if (!(top.has("render") && top.child("render").has("background"))) s.settings.background.reset();
    }
    if (top.has("lights")) s.settings.lights = readLights(doc.at("lights"), file + ".lights");
    if (top.has("cut")) s.settings.cut = readCut(top.child("cut"));
    // One ParaView preset object, read by the same code as preset files.
    s.tf = scene::parseParaViewPreset(top.child("transferFunction").json().dump(), file + ".transferFunction");
    // Version 1 knew only linear colours; a later file without the key means the default.
    if (version == 1 && !top.has("tfColors"))
        s.tfColors = scene::TfColors::Linear;
    else
        settingKey("--tf-colors").read(top, s);
    if (top.has("cameraPath")) s.cameraPath = readCameraPath(top.child("cameraPath"));
    return s;
}

void saveSession(const fs::path& path, const Session& s) { writeFileAtomic(path, sessionJson(s)); }

Session loadSession(const fs::path& path) {
    std::error_code ec;
    AMRVK_CHECK(fs::is_regular_file(path, ec), path.string(), ": no such session file");
    return parseSession(readTextFile(path), path);
}

}  // namespace amrvk::session
