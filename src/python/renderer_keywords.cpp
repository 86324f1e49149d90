#include "python/renderer_keywords.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "scene/limits.h"

namespace amrvk::python {

namespace {

// The keywords Renderer(...) takes besides those of session::settingTable(); any other is a
// TypeError naming it.
const char* const kKnown[] = {"width",
                              "height",
                              "spp",
                              "ambient",
                              "background",
                              "lights",
                              "traversal",
                              "sampler",
                              "backend",
                              "grid",
                              "sub_majorants",
                              "device",
                              "validation",
                              "shader_dir",
                              "gpu_timeout",
                              "samples_per_invocation",
                              "path_regeneration",
                              "quiet",
                              "tf_range",
                              "crop",
                              "clip",
                              "legend",
                              "legend_place",
                              "legend_title",
                              "legend_units",
                              "tf_colors"};

// What a Choice setting takes, as a TypeError says it: "'ratio' or 'ubrm'", "one of 'ae', 'ss', ...".
std::string choicesText(const session::Setting& st) {
    std::vector<std::string> names;
    for (std::string_view c : session::settingChoices(st)) names.push_back("'" + std::string(c) + "'");
    if (names.size() == 2) return names[0] + " or " + names[1];
    std::string text = "one of ";
    for (size_t i = 0; i < names.size(); ++i) text += (i ? ", " : "") + names[i];
    return text;
}

}  // namespace

session::PictureDescription describe(const PyVolume& v, const std::optional<PyTf>& tf,
                                     const std::optional<scene::Camera>& camera, const py::kwargs& kw) {
    session::PictureDescription d;
    session::Session& s = d.session;
    s.input = v.source.input;
    s.read = v.source.read;
    s.field = v.volume->field().name;
    scene::RenderSettings& rs = s.settings;
    auto take = [&](const char* key) -> std::optional<py::object> {
        if (!kw.contains(key)) return std::nullopt;
        py::object o = kw[key];
        return o.is_none() ? std::nullopt : std::optional<py::object>(o);
    };
    for (const auto& item : kw) {
        const std::string key = py::str(item.first);
        const bool inTable = std::any_of(session::settingTable().begin(), session::settingTable().end(),
                                         [&](const session::Setting& st) { return st.keyword == key; });
        if (!inTable && std::find(std::begin(kKnown), std::end(kKnown), key) == std::end(kKnown))
            throw py::type_error("Renderer() got an unexpected keyword argument '" + key + "'");
    }
    if (auto o = take("width")) rs.width = int(wholeArg(*o, "width", 1, scene::kMaxImageSide));
    if (auto o = take("height")) rs.height = int(wholeArg(*o, "height", 1, scene::kMaxImageSide));
    if (auto o = take("spp")) s.spp = countArg(*o, "spp");
    if (auto o = take("ambient")) rs.ambient = vec3(keywordArg<std::vector<double>>(*o, "ambient", kThree), "ambient");
    if (auto o = take("background"))
        rs.background = vec3(keywordArg<std::vector<double>>(*o, "background", kThree), "background");
    if (auto o = take("lights")) rs.lights = keywordArg<std::vector<scene::Light>>(*o, "lights", kLights);
    for (const session::Setting& st : session::settingTable())  // before the camera: fov is one of them
        if (auto o = take(std::string(st.keyword).c_str())) setSettingFromPython(st, *o, s);
    if (auto o = take("crop")) rs.cut.crop = cropOf(*o);
    if (auto o = take("clip")) rs.cut.clips = clipsOf(*o);
    if (auto o = take("legend")) s.legend.show = keywordArg<bool>(*o, "legend", "True or False");
    if (auto o = take("legend_place"))
        s.legend.place = forKeyword("legend_place", [&] {
            return session::parseLegendPlace(keywordArg<std::string>(*o, "legend_place", "'side' or 'overlay'"));
        });
    if (auto o = take("legend_title")) s.legend.title = keywordArg<std::string>(*o, "legend_title", kText);
    if (auto o = take("legend_units")) s.legend.units = keywordArg<std::string>(*o, "legend_units", kText);
    session::checkLegendText(s.legend);
    if (camera) rs.camera = *camera;
    d.fitCamera = !camera;
    if (tf)
        s.tf = tf->channels;
    else
        d.tfSource = session::TfSource{};  // ramp over the field's range, as amrvk render
    if (auto o = take("tf_range")) {
        const auto r = keywordArg<std::pair<float, float>>(*o, "tf_range", "(lo, hi): two numbers");
        d.tfRange = r;
    }
    if (auto o = take("tf_colors"))
        s.tfColors = scene::parseTfColors(keywordArg<std::string>(*o, "tf_colors", "'srgb' or 'linear'"), "tf_colors");
    const std::optional<py::object> traversal = take("traversal");
    const std::string t = traversal ? keywordArg<std::string>(*traversal, "traversal", kText) : "";
    d.fit = t == "auto" ? session::StructureFit::Probe
            : t.empty() ? session::StructureFit::Data
                        : session::StructureFit::None;
    if (!t.empty() && t != "auto") s.structure.traversal = scene::parseTraversal(t);
    if (auto o = take("sampler")) {
        s.structure.sampler = scene::parseSampler(keywordArg<std::string>(*o, "sampler", kText));
        d.samplerGiven = true;
    }
    s.structure.backend = scene::Backend::Auto;
    if (auto o = take("backend")) {
        s.structure.backend = scene::parseBackend(keywordArg<std::string>(*o, "backend", kText));
        d.backendGiven = true;
    }
    if (auto o = take("grid")) {
        s.structure.grid = keywordArg<std::string>(*o, "grid", kText);
        d.gridGiven = true;
    }
    if (auto o = take("sub_majorants")) {
        s.structure.subMajorants = subMajorantsArg(*o);
        d.subMajorantsGiven = true;
    }
    scene::validateSettings(rs);
    return d;
}

void setSettingFromPython(const session::Setting& st, const py::handle& o, session::Session& s) {
    const std::string keyword(st.keyword);
    switch (st.kind) {
        case session::SettingKind::Number: {
            const double v = keywordArg<double>(o, keyword.c_str(), kNumber);
            session::checkSetting(st, v, keyword);
            st.setNumber(s, v);
            return;
        }
        case session::SettingKind::Integer:
            st.setNumber(s, double(wholeArg(o, keyword.c_str(), (long long)st.lo, (long long)st.hi)));
            return;
        case session::SettingKind::Flag:
            st.setNumber(s, keywordArg<bool>(o, keyword.c_str(), "True or False") ? 1 : 0);
            return;
        case session::SettingKind::Choice: {
            session::setSettingChoice(st, s, keywordArg<std::string>(o, keyword.c_str(), choicesText(st).c_str()),
                                      keyword);
            return;
        }
    }
}

py::object settingToPython(const session::Setting& st, const session::Session& s) {
    switch (st.kind) {
        case session::SettingKind::Number:
            return py::float_(st.number(s));
        case session::SettingKind::Integer:
            return py::int_((long long)st.number(s));
        case session::SettingKind::Flag:
            return py::bool_(st.number(s) != 0);
        case session::SettingKind::Choice:
            break;
    }
    return py::str(st.name(s));
}

void bindSettingTable(py::module_& m) {
    m.def(
        "_settings",
        [] {
            py::list rows;
            for (const session::Setting& st : session::settingTable()) {
                static const char* const kKinds[] = {"number", "integer", "choice", "flag"};
                py::dict d;
                d["option"] = std::string(st.option);
                d["keyword"] = std::string(st.keyword);
                d["section"] = std::string(st.section);
                d["key"] = std::string(st.key);
                d["kind"] = kKinds[int(st.kind)];
                d["unit"] = std::string(st.unit);
                d["lo"] = st.lo;
                d["hi"] = st.hi;
                d["lo_open"] = st.loOpen;
                d["hi_open"] = st.hiOpen;
                d["choices"] = std::string(st.choices);
                d["default"] = settingToPython(st, session::Session{});
                d["invalidates"] = scene::describe(st.invalidates);
                rows.append(d);
            }
            return rows;
        },
        "the picture settings of session/setting_table.h, one dict each");
}

}  // namespace amrvk::python
