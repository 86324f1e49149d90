#include "session/series.h"

#include <glob.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <system_error>

#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/json_text.h"
#include "core/progress.h"

namespace fs = std::filesystem;

namespace amrvk::session {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// -1, 0, 1 as a < b, a == b, a > b in natural order (digit runs as numbers).
int naturalCompare(std::string_view a, std::string_view b) {
    size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        if (isDigit(a[i]) && isDigit(b[j])) {
            size_t ie = i, je = j;
            while (ie < a.size() && isDigit(a[ie])) ++ie;
            while (je < b.size() && isDigit(b[je])) ++je;
            std::string_view x = a.substr(i, ie - i), y = b.substr(j, je - j);
            // Compared as numbers of any length: without leading zeros, the longer is larger.
            x.remove_prefix(std::min(x.find_first_not_of('0'), x.size()));
            y.remove_prefix(std::min(y.find_first_not_of('0'), y.size()));
            if (x.size() != y.size()) return x.size() < y.size() ? -1 : 1;
            if (const int c = x.compare(y); c != 0) return c < 0 ? -1 : 1;
            i = ie;
            j = je;
        } else {
            if (a[i] != b[j]) return (unsigned char)a[i] < (unsigned char)b[j] ? -1 : 1;
            ++i;
            ++j;
        }
    }
    if (i < a.size() || j < b.size()) return i < a.size() ? 1 : -1;
    return 0;
}

constexpr uint32_t kMaxFrames = 100000;

}  // namespace

bool naturalLess(std::string_view a, std::string_view b) {
    const int c = naturalCompare(a, b);
    return c != 0 ? c < 0 : a < b;
}

bool isInputPattern(const std::string& arg) {
    std::error_code ec;
    return arg.find_first_of("*?[") != std::string::npos && !fs::exists(arg, ec);
}

std::vector<std::string> expandInputs(const std::vector<std::string>& args) {
    std::vector<std::string> out;
    for (const std::string& arg : args) {
        if (!isInputPattern(arg)) {
            out.push_back(arg);  // a path (a missing one fails when it is read, naming it)
            continue;
        }
        glob_t g{};
        const int rc = ::glob(arg.c_str(), GLOB_TILDE, nullptr, &g);
        std::vector<std::string> matches;
        if (rc == 0)
            for (size_t i = 0; i < g.gl_pathc; ++i) matches.emplace_back(g.gl_pathv[i]);
        ::globfree(&g);
        AMRVK_CHECK(rc != GLOB_NOSPACE, "input '", arg, "': out of memory expanding the pattern");
        AMRVK_CHECK(!matches.empty(), "input '", arg, "': no file or directory matches the pattern");
        out.insert(out.end(), matches.begin(), matches.end());
    }
    std::sort(out.begin(), out.end(), naturalLess);
    for (size_t i = 1; i < out.size(); ++i)
        AMRVK_CHECK(out[i] != out[i - 1], "input '", out[i], "' is named twice (a series shows each output once)");
    return out;
}

SeriesRange parseSeriesRange(std::string_view name) {
    if (name == "first") return SeriesRange::First;
    if (name == "union") return SeriesRange::Union;
    throw Error(strCat("--series-range: '", name, "' is not first or union"));
}

amr::FieldScale seriesScale(const std::vector<std::string>& inputs, const amr::ReadOptions& read,
                            const std::string& field) {
    if (read.scale != amr::FieldScale::Auto || inputs.empty()) return read.scale;
    amr::ReadOptions ro = read;
    if (!field.empty()) ro.fields = {field};
    return amr::resolvedScale(inputs.front(), ro);
}

