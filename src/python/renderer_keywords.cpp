#include "python/renderer_keywords.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "scene/limits.h"

namespace amrvk::python {

namespace {

// The keywords Renderer(...) takes besides the picture settings of session::settingTable(): the
// device's and the console's. Any other is a TypeError naming it.
const char* const kDeviceKeywords[] = {
    "device", "validation", "shader_dir", "gpu_timeout", "samples_per_invocation", "path_regeneration", "quiet"};

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
        if (!session::settingForKeyword(key) &&
            std::find(std::begin(kDeviceKeywords), std::end(kDeviceKeywords), key) == std::end(kDeviceKeywords))
            throw py::type_error("Renderer() got an unexpected keyword argument '" + key + "'");
    }
    // The table's compound settings, parsed here.
    if (auto o = take("width")) rs.width = int(wholeArg(*o, "width", 1, scene::kMaxImageSide));
    if (auto o = take("height")) rs.height = int(wholeArg(*o, "height", 1, scene::kMaxImageSide));
    if (auto o = take("ambient")) rs.ambient = vec3(keywordArg<std::vector<double>>(*o, "ambient", kThree), "ambient");
    if (auto o = take("background"))
        rs.background = vec3(keywordArg<std::vector<double>>(*o, "background", kThree), "background");
    if (auto o = take("lights")) rs.lights = keywordArg<std::vector<scene::Light>>(*o, "lights", kLights);
    if (auto o = take("crop")) rs.cut.crop = cropOf(*o);
    if (auto o = take("clip")) rs.cut.clips = clipsOf(*o);
    if (camera) rs.camera = *camera;
    d.fitCamera = !camera;
    if (tf)
        s.tf = tf->channels;
    else
        d.tfSource = session::TfSource{};  // ramp over the field's range, as amrvk render
    if (auto o = take("tf_range"))
        d.tfRange = keywordArg<std::pair<float, float>>(*o, "tf_range", "(lo, hi): two numbers");
    // The others, each as its row says (fov after the camera: it is one of them).
    bool probe = false;
    for (const session::Setting& st : session::settingTable()) {
        if (st.kind == session::SettingKind::Compound) continue;
        const std::optional<py::object> o = take(std::string(st.keyword).c_str());
        if (!o) continue;
        if (!st.request.empty() && py::isinstance<py::str>(*o) && o->cast<std::string>() == st.request) {
            probe = true;  // traversal 'auto': the picture probes
            continue;
        }
        setSettingFromPython(st, *o, s);
        if (st.section == "structure") d.given.insert(std::string(st.key));
    }
    d.fit = probe                    ? session::StructureFit::Probe
            : d.isGiven("traversal") ? session::StructureFit::None
                                     : session::StructureFit::Data;
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
            // A choice named by a number also takes the number (sub_majorants=8); any other is a TypeError.
            const bool number = py::isinstance<py::int_>(o) && !py::isinstance<py::bool_>(o) &&
                                session::settingChoiceError(st, std::string(py::str(o))).empty();
            const std::string text =
                number ? std::string(py::str(o)) : keywordArg<std::string>(o, keyword.c_str(), choicesText(st).c_str());
            session::setSettingName(st, s, text, keyword);
            return;
        }
        case session::SettingKind::Text:
            session::setSettingName(st, s, keywordArg<std::string>(o, keyword.c_str(), kText), keyword);
            return;
        case session::SettingKind::Compound:
            break;
    }
    throw std::logic_error("internal: " + keyword + " is parsed by describe()");
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
        case session::SettingKind::Text:
            return py::str(st.name(s));
        case session::SettingKind::Compound:
            break;
    }
    throw std::logic_error("internal: " + std::string(st.keyword) + " has no single value");
}

void bindSettingTable(py::module_& m) {
    m.def(
        "_settings",
        [] {
            py::list rows;
            for (const session::Setting& st : session::settingTable()) {
                static const char* const kKinds[] = {"number", "integer", "choice", "flag", "text", "compound"};
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
                d["default"] = st.kind == session::SettingKind::Compound ? py::object(py::none())
                                                                         : settingToPython(st, session::Session{});
                d["value_name"] = std::string(st.valueName);
                d["zero"] = std::string(st.zero);
                d["request"] = std::string(st.request);
                d["python_property"] = st.pythonProperty && st.kind != session::SettingKind::Compound;
                d["invalidates"] = scene::describe(st.invalidates);
                rows.append(d);
            }
            return rows;
        },
        "the picture settings of session/setting_table.h, one dict each");
}

}  // namespace amrvk::python
