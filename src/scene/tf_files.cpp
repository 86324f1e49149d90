#include "scene/tf_files.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/file_io.h"
#include "core/json_text.h"
#include "core/strings.h"
#include "scene/tf_presets.h"

namespace fs = std::filesystem;

namespace amrvk::scene {

namespace {

constexpr int kMaxXfNodes = 1 << 20;
constexpr uint64_t kXfHeaderBytes = 8 + 4 + 2 * 4 + 2 * 4 + 4;
constexpr uint64_t kOldXfBytes = 128 * sizeof(float);

// Node i of n spaced uniformly over [lo, hi] (both ends exact); double arithmetic, monotone in i.
float uniformPosition(int i, int n, double lo, double hi) {
    if (n <= 1 || i == 0) return static_cast<float>(lo);
    if (i == n - 1) return static_cast<float>(hi);
    double p = lo + (hi - lo) * (static_cast<double>(i) / (n - 1));
    return static_cast<float>(std::clamp(p, lo, hi));
}

// The numbers of array member `key`, which must hold a positive multiple of `stride` numbers.
std::vector<double> readNumberArray(const nlohmann::json& preset, const char* key, size_t stride,
                                    const std::string& where) {
    const nlohmann::json& arr = preset.at(key);
    AMRVK_CHECK(arr.is_array(), where, ": ", key, " is not an array (it is a ", arr.type_name(), ")");
    std::vector<double> out;
    out.reserve(arr.size());
    for (size_t i = 0; i < arr.size(); ++i) {
        AMRVK_CHECK(arr[i].is_number(), where, ": ", key, " element ", i, " is a ", arr[i].type_name(),
                    ", not a number");
        out.push_back(arr[i].get<double>());
    }
    AMRVK_CHECK(!out.empty() && out.size() % stride == 0, where, ": ", key, " has ", out.size(),
                " numbers, not a positive multiple of ", stride);
    return out;
}

// Node positions of a ParaView array: finite as float and non-descending.
float presetPosition(double x, size_t node, const char* key, const std::string& where,
                     const std::vector<float>& previous) {
    float p = static_cast<float>(x);
    AMRVK_CHECK(std::isfinite(p), where, ": ", key, " node ", node, " position ", x, " is not a finite float");
    AMRVK_CHECK(previous.empty() || p >= previous.back(), where, ": ", key, " positions not ascending at node ", node,
                " (", x, " after ", previous.back(), ")");
    return p;
}

TfChannels channelsFromJson(const nlohmann::json& preset, const std::string& where, const std::string& name) {
    AMRVK_CHECK(preset.contains("RGBPoints"), where, ": no RGBPoints",
                preset.contains("IndexedColors") ? " (indexed colour maps are not supported)" : "");
    TfChannels out;
    out.name = name;
    std::vector<double> rgbPoints = readNumberArray(preset, "RGBPoints", 4, where);
    for (size_t i = 0; i < rgbPoints.size() / 4; ++i) {
        out.colorPositions.push_back(presetPosition(rgbPoints[4 * i], i, "RGBPoints", where, out.colorPositions));
        glm::dvec3 c(rgbPoints[4 * i + 1], rgbPoints[4 * i + 2], rgbPoints[4 * i + 3]);
        for (int k = 0; k < 3; ++k)
            AMRVK_CHECK(c[k] >= 0.0 && c[k] <= 1.0, where, ": RGBPoints node ", i, " colour ", "rgb"[k], " = ",
                        formatDouble(c[k]), " is outside [0, 1]");
        out.colors.emplace_back(c);
    }
    if (preset.contains("Points")) {
        std::vector<double> points = readNumberArray(preset, "Points", 4, where);
        for (size_t i = 0; i < points.size() / 4; ++i) {
            out.opacityPositions.push_back(presetPosition(points[4 * i], i, "Points", where, out.opacityPositions));
            double a = points[4 * i + 1];
            AMRVK_CHECK(a >= 0.0 && std::isfinite(static_cast<float>(a)), where, ": Points node ", i, " opacity ", a,
                        " is negative or not a finite float");
            out.alphas.push_back(float(a));
        }
    } else {
        out.opacityPositions = {out.colorPositions.front(), out.colorPositions.back()};
        out.alphas = {0.0f, 1.0f};
    }
    out.merged();  // validates the combination (one error naming the preset)
    return out;
}

std::string oneLine(std::string s) {
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

// The presets of a ParaView JSON file: one object or an array of them, each with its label (its
// "Name", else "#index").
struct PresetDocument {
    nlohmann::json doc;
    std::vector<const nlohmann::json*> presets;
    std::vector<std::string> labels;
};

PresetDocument readPresetDocument(const fs::path& path) {
    const std::string file = path.string();
    PresetDocument d;
    try {
        const std::string text = readTextFile(path);
        checkJsonDepth(text, file);
        d.doc = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        std::string msg = e.what();
        if (size_t close = msg.find("] "); msg.starts_with("[json.exception") && close != std::string::npos)
            msg = msg.substr(close + 2);
        AMRVK_CHECK(false, file, ": malformed JSON (", oneLine(msg), ")");
    }
    AMRVK_CHECK(d.doc.is_array() || d.doc.is_object(), file,
                ": expected a ParaView preset object or an array of presets, found a ", d.doc.type_name());
    if (d.doc.is_object()) {
        d.presets.push_back(&d.doc);
    } else {
        for (const nlohmann::json& p : d.doc) d.presets.push_back(&p);
    }
    AMRVK_CHECK(!d.presets.empty(), file, ": no presets (empty array)");
    for (size_t i = 0; i < d.presets.size(); ++i) {
        const nlohmann::json& p = *d.presets[i];
        d.labels.push_back(p.is_object() && p.contains("Name") && p["Name"].is_string() ? p["Name"].get<std::string>()
                                                                                        : strCat("#", i));
    }
    return d;
}

TfChannels presetChannels(const PresetDocument& d, size_t i, const fs::path& path) {
    const std::string where = strCat(path.string(), ": preset '", d.labels[i], "'");
    AMRVK_CHECK(d.presets[i]->is_object(), where, ": not a JSON object");
    return channelsFromJson(*d.presets[i], where, d.labels[i]);
}

}  // namespace

TransferFunction loadParaViewPreset(const fs::path& path, std::string_view presetName) {
    const PresetDocument d = readPresetDocument(path);
    size_t chosen = 0;
    if (!presetName.empty()) {
        chosen = d.presets.size();
        std::string available;
        for (size_t i = 0; i < d.presets.size(); ++i) {
            if (d.labels[i] == presetName && chosen == d.presets.size()) chosen = i;
            if (i < 8)
                available += (i ? ", " : "") + d.labels[i];
            else if (i == 8)
                available += ", ...";
        }
        AMRVK_CHECK(chosen < d.presets.size(), path.string(), ": no preset named '", presetName, "' (",
                    d.presets.size(), " presets: ", available, ")");
    }
    return presetChannels(d, chosen, path).merged();
}

ParaViewPresets loadParaViewPresets(const fs::path& path) {
    const PresetDocument d = readPresetDocument(path);
    ParaViewPresets out;
    for (size_t i = 0; i < d.presets.size(); ++i) {
        try {
            out.presets.push_back(presetChannels(d, i, path));
        } catch (const Error& e) {
            out.skipped.push_back(e.what());
        }
    }
    return out;
}

TfChannels parseParaViewPreset(const std::string& text, const std::string& where) {
    nlohmann::json j;
    checkJsonDepth(text, where);
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        AMRVK_CHECK(false, where, ": malformed JSON (", oneLine(e.what()), ")");
    }
    AMRVK_CHECK(j.is_object(), where, ": expected a ParaView preset object, found a ", j.type_name());
    const std::string name = j.contains("Name") && j["Name"].is_string() ? j["Name"].get<std::string>() : "session";
    return channelsFromJson(j, where, name);
}

std::string paraViewPresetJson(const TfChannels& c) {
    nlohmann::json rgb = nlohmann::json::array(), points = nlohmann::json::array();
    for (size_t i = 0; i < c.colorPositions.size(); ++i)
        for (float v : {c.colorPositions[i], c.colors[i].r, c.colors[i].g, c.colors[i].b}) rgb.push_back(v);
    for (size_t i = 0; i < c.opacityPositions.size(); ++i)
        for (float v : {c.opacityPositions[i], c.alphas[i], 0.5f, 0.0f}) points.push_back(v);
    const nlohmann::ordered_json p = {{"Name", c.name}, {"ColorSpace", "RGB"}, {"RGBPoints", rgb}, {"Points", points}};
    return nlohmann::ordered_json::array({p}).dump(1) + "\n";
}

TransferFunction loadXf(const fs::path& path, float dataLo, float dataHi) {
    const std::string file = path.string();
    BinaryReader in(path);
    uint64_t magic = 0;
    if (in.size() >= sizeof(magic)) in.read(&magic, sizeof(magic));
    std::vector<float> positions;
    std::vector<glm::vec4> colors;
    if (magic == kXfMagic) {
        float opacityScale = 0, absLo = 0, absHi = 0, relLo = 0, relHi = 0;
        int32_t n = 0;
        in.read(&opacityScale, 4);
        in.read(&absLo, 4);
        in.read(&absHi, 4);
        in.read(&relLo, 4);
        in.read(&relHi, 4);
        in.read(&n, 4);
        AMRVK_CHECK(n >= 1 && n <= kMaxXfNodes, file, ": node count N = ", n, " at byte 28 is outside [1, ",
                    kMaxXfNodes, "]");
        const uint64_t expected = kXfHeaderBytes + uint64_t(n) * 16;
        AMRVK_CHECK(in.size() == expected, file, ": size ", in.size(), " bytes, expected ", expected, " for N = ", n,
                    " nodes");
        AMRVK_CHECK(std::isfinite(absLo) && std::isfinite(absHi) && absLo <= absHi, file, ": absDomain [", absLo, ", ",
                    absHi, "] is not a finite ascending range");
        AMRVK_CHECK(std::isfinite(relLo) && std::isfinite(relHi) && relLo <= relHi, file, ": relDomain [", relLo, ", ",
                    relHi, "] (percent) is not a finite ascending range");
        const double scale = std::pow(1.1, static_cast<double>(opacityScale) - 100.0);
        AMRVK_CHECK(std::isfinite(opacityScale) && std::isfinite(static_cast<float>(scale)), file, ": opacityScale ",
                    opacityScale, " is out of range (alpha factor 1.1^(v-100))");
        const double width = static_cast<double>(absHi) - absLo;
        const double lo = absLo + relLo / 100.0 * width, hi = absLo + relHi / 100.0 * width;
        std::vector<float> rgba;
        in.readArray(rgba, uint64_t(n) * 4);
        for (int i = 0; i < n; ++i) {
            const float* c = &rgba[size_t(i) * 4];
            positions.push_back(uniformPosition(i, n, lo, hi));
            colors.emplace_back(c[0], c[1], c[2], static_cast<float>(c[3] * scale));
            AMRVK_CHECK(!(c[3] < 0.0f), file, ": node ", i, " alpha ", c[3], " at byte ",
                        kXfHeaderBytes + uint64_t(i) * 16 + 12, " is negative");
        }
    } else {
        AMRVK_CHECK(in.size() == kOldXfBytes, file, ": not a .xf transfer function: magic 0x", std::hex, magic,
                    " (expected 0x", kXfMagic, ")", std::dec, " and size ", in.size(),
                    " bytes (an owlExaBrick alpha table has ", kOldXfBytes, ")");
        checkRange(dataLo, dataHi, file + ": data");
        std::vector<float> alpha;
        in.seek(0);
        in.readArray(alpha, 128);
        for (int i = 0; i < 128; ++i) {
            positions.push_back(uniformPosition(i, 128, dataLo, dataHi));
            colors.emplace_back(glm::vec3(kGreyAlbedo), alpha[size_t(i)]);
        }
    }
    validateNodes(positions, colors, file);
    return TransferFunction(positions, colors, path.filename().string());
}

TransferFunction loadTransferFunction(std::string_view spec, const amr::Percentiles& data,
                                      const amr::VolumeHistogram& volumes, std::string_view presetName) {
    for (const std::string& name : presetNames())
        if (spec == name) return makePreset(spec, data, volumes);
    return loadTransferFunction(spec, data.lo(), data.hi(), presetName);
}

TransferFunction loadTransferFunction(std::string_view spec, float dataLo, float dataHi, std::string_view presetName) {
    for (const std::string& name : presetNames())
        if (spec == name) return makePreset(spec, dataLo, dataHi);
    const fs::path path(spec);
    std::error_code ec;
    AMRVK_CHECK(fs::exists(path, ec), "'", spec, "' is neither a transfer function preset (", joinedPresetNames(),
                ") nor an existing file");
    const std::string ext = toLower(path.extension().string());
    if (ext == ".xf") return loadXf(path, dataLo, dataHi);
    if (ext == ".json") return loadParaViewPreset(path, presetName);
    BinaryReader in(path);
    std::array<char, 64> head{};
    const uint64_t headBytes = std::min<uint64_t>(in.size(), head.size());
    in.read(head.data(), headBytes);
    uint64_t magic = 0;
    if (headBytes >= sizeof(magic)) std::memcpy(&magic, head.data(), sizeof(magic));
    if (magic == kXfMagic) return loadXf(path, dataLo, dataHi);
    for (uint64_t i = 0; i < headBytes; ++i) {
        if (std::isspace(static_cast<unsigned char>(head[i]))) continue;
        if (head[i] == '[' || head[i] == '{') return loadParaViewPreset(path, presetName);
        break;
    }
    AMRVK_CHECK(false, spec, ": unknown transfer function format (expected a .xf file or a ParaView ",
                "preset .json file)");
    return {};
}

}  // namespace amrvk::scene