SeriesStatistics seriesStatistics(const std::vector<std::string>& inputs, const amr::ReadOptions& read,
                                  std::string& field) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    std::vector<amr::Percentiles> parts;
    std::vector<amr::VolumeHistogram> volumes;
    ProgressBar bar("series range", "outputs");
    for (size_t i = 0; i < inputs.size(); ++i) {
        amr::ReadOptions ro = read;
        if (!field.empty()) ro.fields = {field};
        const amr::Model model = amr::readModel(inputs[i], ro);
        const amr::Field& f = field.empty() ? model.defaultField() : model.field(field);
        if (field.empty()) field = f.name;
        const amr::FieldStats st = amr::computeFieldStats(model, f);
        lo = std::min(lo, st.minValue);
        hi = std::max(hi, st.maxValue);
        parts.push_back(amr::percentilesOf(f.values));
        if (parts.back().count > 0) {  // as scene::makeVolume makes it
            const amr::ModelSummary summary = amr::summarize(model);
            volumes.push_back(amr::volumeHistogramOf(model.cells, f.values, st.minValue, st.maxValue, summary.minLevel,
                                                     summary.bounds.volume()));
        }
        bar.update(i + 1, inputs.size(), inputs[i]);
    }
    bar.finish();
    return {{lo, hi}, amr::pooledPercentiles(parts), amr::pooledVolumeHistograms(volumes)};
}

std::vector<std::string> planFrames(const std::vector<std::string>& inputs, std::optional<uint32_t> frames,
                                    bool orbitGiven) {
    AMRVK_CHECK(!inputs.empty(), "no input data set (give one, or --session FILE)");
    if (frames) {
        AMRVK_CHECK(inputs.size() == 1, "--frames ", *frames, ": renders one input ", *frames, " times (a turntable); ",
                    inputs.size(), " inputs make one frame each, without --frames");
        AMRVK_CHECK(*frames >= 1 && *frames <= kMaxFrames, "--frames ", *frames, " is outside [1, ", kMaxFrames, "]");
        AMRVK_CHECK(orbitGiven || *frames == 1, "--frames ", *frames, " without --orbit would render the same picture ",
                    *frames, " times (add --orbit 360 for a turntable)");
        return std::vector<std::string>(*frames, inputs.front());
    }
    AMRVK_CHECK(inputs.size() <= kMaxFrames, inputs.size(), " inputs: a series has at most ", kMaxFrames, " frames");
    AMRVK_CHECK(!orbitGiven || inputs.size() > 1,
                "--orbit over one input needs --frames N (N frames of it, frame k at k*DEG/N degrees)");
    return inputs;
}

double frameAzimuth(uint32_t k, uint32_t n, double degrees) { return n == 0 ? 0.0 : double(k) * degrees / double(n); }

bool hasFrameNumber(std::string_view text) {
    for (size_t i = 0; i + 1 < text.size(); ++i) {
        if (text[i] != '%') continue;
        if (text[i + 1] == '%') {
            ++i;
            continue;
        }
        size_t j = i + 1;
        if (text[j] == '0') ++j;
        if (j < text.size() && isDigit(text[j])) ++j;
        if (j < text.size() && text[j] == 'd') return true;
    }
    return false;
}

fs::path FrameOutput::frame(uint32_t k) const {
    char buf[4096];
    const int n = std::snprintf(buf, sizeof buf, pattern.c_str(), int(k));  // the one conversion, checked
    AMRVK_CHECK(n > 0 && size_t(n) < sizeof buf, "frame name from '", pattern, "' is too long");
    return fs::path(std::string(buf, size_t(n)));
}

FrameOutput frameOutput(const std::string& option, const std::string& text, uint32_t frameCount) {
    AMRVK_CHECK(!text.empty(), option, ": names no file");
    FrameOutput out;
    std::error_code ec;
    const bool isDir = text.back() == '/' || fs::is_directory(text, ec);
    if (isDir) {
        std::string dir = text;
        while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
        std::string escaped;
        for (char c : dir) escaped += c == '%' ? std::string("%%") : std::string(1, c);
        out.pattern = escaped + "/frame_%04d.png";
        out.directory = dir;
        out.extension = ".png";
        out.manifest = out.directory / "frame_manifest.json";
        return out;
    }
    // One conversion %d, %Nd or %0Nd; every other '%' doubled.
    const size_t slash = text.rfind('/');
    std::string name = slash == std::string::npos ? text : text.substr(slash + 1);
    int conversions = 0;
    std::string manifestName;
    for (size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') {
            if (i > slash || slash == std::string::npos) manifestName += text[i];
            continue;
        }
        if (i + 1 < text.size() && text[i + 1] == '%') {
            if (i > slash || slash == std::string::npos) manifestName += '%';
            ++i;
            continue;
        }
        size_t j = i + 1;
        if (j < text.size() && text[j] == '0') ++j;
        const size_t digits = j;
        while (j < text.size() && isDigit(text[j])) ++j;
        AMRVK_CHECK(
            j < text.size() && text[j] == 'd' && j - digits <= 1, option, " ", text,
            ": '%' starts a frame number only as %d, %4d or %04d (at most one digit of width; %% is a literal %)");
        AMRVK_CHECK(slash == std::string::npos || i > slash, option, " ", text,
                    ": the frame number belongs in the file name, not the directory");
        ++conversions;
        manifestName += "manifest";
        i = j;
    }
    AMRVK_CHECK(conversions <= 1, option, " ", text, ": ", conversions, " frame numbers (%d); give one");
    AMRVK_CHECK(conversions == 1 || frameCount <= 1, option, " ", text, ": ", frameCount,
                " frames need a numbered name with %d (e.g. frames/f_%04d.png), a directory (frames/) or a movie "
                "(movie.mp4)");
    out.pattern = conversions == 1 ? text : [&] {
        std::string escaped;
        for (char c : text) escaped += c == '%' ? std::string("%%") : std::string(1, c);
        return escaped;
    }();
    out.extension = fs::path(name).extension().string();
    AMRVK_CHECK(out.extension == ".png" || out.extension == ".exr" || out.extension == ".pfm", option, " ", text,
                ": unknown image type for frames (use .png, .exr or .pfm, or movie.mp4)");
    std::string dir;  // the directory part with %% read as % (a conversion there was refused above)
    for (size_t i = 0; slash != std::string::npos && i <= slash; ++i) {
        dir += text[i];
        if (text[i] == '%') ++i;
    }
    out.directory = slash == std::string::npos ? fs::path(".") : fs::path(dir).parent_path();
    if (out.directory.empty()) out.directory = "/";
    if (conversions == 0) manifestName = fs::path(manifestName).stem().string() + "_manifest";
    out.manifest = out.directory / fs::path(manifestName).replace_extension(".json");
    return out;
}

namespace {
using Json = nlohmann::ordered_json;
Json vec3(glm::dvec3 v) { return Json::array({v.x, v.y, v.z}); }
glm::dvec3 vec3(const Json& j, const char* key, const std::string& where) {
    AMRVK_CHECK(j.contains(key) && j[key].is_array() && j[key].size() == 3, where, ": '", key, "' is not 3 numbers");
    glm::dvec3 v;
    for (int a = 0; a < 3; ++a) {
        AMRVK_CHECK(j[key][size_t(a)].is_number(), where, ": '", key, "' is not 3 numbers");
        v[a] = j[key][size_t(a)].get<double>();
    }
    return v;
}
}  // namespace

std::optional<FileStamp> fileStamp(const fs::path& path) {
    std::error_code ec;
    const uint64_t bytes = fs::file_size(path, ec);
    if (ec) return std::nullopt;
    const auto modified = fs::last_write_time(path, ec);
    if (ec) return std::nullopt;
    return FileStamp{bytes, int64_t(modified.time_since_epoch().count())};
}

std::optional<FrameManifest> loadFrameManifest(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) return std::nullopt;
    const std::string where = path.string();
    // Read without noting it as an input (readTextFile would): the run rewrites it.
    const uint64_t size = fileSize(path);
    checkAllocation(size, where);
    std::string text(size, '\0');
    std::ifstream in(path, std::ios::binary);
    AMRVK_CHECK(in.read(text.data(), std::streamsize(size)), where, ": cannot read");
    checkJsonDepth(text, where);
    const Json j = Json::parse(text, nullptr, false);
    AMRVK_CHECK(!j.is_discarded() && j.is_object() && j.value("amrvk", "") == "frames", where,
                ": not an amrvk frame manifest (remove it, or write the frames elsewhere)");
    FrameManifest m;
    try {
        m.recipe = j.at("recipe").get<std::string>();
        for (const Json& k : j.at("done")) m.done.insert(k.get<uint32_t>());
        if (!j.at("tfRange").is_null())
            m.tfRange = std::make_pair(j["tfRange"].at(0).get<float>(), j["tfRange"].at(1).get<float>());
        if (j.contains("tfPercentiles") && !j["tfPercentiles"].is_null()) {
            const Json& t = j["tfPercentiles"];
            amr::Percentiles p;
            p.count = t.at("count").get<uint64_t>();
            const Json& v = t.at("values");
            AMRVK_CHECK(v.is_array() && v.size() == p.values.size() && p.count > 0, where,
                        ": malformed frame manifest (tfPercentiles: a count above 0 and 101 values); remove it to "
                        "render every frame");
            for (size_t k = 0; k < p.values.size(); ++k) {
                p.values[k] = v[k].get<float>();
                AMRVK_CHECK(std::isfinite(p.values[k]) && (k == 0 || p.values[k] >= p.values[k - 1]), where,
                            ": malformed frame manifest (tfPercentiles: finite and non-descending); remove it to "
                            "render every frame");
            }
            m.tfPercentiles = p;
        }
        if (j.contains("tfHistogram") && !j["tfHistogram"].is_null()) {
            const Json& t = j["tfHistogram"];
            amr::VolumeHistogram h;
            h.lo = t.at("lo").get<float>();
            h.hi = t.at("hi").get<float>();
            h.boundsVolume = t.at("boundsVolume").get<double>();
            h.volume = t.at("volume").get<std::vector<double>>();
            bool valid = std::isfinite(h.lo) && std::isfinite(h.hi) && h.lo <= h.hi && std::isfinite(h.boundsVolume) &&
                         h.boundsVolume > 0 && h.volume.size() == size_t(amr::VolumeHistogram::kBins) &&
                         m.tfPercentiles.has_value();
            for (double v : h.volume) valid = valid && std::isfinite(v) && v >= 0;
            AMRVK_CHECK(valid, where,
                        ": malformed frame manifest (tfHistogram: a finite range, boundsVolume above 0 and 1024 "
                        "finite volumes >= 0, with tfPercentiles); remove it to render every frame");
            m.tfHistogram = std::move(h);
        }
        const Json& c = j.at("camera");
        m.camera.eye = vec3(c, "eye", where);
        m.camera.target = vec3(c, "target", where);
        m.camera.up = vec3(c, "up", where);
        m.camera.fovYDegrees = c.at("fovYDegrees").get<double>();
        m.centre = vec3(j, "centre", where);
        m.field = j.at("field").get<std::string>();
        // An older amrvk listed the files without their stamps (an array): read as not listed.
        if (j.contains("inputsRead") && j["inputsRead"].is_object()) {
            m.inputsRead.emplace();
            for (const auto& [file, stamp] : j["inputsRead"].items())
                (*m.inputsRead)[file] = {stamp.at(0).get<uint64_t>(), stamp.at(1).get<int64_t>()};
        }
    } catch (const nlohmann::json::exception& e) {
        throw Error(strCat(where, ": malformed frame manifest (", e.what(), "); remove it to render every frame"));
    }
    return m;
}

void saveFrameManifest(const fs::path& path, const FrameManifest& m) {
    Json j = {{"amrvk", "frames"}, {"version", 1}, {"recipe", m.recipe}, {"done", m.done}};
    j["tfRange"] = m.tfRange ? Json::array({m.tfRange->first, m.tfRange->second}) : Json(nullptr);
    j["tfPercentiles"] =
        m.tfPercentiles ? Json{{"count", m.tfPercentiles->count}, {"values", m.tfPercentiles->values}} : Json(nullptr);
    j["tfHistogram"] = m.tfHistogram ? Json{{"lo", m.tfHistogram->lo},
                                            {"hi", m.tfHistogram->hi},
                                            {"boundsVolume", m.tfHistogram->boundsVolume},
                                            {"volume", m.tfHistogram->volume}}
                                     : Json(nullptr);
    j["camera"] = {{"eye", vec3(m.camera.eye)},
                   {"target", vec3(m.camera.target)},
                   {"up", vec3(m.camera.up)},
                   {"fovYDegrees", m.camera.fovYDegrees}};
    j["centre"] = vec3(m.centre);
    j["field"] = m.field;
    if (m.inputsRead) {
        j["inputsRead"] = Json::object();
        for (const auto& [file, stamp] : *m.inputsRead) j["inputsRead"][file] = {stamp.bytes, stamp.modified};
    }
    writeFileAtomic(path, j.dump(2) + "\n");
}

}  // namespace amrvk::session
