// The Python module `amrvk` (its compiled part, `amrvk._amrvk`; python/amrvk/ adds the yt bridge,
// tqdm progress and Jupyter display). A thin layer over the one entry from a picture description
// to pixels (picture::makePicture): Volume is a scene::Volume (from a file through the readers, or
// from numpy arrays validated as the readers validate), TransferFunction a scene::TfChannels,
// Camera a scene::Camera, and Renderer a picture with its session kept in step with every edit.
// The GIL is released while the device works; long work runs in chunks of about a quarter of a
// second (whole samples, or tiles of rows when one sample takes longer), so Ctrl-C
// (KeyboardInterrupt) and a progress callback are served between chunks. Errors are the CLI's
// one-line messages: amrvk::Error -> ValueError (bad input) or RuntimeError (device, state).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "amr/readers.h"
#include "core/checked_size.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/font.h"
#include "core/image_io.h"
#include "core/movie_io.h"
#include "core/stats.h"
#include "core/strings.h"
#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "picture/first_frame.h"
#include "picture/picture.h"
#include "python/fair_mutex.h"
#include "python/keyword_messages.h"
#include "scene/camera.h"
#include "scene/limits.h"
#include "scene/transfer_function.h"
#include "session/picture_description.h"
#include "session/legend_image.h"
#include "session/series.h"
#include "session/session.h"

namespace py = pybind11;
namespace fs = std::filesystem;
using namespace amrvk;

namespace {

// A value as a message shows it: its repr where that is one short line, else its type.
std::string shortRepr(const py::handle& o) {
    std::string shown = py::repr(o).cast<std::string>();
    if (shown.size() > 64 || shown.find('\n') != std::string::npos) shown = strCat("a ", Py_TYPE(o.ptr())->tp_name);
    return shown;
}

// A whole number from Python in [lo, hi], the CLI's range for that option; anything else is one
// line naming the keyword and the value (not pybind11's list of signatures).
long long wholeArg(const py::handle& o, const char* name, long long lo, long long hi) {
    const std::string shown = shortRepr(o);
    if (!py::isinstance<py::int_>(o) || py::isinstance<py::bool_>(o))
        throw py::type_error(strCat(name, ": expected a whole number in [", lo, ", ", hi, "], got ", shown));
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(o.ptr(), &overflow);
    if (overflow != 0 || v < lo || v > hi) throw py::value_error(strCat(name, ": ", shown, " is outside [", lo, ", ", hi, "]"));
    return v;
}

// sub_majorants: 'off' or False (0), or 2, 4, 8, 16 (a number or its string), as --sub-majorants.
uint32_t subMajorantsArg(const py::handle& o) {
    if (py::isinstance<py::bool_>(o) && !o.cast<bool>()) return 0;
    std::string text;
    if (py::isinstance<py::str>(o)) text = o.cast<std::string>();
    else if (py::isinstance<py::int_>(o) && !py::isinstance<py::bool_>(o)) text = std::to_string(wholeArg(o, "sub_majorants", 0, 16));
    else throw py::type_error(strCat("sub_majorants: expected 'off', 2, 4, 8 or 16, got ", shortRepr(o)));
    if (text == "0") return 0;
    try {
        return scene::parseSubMajorants(text, "sub_majorants");
    } catch (const Error& e) {
        throw py::value_error(e.what());
    }
}

// A count from Python (spp, n): a whole number in [1, 2^24], the CLI's --spp range.
uint32_t countArg(const py::handle& o, const char* name) { return uint32_t(wholeArg(o, name, 1, scene::kMaxSpp)); }

constexpr const char* kNumber = "a number";
constexpr const char* kText = "a string";
constexpr const char* kThree = "3 numbers";
constexpr const char* kLights = "a list of amrvk.Light";
constexpr const char* kModes = "one of 'ae', 'ss', 'ms', 'dvr'";
constexpr const char* kTransmittances = "'ratio' or 'ubrm'";
constexpr const char* kControls = "'none' or 'minorant'";

// A keyword's value as T; a value of another type is one TypeError naming the keyword, what it
// takes and what it got.
template <typename T>
T keywordArg(const py::handle& o, const char* name, const char* expected) {
    if constexpr (std::is_arithmetic_v<T>) {
        // pybind11 would take True as 1 and a numpy array of one element as a number.
        if (py::isinstance<py::bool_>(o) && !std::is_same_v<T, bool>)
            throw py::type_error(strCat(name, ": expected ", expected, ", got ", shortRepr(o)));
    }
    try {
        return o.cast<T>();
    } catch (const std::exception&) {  // cast_error, or reference_cast_error for None as a class
        throw py::type_error(strCat(name, ": expected ", expected, ", got ", shortRepr(o)));
    }
}

// An amrvk error raised while handling `keyword`, with the keyword in front where the message does
// not name it already.
template <typename F>
auto forKeyword(const char* keyword, F f) {
    try {
        return f();
    } catch (const Error& e) {
        const std::string m = python::keywordMessage(e.what());
        throw py::value_error(m.rfind(keyword, 0) == 0 ? m : strCat(keyword, ": ", m));
    }
}

// ---- Contexts: one per device choice, shared by the renderers that name it ---------------------

std::shared_ptr<gpu::Context> contextFor(const gpu::ContextOptions& o) {
    static std::mutex mutex;
    static std::map<std::string, std::weak_ptr<gpu::Context>> contexts;
    const std::string key = o.device + "|" + std::to_string(o.validation) + "|" + std::to_string(o.gpuTimeoutSeconds) +
                            "|" + std::to_string(o.samplesPerInvocation) + "|" + std::to_string(o.pathRegeneration);
    std::lock_guard lock(mutex);
    if (auto ctx = contexts[key].lock()) return ctx;
    auto ctx = std::make_shared<gpu::Context>(o);
    contexts[key] = ctx;
    return ctx;
}

// ---- numpy helpers ---------------------------------------------------------------------------

// A numpy array's element (i, k) as T, whatever its strides (non-contiguous and read-only arrays
// are only read).
template <typename T>
T element(const py::array& a, py::ssize_t i, py::ssize_t k = 0) {
    const char* p = static_cast<const char*>(a.data()) + i * a.strides(0) + (a.ndim() > 1 ? k * a.strides(1) : 0);
    const py::dtype dt = a.dtype();
    switch (dt.kind()) {
        case 'i':
            if (dt.itemsize() == 8) return T(*reinterpret_cast<const int64_t*>(p));
            if (dt.itemsize() == 4) return T(*reinterpret_cast<const int32_t*>(p));
            if (dt.itemsize() == 2) return T(*reinterpret_cast<const int16_t*>(p));
            return T(*reinterpret_cast<const int8_t*>(p));
        case 'u':
            if (dt.itemsize() == 8) return T(*reinterpret_cast<const uint64_t*>(p));
            if (dt.itemsize() == 4) return T(*reinterpret_cast<const uint32_t*>(p));
            if (dt.itemsize() == 2) return T(*reinterpret_cast<const uint16_t*>(p));
            return T(*reinterpret_cast<const uint8_t*>(p));
        case 'f':
            if (dt.itemsize() == 8) return T(*reinterpret_cast<const double*>(p));
            if (dt.itemsize() == 4) return T(*reinterpret_cast<const float*>(p));
            break;
        default:
            break;
    }
    throw py::type_error("unsupported array dtype " + std::string(py::str(py::handle(dt))));
}

// An integer array's element (i, k): its value where it fits int64 (a uint64 above INT64_MAX does
// not), and its text as read, for messages (never a uint64 shown as a negative number).
struct WholeNumber {
    std::optional<int64_t> value;
    std::string text;
};
WholeNumber wholeElement(const py::array& a, py::ssize_t i, py::ssize_t k = 0) {
    if (a.dtype().kind() == 'u' && a.dtype().itemsize() == 8) {
        const uint64_t u = element<uint64_t>(a, i, k);
        return {u <= uint64_t(INT64_MAX) ? std::optional<int64_t>(int64_t(u)) : std::nullopt, std::to_string(u)};
    }
    const int64_t v = element<int64_t>(a, i, k);
    return {v, std::to_string(v)};
}

// `a` as an array, checked: `kinds` are the dtype kinds allowed ("iu", "iuf"), ndim and the
// length of axis 1 where it has two.
py::array checkedArray(const py::object& obj, const char* name, const char* kinds, int ndim, py::ssize_t columns = 0) {
    if (!py::isinstance<py::array>(obj))
        throw py::type_error(std::string(name) + ": expected a numpy array, got " +
                             std::string(py::str(obj.get_type().attr("__name__"))));
    py::array a = py::reinterpret_borrow<py::array>(obj);
    const char kind = a.dtype().kind();
    if (std::string(kinds).find(kind) == std::string::npos || (kind == 'f' && a.dtype().itemsize() < 4) ||
        a.dtype().itemsize() > 8)
        throw py::type_error(std::string(name) + ": dtype " + std::string(py::str(py::handle(a.dtype()))) + " is not " +
                             (std::string(kinds) == "iu" ? "an integer type" : "an integer or float32/float64 type"));
    if (a.ndim() != ndim || (ndim == 2 && a.shape(1) != columns))
        throw py::value_error(std::string(name) + ": expected shape " + (ndim == 1 ? "(N,)" : "(N, " + std::to_string(columns) + ")") +
                              ", got " + std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()))))));
    return a;
}

glm::dvec3 vec3(const std::vector<double>& v, const char* name) {
    if (v.size() != 3) throw py::value_error(std::string(name) + ": expected 3 numbers, got " + std::to_string(v.size()));
    for (double x : v)
        if (!std::isfinite(x)) throw py::value_error(std::string(name) + ": " + std::to_string(x) + " is not finite");
    return {v[0], v[1], v[2]};
}

std::vector<double> list3(glm::dvec3 v) { return {v.x, v.y, v.z}; }

// A keyword's 3 finite numbers (a list, tuple or array); one line naming it otherwise.
glm::dvec3 vec3Arg(const py::handle& o, const char* name) {
    return vec3(keywordArg<std::vector<double>>(o, name, kThree), name);
}

// Numbers in __repr__s: 4 significant digits ("1.235e-27", "0.5"); vectors as "(x, y, z)".
std::string g4(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}
std::string g4(glm::dvec3 v) { return "(" + g4(v.x) + ", " + g4(v.y) + ", " + g4(v.z) + ")"; }

// crop=(lo, hi) (world; None: no crop) and clip=[(point, normal), ...] (world), as --crop and --clip.
std::optional<scene::CropBox> cropOf(const py::object& o) {
    if (o.is_none()) return std::nullopt;
    const auto corners = keywordArg<std::pair<std::vector<double>, std::vector<double>>>(o, "crop", "(lo, hi): two lists of 3 numbers, or None");
    return scene::CropBox{vec3(corners.first, "crop lo"), vec3(corners.second, "crop hi")};
}
std::vector<scene::ClipPlane> clipsOf(const py::object& o) {
    std::vector<scene::ClipPlane> out;
    if (o.is_none()) return out;
    for (const auto& [point, normal] : keywordArg<std::vector<std::pair<std::vector<double>, std::vector<double>>>>(
             o, "clip", "a list of (point, normal) pairs of 3 numbers each"))
        out.push_back({vec3(point, "clip point"), vec3(normal, "clip normal")});
    return out;
}
py::object cropObject(const std::optional<scene::CropBox>& c) {
    return c ? py::object(py::make_tuple(list3(c->lo), list3(c->hi))) : py::object(py::none());
}
py::list clipObject(const std::vector<scene::ClipPlane>& clips) {
    py::list out;
    for (const scene::ClipPlane& c : clips) out.append(py::make_tuple(list3(c.point), list3(c.normal)));
    return out;
}

// An image as numpy float32 (H, W, 4), row 0 = top.
py::array_t<float> imageArray(const Image& image) {
    py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(4)});
    std::memcpy(out.mutable_data(), image.pixels.data(), image.pixels.size() * sizeof(glm::vec4));
    return out;
}

// ---- Volume ----------------------------------------------------------------------------------

struct PyVolume {
    std::shared_ptr<const scene::Volume> volume;
    session::Session source;  // input, read options and field (sessions name them); input "" for arrays
    std::vector<NamedPath> files;  // the files the data set was read from (none for arrays and yt)
    std::string madeBy = "file";   // "file", "arrays" or "yt" (set by from_yt)

    // Why a session cannot name this volume's file ("" where it has one).
    std::string noFileReason() const {
        if (madeBy == "yt")
            return strCat("save_session: this volume came from yt (", volume->model.source, "), not from a file amrvk "
                          "reads: a session needs one (amrvk.Volume(path, field=...) reads Enzo, AMReX, Chombo, RAMSES "
                          "and ExaBrick files), or save the image instead");
        return "save_session: this volume was made from arrays, not read from a file: a session needs a file "
               "(write the cells with amrvk convert, or save the image instead)";
    }

    // "Volume(DD0018, field 'Density' [g/cm**3], 137502 cells on 4 levels, values 1.2e-31..4.5e-27,
    // world (0, 0, 0)..(1, 1, 1))": what a scientist checks first.
    std::string repr() const {
        const scene::Volume& v = *volume;
        const size_t levels = std::count_if(v.summary.cellsPerLevel.begin(), v.summary.cellsPerLevel.end(),
                                            [](uint64_t n) { return n > 0; });
        const std::string& units = v.field().units;
        return strCat("Volume(", v.model.source, ", field '", v.field().name, "'", units.empty() ? "" : " [" + units + "]",
                      ", ", v.model.cellCount(), " cells on ", levels, levels == 1 ? " level" : " levels", ", values ",
                      g4(v.valueLo()), "..", g4(v.valueHi()), ", world ", g4(v.worldLo()), "..", g4(v.worldHi()), ")");
    }

    py::dict summary() const {
        const scene::Volume& v = *volume;
        py::dict d;
        d["source"] = v.model.source;
        d["field"] = v.field().name;
        d["units"] = v.field().units;
        d["cells"] = v.model.cellCount();
        std::vector<uint64_t> perLevel = v.summary.cellsPerLevel;
        d["cells_per_level"] = perLevel;  // index = level, 0 = finest
        d["finest_level"] = v.minLevel();
        d["coarsest_level"] = v.summary.maxLevel;
        d["value_range"] = py::make_tuple(v.valueLo(), v.valueHi());
        d["volume_weighted_mean"] = v.fieldStats.volumeWeightedMean;
        d["world_lo"] = list3(v.worldLo());
        d["world_hi"] = list3(v.worldHi());
        d["bricks"] = v.bricks.bricks.size();
        d["host_bytes"] = v.modelBytes() + v.bricks.memoryBytes();
        return d;
    }
};

std::shared_ptr<PyVolume> volumeFromFile(const fs::path& path, const std::string& field, const std::string& format,
                                         const std::string& nan, const std::optional<std::vector<int>>& dims,
                                         const std::string& type, double threshold, const std::string& scale,
                                         double logFloor) {
    auto v = std::make_shared<PyVolume>();
    session::Session& s = v->source;
    s.input = path.string();
    s.field = field;
    s.read.format = format;
    s.read.nanPolicy = forKeyword("nan", [&] { return amr::parseNanPolicy(nan); });
    if (dims) {
        if (dims->size() != 3) throw py::value_error("dims: expected 3 integers");
        for (int d : *dims)
            if (d < 1 || d > amr::kMaxRawDim)
                throw py::value_error(strCat("dims: ", d, " is outside [1, ", amr::kMaxRawDim, "]"));
        s.read.rawDims = {(*dims)[0], (*dims)[1], (*dims)[2]};
    }
    s.read.rawType = type;
    s.read.rawThreshold = threshold;
    s.read.scale = forKeyword("scale", [&] { return amr::parseFieldScale(scale); });
    s.read.logFloor = logFloor;
    {
        py::gil_scoped_release release;
        InputFileRecorder recorder;
        v->volume = session::loadVolume(s);
        v->files = recorder.files("the volume's data");
    }
    s.field = v->volume->field().name;
    s.read.scale = amr::scaleOf(v->volume->model);  // auto: what the field decided
    return v;
}

std::shared_ptr<PyVolume> volumeFromArrays(const py::object& lowerObj, const py::object& levelObj,
                                           const py::object& valuesObj, const std::string& field,
                                           const std::vector<double>& origin, const std::vector<double>& spacing,
                                           const std::string& nan, const std::string& units, const std::string& source) {
    const py::array lower = checkedArray(lowerObj, "lower", "iu", 2, 3);
    const py::array level = checkedArray(levelObj, "level", "iu", 1);
    const py::array values = checkedArray(valuesObj, "values", "iuf", 1);
    const py::ssize_t n = lower.shape(0);
    if (level.shape(0) != n || values.shape(0) != n)
        throw py::value_error("lower, level and values must have the same length (got " + std::to_string(n) + ", " +
                              std::to_string(level.shape(0)) + ", " + std::to_string(values.shape(0)) + ")");
    // amrvk::Error, not py::value_error: the name is the caller's and is shown escaped, on one line.
    AMRVK_CHECK(!field.empty() && field.find('/') == std::string::npos, "field: '", field, "' is not a field name");
    amr::Model m;
    m.format = "arrays";
    m.source = source;
    m.voxelToWorld.origin = vec3(origin, "origin");
    m.voxelToWorld.scale = vec3(spacing, "spacing");
    for (int a = 0; a < 3; ++a)
        if (!(m.voxelToWorld.scale[a] > 0)) throw py::value_error("spacing: every component must be > 0");
    checkAllocation(uint64_t(n) * (sizeof(amr::Cell) + sizeof(float)), "the cells");
    m.cells.resize(size_t(n));
    m.fields.push_back({field, std::vector<float>(size_t(n)), units});
    m.availableFields = {field};
    // One copy, numpy -> model; coordinates checked to fit the 32-bit cell format.
    for (py::ssize_t i = 0; i < n; ++i) {
        amr::Cell cell;
        for (int a = 0; a < 3; ++a) {
            const WholeNumber c = wholeElement(lower, i, a);
            if (!c.value || *c.value < INT32_MIN || *c.value > INT32_MAX)
                throw py::value_error("lower[" + std::to_string(i) + "]: " + c.text + " does not fit in 32 bits");
            cell.lower[a] = int32_t(*c.value);
        }
        const WholeNumber l = wholeElement(level, i);
        if (!l.value || *l.value < 0 || *l.value > amr::kMaxLevel)
            throw py::value_error("level[" + std::to_string(i) + "]: " + l.text + " is outside [0, " +
                                  std::to_string(amr::kMaxLevel) + "] (0 = finest)");
        cell.level = int32_t(*l.value);
        m.cells.set(size_t(i), cell);
        m.fields[0].values[size_t(i)] = element<float>(values, i);
    }
    auto v = std::make_shared<PyVolume>();
    v->madeBy = "arrays";
    v->source.field = field;
    v->source.read.nanPolicy = forKeyword("nan", [&] { return amr::parseNanPolicy(nan); });
    const amr::NanPolicy policy = v->source.read.nanPolicy;
    py::gil_scoped_release release;
    v->volume = scene::makeVolume(amr::checkedModel(std::move(m), policy), field);  // the readers' checks
    return v;
}

// ---- Transfer function -----------------------------------------------------------------------

// A range a user gives (preset, rescaled), as --tf-range takes it: finite in float32, lo below hi.
void checkTfRange(float lo, float hi, const char* what) {
    if (!std::isfinite(lo) || !std::isfinite(hi))
        throw py::value_error(strCat(what, ": ", lo, " ", hi, " is not a finite float32 range"));
    if (!(lo < hi)) throw py::value_error(strCat(what, ": ", lo, " ", hi, ": LO must be below HI"));
}

struct PyTf {
    scene::TfChannels channels;
    static PyTf preset(const std::string& name, float lo, float hi) {
        checkTfRange(lo, hi, "preset");
        return {scene::TfChannels::split(scene::makePreset(name, lo, hi))};
    }
    // Fitted to a volume's data as `amrvk render --tf NAME` fits it (spiky and foggy over its percentiles,
    // layers over its volume histogram).
    static PyTf presetFor(const std::string& name, const PyVolume& v) {
        return {scene::TfChannels::split(scene::makePreset(name, v.volume->percentiles, v.volume->volumeHistogram))};
    }
    static PyTf fromFile(const fs::path& path, const std::string& preset, float lo, float hi) {
        return {scene::TfChannels::split(scene::loadTransferFunction(path.string(), lo, hi, preset))};
    }
    static PyTf fromNodes(const py::object& positionsObj, const py::object& colorsObj, const std::string& name) {
        const py::array p = checkedArray(positionsObj, "positions", "iuf", 1);
        const py::array c = checkedArray(colorsObj, "colors", "iuf", 2, 4);
        if (p.shape(0) != c.shape(0)) throw py::value_error("positions and colors must have the same length");
        std::vector<float> pos(size_t(p.shape(0)));
        std::vector<glm::vec4> col(pos.size());
        for (py::ssize_t i = 0; i < p.shape(0); ++i) {
            pos[size_t(i)] = element<float>(p, i);
            for (int k = 0; k < 4; ++k) col[size_t(i)][k] = element<float>(c, i, k);
        }
        return {scene::TfChannels::split(scene::TransferFunction(pos, col, name))};  // validated
    }
    scene::TransferFunction merged() const { return channels.merged(); }
    PyTf rescaled(float lo, float hi) const {
        checkTfRange(lo, hi, "rescaled");
        return {scene::TfChannels::split(merged().rescaled(lo, hi))};
    }
    py::tuple range() const {
        const scene::TransferFunction tf = merged();
        return py::make_tuple(tf.firstPosition(), tf.lastPosition());
    }
    py::tuple nodes() const {
        const scene::TransferFunction tf = merged();
        py::array_t<float> pos(py::ssize_t(tf.nodeCount()));
        py::array_t<float> col({py::ssize_t(tf.nodeCount()), py::ssize_t(4)});
        std::memcpy(pos.mutable_data(), tf.positions().data(), tf.nodeCount() * sizeof(float));
        std::memcpy(col.mutable_data(), tf.colors().data(), tf.nodeCount() * sizeof(glm::vec4));
        return py::make_tuple(pos, col);
    }
    py::array_t<float> evaluate(const py::object& valuesObj) const {
        const py::array v = checkedArray(valuesObj, "values", "iuf", 1);
        const scene::TransferFunction tf = merged();
        py::array_t<float> out({v.shape(0), py::ssize_t(4)});
        auto o = out.mutable_unchecked<2>();
        for (py::ssize_t i = 0; i < v.shape(0); ++i) {
            const glm::vec4 c = tf.evaluate(element<float>(v, i));
            for (int k = 0; k < 4; ++k) o(i, k) = c[k];
        }
        return out;
    }
    std::string json() const { return scene::paraViewPresetJson(channels); }
    // "TransferFunction('ramp', 5 nodes over [-31, -26.5], alpha up to 1)".
    std::string repr() const {
        const scene::TransferFunction tf = merged();
        float alpha = 0;
        for (const glm::vec4& c : tf.colors()) alpha = std::max(alpha, c.a);
        return strCat("TransferFunction('", channels.name, "', ", tf.nodeCount(), " nodes over [", g4(tf.firstPosition()),
                      ", ", g4(tf.lastPosition()), "], alpha up to ", g4(alpha), ")");
    }
    void save(const fs::path& path) const { writeFileAtomic(path, json()); }
};

// ---- Renderer --------------------------------------------------------------------------------

class PyRenderer {
public:
    PyRenderer(std::shared_ptr<gpu::Context> ctx, std::shared_ptr<const scene::Volume> volume,
               const session::PictureDescription& d, const fs::path& shaderDir, bool quiet,
               std::vector<NamedPath> dataFiles)
        : mCtx(std::move(ctx)), mDataFiles(std::move(dataFiles)) {
        picture::Options o;
        o.shaders = gpu::ShaderLibrary(shaderDir);
        if (!quiet) o.note = [](const std::string& line) { std::fprintf(stderr, "amrvk: %s\n", line.c_str()); };
        py::gil_scoped_release release;
        mPicture = picture::makePicture(*mCtx, std::move(volume), d, o);
    }

    // ---- the picture ----
    session::Session session() const { return open().session(); }
    const scene::RenderSettings& settings() const { return open().renderer->settings(); }
    scene::Camera camera() const { return settings().camera; }
    void setCamera(const scene::Camera& c) { editSettings([&](scene::RenderSettings& s) { s.camera = c; }); }
    PyTf tf() const { return {session().tf}; }
    void setTf(const PyTf& tf) {
        locked([&] { mPicture.setTransferFunction(tf.channels); });
    }
    std::string tfColors() const { return scene::tfColorsName(session().tfColors); }
    void setTfColors(const py::object& o) {
        const scene::TfColors c =
            scene::parseTfColors(keywordArg<std::string>(o, "tf_colors", "'srgb' or 'linear'"), "tf_colors");
        locked([&] { mPicture.setTfColors(c); });
    }
    // Settings edited by `edit` on a copy, validated, then applied (the renderer redoes what the
    // invalidation rule says); an invalid value changes nothing.
    template <typename Edit>
    void editSettings(Edit edit) {
        // Read under the lock: a first frame being made in another thread (the widget's) holds it
        // while the renderer is switched to dvr; a copy read then wrote dvr back for good.
        scene::RenderSettings s = onDevice([](render::Renderer& r) { return r.settings(); });
        edit(s);
        scene::validateSettings(s);
        locked([&] { mPicture.renderer->setSettings(s); });
    }
    void setStructure(const std::optional<std::string>& traversal, const std::optional<std::string>& sampler,
                      const std::optional<std::string>& backend, const std::optional<std::string>& grid,
                      std::optional<uint32_t> kdLeaves, const std::optional<std::string>& subMajorants) {
        scene::StructureConfig c = open().described.structure;
        if (traversal) c.traversal = scene::parseTraversal(*traversal);
        if (sampler) c.sampler = scene::parseSampler(*sampler);
        if (backend) c.backend = scene::parseBackend(*backend);
        if (grid) c.grid = *grid;
        if (kdLeaves) c.kdLeaves = *kdLeaves;
        if (subMajorants) c.subMajorants = scene::parseSubMajorants(*subMajorants, "sub_majorants");
        scene::StructureConfig resolved = c;
        picture::resolveStructure(*mCtx, resolved);  // validated before anything is built
        locked([&] { mPicture.setStructure(c, resolved); });
    }
    py::dict structure() const {
        const scene::StructureConfig& c = open().renderer->config();
        py::dict d;
        d["traversal"] = scene::traversalName(c.traversal);
        d["sampler"] = scene::samplerName(c.sampler);
        d["backend"] = scene::backendName(c.backend);
        d["backend_requested"] = scene::backendName(session().structure.backend);
        d["grid"] = c.grid;
        d["kd_leaves"] = c.kdLeaves;
        d["sub_majorants"] = scene::subMajorantsName(c.subMajorants);
        return d;
    }

    // ---- accumulation ----
    void reset() { locked([&] { mPicture.renderer->resetAccumulation(); }); }
    uint32_t spp() const { return open().renderer->accumulatedSpp(); }
    // Adds n samples per pixel to the current estimate in chunks of about a quarter second, serving
    // signals (Ctrl-C) and `progress(done, n)` between chunks with the GIL held, and other threads'
    // calls in turn (FairMutex: a widget on the same renderer goes on refreshing).
    void accumulate(const py::object& count, const py::object& progress) {
        accumulateChunks(countArg(count, "n"), progress, false);
    }
    // The chunks of accumulate(), and of render() (`restart`: the estimate reset under the first
    // chunk's lock, so that it ends with exactly n samples). The call counts the image's samples, not
    // its own: samples another thread adds meanwhile count, and an edit from another thread that
    // restarts the estimate restarts the count, so the call ends with the image at n samples of the
    // picture as it then is (issue 52, point 15).
    void accumulateChunks(uint32_t n, const py::object& progress, bool restart) {
        open();
        uint32_t target = 0;             // the image's samples when this call is done
        std::optional<uint64_t> resets;  // the estimate's resets when this call last worked on it
        for (uint32_t done = 0; done < n;) {
            uint32_t spp = 0;
            {
                py::gil_scoped_release release;
                std::lock_guard lock(mMutex);
                if (mClosed) break;  // closed by another thread between chunks
                render::Renderer& r = *mPicture.renderer;
                if (restart && !resets) r.resetAccumulation();
                if (!resets) {
                    target = restart ? n : r.accumulatedSpp() + n;
                } else if (*resets != r.updateCounts().accumulationResets) {
                    target = n;  // restarted meanwhile
                }
                if (r.accumulatedSpp() < target) accumulateChunk(r, target - r.accumulatedSpp());
                resets = r.updateCounts().accumulationResets;
                spp = r.accumulatedSpp();
            }
            const uint32_t was = done;
            done = n - (target - std::min(spp, target));
            requireNoValidationErrors();
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (!progress.is_none() && done > was) progress(done, n);
        }
    }
    // One chunk of at most `most` samples per pixel (the device lock held): whole samples where
    // they fit about a quarter second, else tiles of rows.
    void accumulateChunk(render::Renderer& r, uint32_t most) {
        const uint32_t height = uint32_t(r.settings().height);
        uint32_t rows = 0;
        Timer t;
        const double perSample = mSecondsPerRow * double(height);
        if (mSecondsPerRow > 0 && perSample < kChunkSeconds && r.rowsDone() == 0) {
            const uint32_t k = std::min(most, uint32_t(std::clamp(kChunkSeconds / perSample, 1.0, 64.0)));
            r.accumulate(k, {}, k);
            rows = k * height;
        } else {
            // Tiles of rows: the first sample (its cost unknown), and samples slower than a chunk.
            rows = mSecondsPerRow > 0 ? uint32_t(std::clamp(kChunkSeconds / mSecondsPerRow, 1.0, double(height)))
                                      : std::min(height, 8u);
            rows = std::min(rows, height - r.rowsDone());
            r.accumulateRows(rows);
        }
        const double perRow = t.seconds() / double(std::max(rows, 1u));
        mSecondsPerRow = mSecondsPerRow > 0 ? 0.5 * (mSecondsPerRow + perRow) : perRow;
    }
    py::array_t<float> render(const py::object& spp, const py::object& progress, const py::object& legend,
                              const py::object& until) {
        const bool withLegend = !legend.is_none() && keywordArg<bool>(legend, "legend", "True, False or None");
        const uint32_t n = spp.is_none() ? (session().spp > 0 ? session().spp : 64) : countArg(spp, "spp");
        if (until.is_none()) {
            accumulateChunks(n, progress, true);
            return imageArray(picture(withLegend));
        }
        reset();
        // As render --until-error: checks at scene::kFirstNoiseCheckSpp and at each doubling, spp the cap.
        const double target = keywordArg<double>(until, "until", "a number in (0, 1]");
        if (!(target > 0 && target <= 1)) throw py::value_error(strCat("until: ", formatDouble(target), " is outside (0, 1]"));
        if (n < 2) throw py::value_error(strCat("until: needs spp of at least 2 as its cap (got ", n, ")"));
        for (uint32_t k; (k = scene::nextNoiseBatch(output(), n, target)) > 0;) accumulate(py::int_(k), progress);
        return imageArray(picture(withLegend));
    }
    // The image's noise so far (scene::meanRelativeError); None below 2 spp.
    py::object noise() const {
        const scene::RenderOutput out = output();
        return out.spp < 2 ? py::object(py::none()) : py::object(py::float_(scene::meanRelativeError(out)));
    }
    scene::RenderOutput output() const {
        return onDevice([](render::Renderer& r) { return r.output(); });
    }
    // ---- the colour legend (session/legend_image.h: the CLI's --legend drawing) ----
    // `legend` True/False, or None for the session's setting (Renderer(legend=True), .legend).
    bool legendWanted(const py::object& legend) const {
        return legend.is_none() ? session().legend.show : keywordArg<bool>(legend, "legend", "True, False or None");
    }
    // The picture so far, with the legend drawn at its side or over it when `withLegend`. Before
    // any sample it is the first frame (firstFrame), not a black image.
    Image picture(bool withLegend) const { return pictureOf(output(), withLegend); }
    Image pictureOf(const scene::RenderOutput& out, bool withLegend) const {
        Image mean = out.spp > 0 ? out.mean : firstFrame().image;  // before any sample: the first frame
        if (!withLegend) return mean;
        const session::Session s = session();
        if (!mFont || !(mFontFor == s.legend.font)) {
            mFont = session::openLegendFont(s.legend);
            mFontFor = s.legend.font;
        }
        const std::string& units = mPicture.volume->field().units;
        session::checkLegendFits(s, units, *mFont);
        return session::drawLegend(mean, session::legendContent(s, units), s.legend.place, *mFont);
    }
    session::Legend legend() const { return session().legend; }
    template <typename Edit>
    void editLegend(Edit edit) {
        session::Legend l = legend();
        edit(l);
        session::checkLegendText(l);
        locked([&] { mPicture.described.legend = l; });
    }

    // Arrays (image, render) are the picture alone unless legend=True: they match variance()'s shape.
    py::array_t<float> image(const py::object& legend) const {
        return imageArray(picture(!legend.is_none() && keywordArg<bool>(legend, "legend", "True, False or None")));
    }
    py::array_t<float> variance() const {
        const scene::RenderOutput out = output();
        if (out.spp < 2) throw py::value_error("variance needs at least 2 samples per pixel (have " + std::to_string(out.spp) + ")");
        const std::vector<float> v = scene::varianceOfMean(out);
        py::array_t<float> a({py::ssize_t(out.mean.height), py::ssize_t(out.mean.width), py::ssize_t(3)});
        std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(float));
        return a;
    }
    py::object stats() const {
        const scene::RenderOutput out = output();
        const std::string text = picture::renderStats(mPicture, out).dump();
        return py::module_::import("json").attr("loads")(text);
    }
    std::vector<std::string> notes() const { return open().report.notes; }
    // Outputs never replace a file the renderer's data set was read from (as the CLI refuses
    // -o onto an input); everything else is checkOutputs' and AtomicFileWriter's policy.
    // legend None: drawn into PNGs where the session has it on (other formats as they are, as the
    // CLI does with a session's legend); True: a PNG is required.
    void save(const fs::path& path, const py::object& legend) const {
        checkOutputs({{"save", path}}, mDataFiles);
        std::string ext = path.extension().string();
        std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
        if (!legend.is_none() && legendWanted(legend) && ext != ".png")
            throw py::value_error("legend: only PNG images get a legend (save to a .png, or legend=False)");
        writeImage(path, picture(legendWanted(legend) && ext == ".png"));
    }
    // One state of the image, read together (the widget's status counted samples in one call and
    // showed the image of another: "16/64" over 72): (spp, PNG bytes, mean standard error or None);
    // (0, None, None) while the image has no sample (no first frame is made for it).
    py::tuple snapshot(const py::object& legend) const {
        const scene::RenderOutput out = output();
        if (out.spp == 0) return py::make_tuple(0, py::none(), py::none());
        const std::vector<uint8_t> bytes = pngBytes(pictureOf(out, legendWanted(legend)));
        return py::make_tuple(out.spp, py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                              out.spp >= 2 ? py::object(py::float_(meanStandardError(out))) : py::object(py::none()));
    }
    py::bytes png(const py::object& legend) const {
        const std::vector<uint8_t> bytes = pngBytes(picture(legendWanted(legend)));
        return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    }
    void saveSession(const fs::path& path) const {
        session::Session s = session();
        s.input = s.input.empty() ? s.input : fs::absolute(s.input).lexically_normal().string();
        if (s.input.empty()) throw py::value_error(noSessionReason);
        checkOutputs({{"save_session", path}}, mDataFiles);
        session::saveSession(path, s);
    }
    void close() {
        std::lock_guard lock(mMutex);
        mPicture.renderer.reset();
        mPicture.volume.reset();
        mClosed = true;
    }
    bool closed() const { return mClosed; }
    // "Renderer(DD0018 'Density', 256x256 ms, tf 'ramp' over [-31, -26.5], density_scale 1, 16 spp so
    // far, mean standard error 0.0021, grid-dda/grid/sw)".
    std::string repr() const {
        if (mClosed || !mPicture.renderer) return "Renderer(closed)";
        const session::Session s = session();
        const scene::RenderSettings& rs = settings();
        const scene::TransferFunction tf = s.tf.merged();
        const scene::StructureConfig& c = mPicture.renderer->config();
        std::string noise;
        const scene::RenderOutput out = output();
        if (out.spp >= 2) noise = ", mean standard error " + g4(meanStandardError(out));
        const picture::FirstFrame* f = shownFirstFrame();
        const std::string first = f ? strCat(" (shown: the dvr first frame, ", picture::kFirstFrameSpp, " spp, dt ",
                                             g4(f->dt), ", noise ", g4(f->noise), ")")
                                    : std::string();
        return strCat("Renderer(", mPicture.volume->model.source, " '", mPicture.volume->field().name, "', ", rs.width,
                      "x", rs.height, " ", scene::modeName(rs.mode), ", tf '", s.tf.name, "' over [", g4(tf.firstPosition()),
                      ", ", g4(tf.lastPosition()), "], density_scale ", g4(rs.densityScale), ", ", out.spp,
                      " spp so far", noise, first, ", ", scene::traversalName(c.traversal), "/", scene::samplerName(c.sampler),
                      "/", scene::backendName(c.backend), ")");
    }
    std::string noSessionReason;  // why save_session cannot name a file (a volume from arrays or yt)

    // The first frame (picture/first_frame.h): what a renderer with no sample shows (inline,
    // image(), save()): the same picture ray-marched, clean in about a second where path tracing a
    // haze is still grainy at 16 spp (docs/python.md section 1). The renderer keeps its own mode
    // and no sample, so render() and accumulate() path-trace from scratch and refine it. Kept
    // until an edit resets the image.
    struct ShownFirstFrame {
        picture::FirstFrame frame;
        uint64_t resets = 0;  // the renderer's accumulationResets after it was made
    };
    // Whether the last first frame made is of the renderer's current picture (no edit since).
    bool firstFrameCurrent() const {
        return mFirstFrame && mFirstFrame->resets == mPicture.renderer->updateCounts().accumulationResets;
    }
    const picture::FirstFrame& firstFrame() const {
        open();
        if (firstFrameCurrent()) return mFirstFrame->frame;
        onDevice([&](render::Renderer& r) {
            ShownFirstFrame shown{picture::renderFirstFrame(r)};
            requireNoValidationErrors();
            shown.resets = r.updateCounts().accumulationResets;
            mFirstFrame = std::move(shown);
        });
        return mFirstFrame->frame;
    }
    // The first frame shown while the renderer holds no sample: {"mode", "spp", "dt", "noise",
    // "gpu_seconds", "frames"}; None before one is shown and once the image has samples.
    const picture::FirstFrame* shownFirstFrame() const {
        if (mClosed || !mPicture.renderer || mPicture.renderer->accumulatedSpp() > 0 || !firstFrameCurrent())
            return nullptr;
        return &mFirstFrame->frame;
    }
    py::object firstFrameInfo() const {
        const picture::FirstFrame* f = shownFirstFrame();
        if (!f) return py::none();
        py::dict d;
        d["mode"] = "dvr";
        d["spp"] = picture::kFirstFrameSpp;
        d["dt"] = f->dt;
        d["noise"] = f->noise;
        d["gpu_seconds"] = f->gpuSeconds;
        d["frames"] = f->frames;
        return d;
    }

private:
    static constexpr double kChunkSeconds = 0.25;

    // The mean over pixels and channels of the standard error of the mean (out.spp >= 2).
    static double meanStandardError(const scene::RenderOutput& out) {
        const std::vector<float> var = scene::varianceOfMean(out);
        double sum = 0;
        for (float x : var) sum += std::sqrt(std::max(x, 0.0f));
        return sum / double(std::max<size_t>(var.size(), 1));
    }

    // As the CLI: with validation on, any validation error fails the call (its message went to
    // stderr when it happened).
    void requireNoValidationErrors() const {
        AMRVK_CHECK(mCtx->validationErrors() == 0, "Vulkan validation reported ", mCtx->validationErrors(),
                    " error(s); last: ", mCtx->lastValidationMessage());
    }

    const picture::Picture& open() const {
        if (mClosed || !mPicture.renderer) throw py::value_error("the renderer is closed");
        return mPicture;
    }
    template <typename F>
    void locked(F f) {
        onDevice([&](render::Renderer&) { f(); });
    }
    // f(renderer) with the GIL released and the device lock held, the renderer checked open under
    // the lock: close() from another thread takes the same lock, so it cannot free the renderer
    // between the check and the call (it did: SIGSEGV in PathTracePass::read).
    template <typename F>
    std::invoke_result_t<F, render::Renderer&> onDevice(F f) const {
        open();
        py::gil_scoped_release release;
        std::lock_guard lock(mMutex);
        if (mClosed || !mPicture.renderer) throw py::value_error("the renderer is closed");
        return f(*mPicture.renderer);
    }

    std::shared_ptr<gpu::Context> mCtx;  // outlives the picture (declared first)
    std::vector<NamedPath> mDataFiles;   // outputs refuse these
    picture::Picture mPicture;
    mutable python::FairMutex mMutex;     // one device call at a time, in the order they came (the GIL is
                                          // released around them)
    mutable std::unique_ptr<Font> mFont;  // the legend's, opened when first drawn
    mutable std::string mFontFor;         // the legend.font it was opened for
    double mSecondsPerRow = 0;  // measured, for chunk sizes
    mutable std::optional<ShownFirstFrame> mFirstFrame;  // the last first frame made (firstFrame)
    bool mClosed = false;
};

// The description a Python Renderer(...) call makes, as `amrvk render` makes one from its options.
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
    static const char* kKnown[] = {"width",    "height",  "mode",    "spp",     "seed",          "density_scale",
                                   "g",        "ambient", "background", "lights", "dt",          "dvr_shading", "transmittance", "control_extinction",
                                   "traversal", "sampler", "backend", "grid",    "kd_leaves",     "dense_max_mib", "sub_majorants",
                                   "device",   "validation", "shader_dir", "gpu_timeout", "samples_per_invocation", "path_regeneration",
                                   "quiet",    "fov",     "tf_range", "crop",    "clip",   "legend",
                                   "legend_place", "legend_title", "legend_units", "tf_colors"};
    for (const auto& item : kw) {
        const std::string key = py::str(item.first);
        if (std::find(std::begin(kKnown), std::end(kKnown), key) == std::end(kKnown))
            throw py::type_error("Renderer() got an unexpected keyword argument '" + key + "'");
    }
    if (auto o = take("width")) rs.width = int(wholeArg(*o, "width", 1, scene::kMaxImageSide));
    if (auto o = take("height")) rs.height = int(wholeArg(*o, "height", 1, scene::kMaxImageSide));
    if (auto o = take("mode")) rs.mode = scene::parseMode(keywordArg<std::string>(*o, "mode", kModes));
    if (auto o = take("spp")) s.spp = countArg(*o, "spp");
    if (auto o = take("seed")) rs.seed = uint32_t(wholeArg(*o, "seed", 0, UINT32_MAX));
    if (auto o = take("density_scale")) rs.densityScale = keywordArg<double>(*o, "density_scale", kNumber);
    if (auto o = take("g")) rs.g = keywordArg<double>(*o, "g", kNumber);
    if (auto o = take("ambient")) rs.ambient = vec3(keywordArg<std::vector<double>>(*o, "ambient", kThree), "ambient");
    if (auto o = take("background")) rs.background = vec3(keywordArg<std::vector<double>>(*o, "background", kThree), "background");
    if (auto o = take("lights")) rs.lights = keywordArg<std::vector<scene::Light>>(*o, "lights", kLights);
    if (auto o = take("dt")) rs.dvrStep = keywordArg<double>(*o, "dt", kNumber);
    if (auto o = take("dvr_shading")) rs.dvrShading = keywordArg<bool>(*o, "dvr_shading", "True or False");
    if (auto o = take("transmittance"))
        rs.transmittance = scene::parseTransmittance(keywordArg<std::string>(*o, "transmittance", kTransmittances));
    if (auto o = take("control_extinction"))
        rs.controlExtinction =
            scene::parseControlExtinction(keywordArg<std::string>(*o, "control_extinction", kControls));
    if (auto o = take("fov")) rs.camera.fovYDegrees = keywordArg<double>(*o, "fov", kNumber);
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
    if (tf) s.tf = tf->channels;
    else d.tfSource = session::TfSource{};  // ramp over the field's range, as amrvk render
    if (auto o = take("tf_range")) {
        const auto r = keywordArg<std::pair<float, float>>(*o, "tf_range", "(lo, hi): two numbers");
        d.tfRange = r;
    }
    if (auto o = take("tf_colors"))
        s.tfColors = scene::parseTfColors(keywordArg<std::string>(*o, "tf_colors", "'srgb' or 'linear'"), "tf_colors");
    const std::optional<py::object> traversal = take("traversal");
    const std::string t = traversal ? keywordArg<std::string>(*traversal, "traversal", kText) : "";
    d.fit = t == "auto" ? session::StructureFit::Probe : t.empty() ? session::StructureFit::Data : session::StructureFit::None;
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
    if (auto o = take("kd_leaves")) s.structure.kdLeaves = uint32_t(wholeArg(*o, "kd_leaves", 1, scene::kMaxKdLeaves));
    if (auto o = take("sub_majorants")) {
        s.structure.subMajorants = subMajorantsArg(*o);
        d.subMajorantsGiven = true;
    }
    if (auto o = take("dense_max_mib")) s.structure.denseMaxBytes = uint64_t(wholeArg(*o, "dense_max_mib", 1, scene::kMaxDenseMiB)) << 20;
    scene::validateSettings(rs);
    return d;
}

gpu::ContextOptions contextOptions(const py::kwargs& kw) {
    gpu::ContextOptions o;
    auto has = [&](const char* k) { return kw.contains(k) && !kw[k].is_none(); };
    if (has("device")) o.device = py::str(kw["device"]);
    if (has("validation")) o.validation = keywordArg<bool>(kw["validation"], "validation", "True or False");
    if (has("gpu_timeout")) o.gpuTimeoutSeconds = keywordArg<double>(kw["gpu_timeout"], "gpu_timeout", kNumber);
    if (has("samples_per_invocation")) o.samplesPerInvocation = uint32_t(wholeArg(kw["samples_per_invocation"], "samples_per_invocation", 1, UINT32_MAX));
    if (has("path_regeneration"))
        o.pathRegeneration = keywordArg<bool>(kw["path_regeneration"], "path_regeneration", "True or False");
    return o;
}

// Renderer(volume, tf=None, camera=None, **options): each argument checked for its type first.
std::shared_ptr<PyRenderer> makeRenderer(const py::object& volumeObj, const py::object& tfObj,
                                         const py::object& cameraObj, const py::kwargs& kw) {
    if (!py::isinstance<PyVolume>(volumeObj))
        throw py::type_error("volume: expected an amrvk.Volume, got " + py::repr(volumeObj).cast<std::string>().substr(0, 60));
    const PyVolume& volume = volumeObj.cast<const PyVolume&>();
    const std::optional<PyTf> tf = tfObj.is_none() ? std::nullopt
                                                   : std::optional<PyTf>(keywordArg<PyTf>(tfObj, "tf", "an amrvk.TransferFunction or None"));
    const std::optional<scene::Camera> camera =
        cameraObj.is_none() ? std::nullopt : std::optional<scene::Camera>(keywordArg<scene::Camera>(cameraObj, "camera", "an amrvk.Camera or None"));
    const session::PictureDescription d = describe(volume, tf, camera, kw);
    gpu::ContextOptions co = contextOptions(kw);
    co.requireRayQuery = d.session.structure.backend == scene::Backend::Rq;
    const fs::path shaderDir = kw.contains("shader_dir") && !kw["shader_dir"].is_none()
                                   ? fs::path(py::str(kw["shader_dir"]).cast<std::string>())
                                   : fs::path();
    const bool quiet = kw.contains("quiet") && keywordArg<bool>(kw["quiet"], "quiet", "True or False");
    std::shared_ptr<gpu::Context> ctx;
    {
        py::gil_scoped_release release;
        ctx = contextFor(co);
    }
    auto r = std::make_shared<PyRenderer>(std::move(ctx), volume.volume, d, shaderDir, quiet, volume.files);
    r->noSessionReason = volume.noFileReason();
    return r;
}

std::shared_ptr<PyRenderer> rendererFromSession(const fs::path& path, const py::kwargs& kw) {
    session::PictureDescription d;
    d.session = session::loadSession(path);
    std::shared_ptr<const scene::Volume> volume;
    std::vector<NamedPath> files;
    {
        py::gil_scoped_release release;
        InputFileRecorder recorder;
        volume = session::loadVolume(d.session);
        files = recorder.files("the volume's data");
    }
    gpu::ContextOptions co = contextOptions(kw);
    co.requireRayQuery = d.session.structure.backend == scene::Backend::Rq;
    const bool quiet = kw.contains("quiet") && keywordArg<bool>(kw["quiet"], "quiet", "True or False");
    std::shared_ptr<gpu::Context> ctx;
    {
        py::gil_scoped_release release;
        ctx = contextFor(co);
    }
    return std::make_shared<PyRenderer>(std::move(ctx), std::move(volume), d, fs::path(), quiet, std::move(files));
}

}  // namespace

namespace {

// One-line errors: amrvk's own errors are bad input (ValueError) unless they come from the device
// or the runtime, which raise RuntimeError through their own types.
// The message as Python text: bytes that are not UTF-8 (a name from a file, bytes passed for a
// str) are shown as \xNN instead of emptying the message (PyErr_SetString's decode fails).
void raise(PyObject* type, const std::string& message) {
    PyObject* text = PyUnicode_DecodeUTF8(message.data(), Py_ssize_t(message.size()), "backslashreplace");
    PyErr_SetObject(type, text);
    Py_XDECREF(text);
}

void bindErrors() {
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const gpu::ShaderCompileError& e) {
            raise(PyExc_RuntimeError, e.what());
        } catch (const Error& e) {
            raise(PyExc_ValueError, python::keywordMessage(e.what()));
        } catch (const std::bad_alloc&) {
            PyErr_SetString(PyExc_MemoryError, "out of memory");
        } catch (const py::cast_error& e) {  // a value that keywordArg did not name: still one line, a TypeError
            raise(PyExc_TypeError, strCat("a value of the wrong type (", e.what(), ")"));
        }
    });

}

void bindCamera(py::module_& m) {
    py::class_<scene::Camera>(m, "Camera", "eye, target and up in world space; vertical field of view in degrees")
        .def(py::init([](const py::object& eye, const py::object& target, const py::object& up, const py::object& fov) {
                 scene::Camera c{vec3Arg(eye, "eye"), vec3Arg(target, "target"), vec3Arg(up, "up"),
                                 keywordArg<double>(fov, "fov", kNumber)};
                 scene::RenderSettings s;
                 s.camera = c;
                 scene::validateSettings(s);
                 return c;
             }),
             py::arg("eye"), py::arg("target"), py::arg("up") = std::vector<double>{0, 0, 1}, py::arg("fov") = 40.0,
             "eye, target and up: 3 numbers each (world space); fov: vertical field of view in degrees")
        .def_static(
            "frame",
            [](const py::object& volume, const py::object& fovObj) {
                const PyVolume& v = keywordArg<const PyVolume&>(volume, "volume", "an amrvk.Volume");
                const double fov = keywordArg<double>(fovObj, "fov", kNumber);
                AMRVK_CHECK(scene::validFov(fov), "--fov ", fov, " is outside (0, ", scene::kMaxFovDegrees, ")");
                return scene::defaultCamera(v.volume->worldLo(), v.volume->worldHi(), fov);
            },
            py::arg("volume"), py::arg("fov") = 40.0, "the default three-quarter view that frames the volume (z up)")
        .def_property_readonly("eye", [](const scene::Camera& c) { return list3(c.eye); })
        .def_property_readonly("target", [](const scene::Camera& c) { return list3(c.target); })
        .def_property_readonly("up", [](const scene::Camera& c) { return list3(c.up); })
        .def_property_readonly("fov", [](const scene::Camera& c) { return c.fovYDegrees; })
        .def("__eq__", [](const scene::Camera& a, const scene::Camera& b) { return a == b; })
        .def("__repr__", [](const scene::Camera& c) {
            return strCat("Camera(eye=", c.eye.x, ",", c.eye.y, ",", c.eye.z, " target=", c.target.x, ",", c.target.y,
                          ",", c.target.z, " fov=", c.fovYDegrees, ")");
        });

}

void bindLight(py::module_& m) {
    py::class_<scene::Light>(m, "Light", "a directional light (towards direction) or a point light, world space")
        .def_static(
            "directional",
            [](const py::object& direction, const py::object& radiance) {
                return scene::Light{false, vec3Arg(direction, "direction"), vec3Arg(radiance, "radiance")};
            },
            py::arg("direction"), py::arg("radiance") = std::vector<double>{1, 1, 1})
        .def_static(
            "point",
            [](const py::object& position, const py::object& intensity) {
                return scene::Light{true, vec3Arg(position, "position"), vec3Arg(intensity, "intensity")};
            },
            py::arg("position"), py::arg("intensity") = std::vector<double>{1, 1, 1})
        .def_property_readonly("is_point", [](const scene::Light& l) { return l.point; })
        .def_property_readonly("position_or_direction", [](const scene::Light& l) { return list3(l.posOrDir); })
        .def_property_readonly("radiance", [](const scene::Light& l) { return list3(l.radiance); })
        .def("__repr__", [](const scene::Light& l) {
            return l.point ? strCat("Light.point(", g4(l.posOrDir), ", intensity ", g4(l.radiance), ")")
                           : strCat("Light.directional(", g4(l.posOrDir), ", radiance ", g4(l.radiance), ")");
        });

}

void bindTransferFunction(py::module_& m) {
    py::class_<PyTf>(m, "TransferFunction",
                     "a piecewise-linear map from field values to albedo (rgb) and alpha (extinction per finest "
                     "cell width before the density scale); colour and opacity channels kept apart as ParaView does")
        .def_static("preset", &PyTf::presetFor, py::arg("name"), py::arg("volume"),
                    "a built-in preset (ramp, grey, spiky, foggy, constant, empty) fitted to the volume's data as "
                    "amrvk render fits it: spiky and foggy over its percentiles by cell count, the others over its "
                    "value range")
        .def_static("preset", &PyTf::preset, py::arg("name"), py::arg("lo"), py::arg("hi"),
                    "a built-in preset in its range-fixed shape over [lo, hi] (as with --tf-range)")
        .def_static("from_file", &PyTf::fromFile, py::arg("path"), py::arg("preset") = "", py::arg("lo") = 0.0f,
                    py::arg("hi") = 1.0f, "a ParaView JSON preset file (preset: its name) or .xf; lo/hi for .xf alpha tables")
        .def_static("from_nodes", &PyTf::fromNodes, py::arg("positions"), py::arg("colors"), py::arg("name") = "nodes",
                    "nodes: positions (N,) ascending, colors (N, 4) rgb in [0, 1] and alpha >= 0")
        .def(
            "rescaled",
            [](const PyTf& t, const py::object& lo, const py::object& hi) {
                return t.rescaled(keywordArg<float>(lo, "lo", kNumber), keywordArg<float>(hi, "hi", kNumber));
            },
            py::arg("lo"), py::arg("hi"), "the nodes mapped onto [lo, hi]")
        .def_property_readonly("range", &PyTf::range)
        .def_property_readonly("nodes", &PyTf::nodes, "(positions (N,), colors (N, 4)) of the merged function")
        .def_property_readonly("name", [](const PyTf& t) { return t.channels.name; })
        .def("evaluate", &PyTf::evaluate, py::arg("values"), "rgba (N, 4) at each value")
        .def("to_paraview_json", &PyTf::json)
        .def("save", &PyTf::save, py::arg("path"), "as a ParaView JSON preset file")
        .def("__repr__", &PyTf::repr);

}

void bindVolume(py::module_& m) {
    py::class_<PyVolume, std::shared_ptr<PyVolume>>(m, "Volume",
                                                    "one field of an AMR data set, in brick order with its bricks")
        .def(py::init(&volumeFromFile), py::arg("path"), py::arg("field") = "", py::arg("format") = "auto",
             py::arg("nan") = "reject", py::arg("dims") = py::none(), py::arg("type") = "", py::arg("threshold") = 0.0,
             py::arg("scale") = "auto", py::arg("log_floor") = 0.0,
             "read a data set (ExaBrick .cells, AMReX plotfile, Enzo parameter file, Chombo .hdf5, RAMSES output "
             "directory, raw .raw); "
             "scale='log': log10 of each cell's value (values <= 0 floored at log_floor, default the smallest "
             "positive value), as amrvk render --scale log; 'auto' (the default): log where every value is "
             "positive and spans two decades or more, as amrvk render")
        .def_static("from_arrays", &volumeFromArrays, py::arg("lower"), py::arg("level"), py::arg("values"),
                    py::arg("field") = "values", py::arg("origin") = std::vector<double>{0, 0, 0},
                    py::arg("spacing") = std::vector<double>{1, 1, 1}, py::arg("nan") = "reject", py::arg("units") = "",
                    py::arg("source") = "arrays",
                    "leaf cells: lower (N, 3) integer corners in finest-level units, level (N,) with 0 = finest "
                    "(a cell is 2^level units wide, its corner a multiple of that), values (N,); world = origin + "
                    "spacing * voxel. Validated as the readers validate (alignment, levels, NaN policy, overlaps)")
        .def_property_readonly("field", [](const PyVolume& v) { return v.volume->field().name; })
        .def_property_readonly(
            "units", [](const PyVolume& v) { return v.volume->field().units; },
            "the values' units as the reader or yt gives them (e.g. 'code units (1 = 2.4967e-29 g/cm^3)'); "
            "'' = not known")
        .def_property_readonly("cells", [](const PyVolume& v) { return v.volume->model.cellCount(); })
        .def_property_readonly("value_range", [](const PyVolume& v) { return py::make_tuple(v.volume->valueLo(), v.volume->valueHi()); })
        .def_property_readonly(
            "percentiles",
            [](const PyVolume& v) {
                py::array_t<float> out(py::ssize_t(101));
                std::memcpy(out.mutable_data(), v.volume->percentiles.values.data(), 101 * sizeof(float));
                return out;
            },
            "the field's percentiles 0..100 by cell count (float32 (101,), numpy's method='lower'): what the "
            "spiky and foggy presets follow")
        .def_readwrite("_made_by", &PyVolume::madeBy, "file, arrays or yt (what save_session's refusal names)")
        .def("summary", &PyVolume::summary, "cells per level, value range, world bounds, bytes")
        .def("__repr__", &PyVolume::repr);

}

// Renderer: construction, accumulation, the image and the structure.
py::class_<PyRenderer, std::shared_ptr<PyRenderer>> bindRenderer(py::module_& m) {
    return py::class_<PyRenderer, std::shared_ptr<PyRenderer>>(m, "Renderer",
                                                        "a path-traced picture of a volume on a Vulkan device")
        .def(py::init(&makeRenderer), py::arg("volume"), py::arg("tf") = py::none(), py::arg("camera") = py::none(),
             "options: amrvk render's, with underscores (docs/python.md)")
        .def_static("from_session", &rendererFromSession, py::arg("path"),
                    "the picture a session file describes (amrvk view's, amrvk render --session's)")
        .def("render", &PyRenderer::render, py::arg("spp") = py::none(), py::arg("progress") = py::none(),
             py::arg("legend") = py::none(), py::arg("until") = py::none(),
             "from scratch: spp samples per pixel (default the session's), returns image(legend); until=E stops "
             "once the noise (mean relative standard error of the visible pixels) is at most E, spp the cap")
        .def_property_readonly("first_frame", &PyRenderer::firstFrameInfo,
                               "while the image has no sample and its first frame was shown (inline, image(), "
                               "save()): {'mode': 'dvr', 'spp', 'dt', 'noise', 'gpu_seconds', 'frames'}; else None")
        .def_property_readonly("noise", &PyRenderer::noise,
                               "the image's noise: mean relative standard error of its visible pixels (None below 2 spp)")
        .def("accumulate", &PyRenderer::accumulate, py::arg("n"), py::arg("progress") = py::none(),
             "n more samples per pixel, continuing the same estimate")
        .def("reset", &PyRenderer::reset)
        .def("image", &PyRenderer::image, py::arg("legend") = py::none(),
             "the mean so far: float32 (height, width, 4), row 0 = top, linear radiance, alpha 1; legend=True: "
             "with the colour legend drawn (wider with legend_place 'side')")
        .def("variance", &PyRenderer::variance, "variance of the mean per pixel: float32 (height, width, 3)")
        .def_property_readonly("spp", &PyRenderer::spp)
        .def_property_readonly("stats", &PyRenderer::stats, "amrvk render --json's content for the image so far")
        .def_property_readonly("notes", &PyRenderer::notes, "what was fitted to the data, one line each")
        .def_property_readonly("structure", &PyRenderer::structure)
        .def(
            "set_structure",
            [](PyRenderer& r, const py::object& traversal, const py::object& sampler, const py::object& backend,
               const py::object& grid, const py::object& kdLeaves, const py::object& subMajorants) {
                auto text = [](const py::object& o, const char* name) {
                    return o.is_none() ? std::nullopt : std::optional<std::string>(keywordArg<std::string>(o, name, kText));
                };
                r.setStructure(text(traversal, "traversal"), text(sampler, "sampler"), text(backend, "backend"),
                               text(grid, "grid"),
                               kdLeaves.is_none() ? std::nullopt
                                                  : std::optional<uint32_t>(uint32_t(wholeArg(kdLeaves, "kd_leaves", 1, scene::kMaxKdLeaves))),
                               subMajorants.is_none() ? std::nullopt
                                                      : std::optional<std::string>(scene::subMajorantsName(subMajorantsArg(subMajorants))));
            },
            py::arg("traversal") = py::none(),
             py::arg("sampler") = py::none(), py::arg("backend") = py::none(), py::arg("grid") = py::none(),
             py::arg("kd_leaves") = py::none(), py::arg("sub_majorants") = py::none())
        .def_property("camera", &PyRenderer::camera,
                      [](PyRenderer& r, const py::object& c) { r.setCamera(keywordArg<scene::Camera>(c, "camera", "an amrvk.Camera")); })
        .def_property("tf", &PyRenderer::tf, [](PyRenderer& r, const py::object& t) {
            r.setTf(keywordArg<PyTf>(t, "tf", "an amrvk.TransferFunction"));
        })
        .def_property("tf_colors", &PyRenderer::tfColors, &PyRenderer::setTfColors,
                      "what the TF's colours mean: 'srgb' (display colours, as matplotlib, yt and ParaView; the "
                      "default) or 'linear' (albedo as given)")
;
}

// Renderer: the picture's settings as properties (each edit through editSettings), then output.
void bindRendererSettings(py::class_<PyRenderer, std::shared_ptr<PyRenderer>>& c) {
    c
        .def_property(
            "mode", [](const PyRenderer& r) { return std::string(scene::modeName(r.settings().mode)); },
            [](PyRenderer& r, const py::object& o) {
                const std::string name = keywordArg<std::string>(o, "mode", kModes);
                r.editSettings([&](auto& s) { s.mode = scene::parseMode(name); });
            })
        .def_property(
            "transmittance",
            [](const PyRenderer& r) { return std::string(scene::transmittanceName(r.settings().transmittance)); },
            [](PyRenderer& r, const py::object& o) {
                const std::string name = keywordArg<std::string>(o, "transmittance", kTransmittances);
                r.editSettings([&](auto& s) { s.transmittance = scene::parseTransmittance(name); });
            })
        .def_property(
            "control_extinction",
            [](const PyRenderer& r) { return std::string(scene::controlExtinctionName(r.settings().controlExtinction)); },
            [](PyRenderer& r, const py::object& o) {
                const std::string name = keywordArg<std::string>(o, "control_extinction", kControls);
                r.editSettings([&](auto& s) { s.controlExtinction = scene::parseControlExtinction(name); });
            })
        .def_property(
            "density_scale", [](const PyRenderer& r) { return r.settings().densityScale; },
            [](PyRenderer& r, const py::object& o) {
                const double d = keywordArg<double>(o, "density_scale", kNumber);
                r.editSettings([&](auto& s) { s.densityScale = d; });
            })
        .def_property(
            "size", [](const PyRenderer& r) { return py::make_tuple(r.settings().width, r.settings().height); },
            [](PyRenderer& r, const py::object& o) {
                const auto wh = keywordArg<std::pair<py::object, py::object>>(o, "size", "(width, height)");
                const int w = int(wholeArg(wh.first, "size: width", 1, scene::kMaxImageSide));
                const int h = int(wholeArg(wh.second, "size: height", 1, scene::kMaxImageSide));
                r.editSettings([&](auto& s) {
                    s.width = w;
                    s.height = h;
                });
            },
            "(width, height) in pixels, each in [1, 16384] as --size")
        .def_property(
            "crop", [](const PyRenderer& r) { return cropObject(r.settings().cut.crop); },
            [](PyRenderer& r, const py::object& o) { r.editSettings([&](auto& s) { s.cut.crop = cropOf(o); }); },
            "cut-away box (lo, hi) in world space, or None; the medium outside is empty (docs/cut-aways.md)")
        .def_property(
            "clip", [](const PyRenderer& r) { return clipObject(r.settings().cut.clips); },
            [](PyRenderer& r, const py::object& o) { r.editSettings([&](auto& s) { s.cut.clips = clipsOf(o); }); },
            "clip planes [(point, normal), ...] in world space; the side each normal points to is removed (at most 4)")
        .def_property(
            "seed", [](const PyRenderer& r) { return r.settings().seed; },
            [](PyRenderer& r, const py::object& o) {
                const auto seed = uint32_t(wholeArg(o, "seed", 0, UINT32_MAX));
                r.editSettings([&](auto& s) { s.seed = seed; });
            })
        .def_property(
            "lights", [](const PyRenderer& r) { return r.settings().lights; },
            [](PyRenderer& r, const py::object& o) {
                const auto l = keywordArg<std::vector<scene::Light>>(o, "lights", kLights);
                r.editSettings([&](auto& s) { s.lights = l; });
            })
        .def_property(
            "ambient", [](const PyRenderer& r) { return list3(r.settings().ambient); },
            [](PyRenderer& r, const py::object& o) {
                const glm::dvec3 a = vec3(keywordArg<std::vector<double>>(o, "ambient", kThree), "ambient");
                r.editSettings([&](auto& s) { s.ambient = a; });
            })
        .def_property(
            "background",
            [](const PyRenderer& r) -> py::object {
                const auto& b = r.settings().background;
                return b ? py::cast(list3(*b)) : py::none();
            },
            [](PyRenderer& r, const py::object& o) {
                const std::optional<glm::dvec3> b =
                    o.is_none() ? std::nullopt
                                : std::optional<glm::dvec3>(vec3(keywordArg<std::vector<double>>(o, "background", kThree), "background"));
                r.editSettings([&](auto& s) { s.background = b; });
            },
            "radiance seen by rays that escape without scattering; None = the ambient light")
        .def_property(
            "g", [](const PyRenderer& r) { return r.settings().g; },
            [](PyRenderer& r, const py::object& o) {
                const double g = keywordArg<double>(o, "g", kNumber);
                r.editSettings([&](auto& s) { s.g = g; });
            },
            "Henyey-Greenstein asymmetry in (-1, 1)")
        .def("save", &PyRenderer::save, py::arg("path"), py::arg("legend") = py::none(),
             "the image so far: .png (sRGB), .exr or .pfm (linear); the legend in PNGs (legend None: the renderer's)")
        .def("save_session", &PyRenderer::saveSession, py::arg("path"),
             "the picture as a session file (amrvk view --session, amrvk render --session)")
        .def("_snapshot", &PyRenderer::snapshot, py::arg("legend") = py::none(),
             "(spp, png bytes, mean standard error or None) of one state of the image (the widget's status); "
             "(0, None, None) without a sample")
        .def("png", &PyRenderer::png, py::arg("legend") = py::none(),
             "the image so far as PNG bytes (what save writes to a .png)")
        .def("close", &PyRenderer::close, "free the device memory; every later call raises ValueError")
        .def_property_readonly("closed", &PyRenderer::closed)
        .def("__repr__", &PyRenderer::repr);

}

// Renderer: the colour legend's settings (the session's, as --legend, --legend-place, ...).
void bindRendererLegend(py::class_<PyRenderer, std::shared_ptr<PyRenderer>>& c) {
    c
        .def_property(
            "legend", [](const PyRenderer& r) { return r.legend().show; },
            [](PyRenderer& r, const py::object& o) {
                const bool show = keywordArg<bool>(o, "legend", "True or False");
                r.editLegend([&](session::Legend& l) { l.show = show; });
            },
            "the colour legend in PNGs and inline pictures (as --legend)")
        .def_property(
            "legend_place", [](const PyRenderer& r) { return std::string(session::legendPlaceName(r.legend().place)); },
            [](PyRenderer& r, const py::object& o) {
                const auto place = forKeyword("legend_place", [&] {
                    return session::parseLegendPlace(keywordArg<std::string>(o, "legend_place", "'side' or 'overlay'"));
                });
                r.editLegend([&](session::Legend& l) { l.place = place; });
            },
            "'side' (a strip right of the picture) or 'overlay' (over its lower right corner)")
        .def_property(
            "legend_title", [](const PyRenderer& r) { return r.legend().title; },
            [](PyRenderer& r, const py::object& o) {
                const std::string t = keywordArg<std::string>(o, "legend_title", kText);
                r.editLegend([&](session::Legend& l) { l.title = t; });
            },
            "the legend's title; '' = the field's name")
        .def_property(
            "legend_units", [](const PyRenderer& r) { return r.legend().units; },
            [](PyRenderer& r, const py::object& o) {
                const std::string u = keywordArg<std::string>(o, "legend_units", kText);
                r.editLegend([&](session::Legend& l) { l.units = u; });
            },
            "the units line under the legend's title; '' = the volume's own (Volume.units)");
}

void bindDevices(py::module_& m) {
    m.def(
        "devices",
        [] {
            std::vector<py::dict> out;
            for (const gpu::DeviceReport& d : gpu::listDevices()) {
                py::dict e;
                e["index"] = d.index;
                e["name"] = d.name;
                e["type"] = d.type;
                e["driver"] = d.driver;
                e["ray_query"] = d.rayQuery;
                e["rounding_mode_rte_float32"] = d.roundingModeRTEFloat32;
                e["usable"] = d.usable;
                e["reject_reason"] = d.rejectReason;
                out.push_back(e);
            }
            return out;
        },
        "every Vulkan device, and why an unusable one is rejected");
}

// The series planning of `amrvk render` (session/series.h), for python/amrvk/series.py: which
// inputs in which order, the frames of a turntable, each frame's azimuth and file, and MP4s.
void bindSeries(py::module_& m) {
    m.def("_expand_inputs", &session::expandInputs, py::arg("inputs"),
          "paths as they are, glob patterns expanded; all in natural order (output_2 before output_10)");
    m.def(
        "_plan_frames",
        [](const std::vector<std::string>& inputs, std::optional<uint32_t> frames, bool orbitGiven) {
            return session::planFrames(inputs, frames, orbitGiven);
        },
        py::arg("inputs"), py::arg("frames"), py::arg("orbit_given"));
    m.def("_frame_azimuth", &session::frameAzimuth, py::arg("k"), py::arg("n"), py::arg("degrees"));
    m.def(
        "_frame_files",
        [](const std::string& text, uint32_t count) {
            const session::FrameOutput out = session::frameOutput("out", text, count);
            std::vector<std::string> files;
            for (uint32_t k = 0; k < count; ++k) files.push_back(out.frame(k).string());
            return py::make_tuple(out.pattern, files);
        },
        py::arg("out"), py::arg("count"), "(printf pattern, the file of each frame) of an -o of numbered frames");
    m.def(
        "_encode_mp4",
        [](const std::string& pattern, uint32_t count, double fps, const fs::path& output) {
            requireFfmpeg("out", output);
            py::gil_scoped_release release;
            encodeMp4(pattern, count, fps, output);
        },
        py::arg("pattern"), py::arg("count"), py::arg("fps"), py::arg("output"));
    // The TF of a series as `amrvk render` fits it: spiky and foggy over the outputs' pooled
    // percentiles (amr::pooledPercentiles), layers over their pooled volume histograms
    // (amr::pooledVolumeHistograms); one output: its own. A part is what _distribution returns.
    struct Distribution {
        amr::Percentiles percentiles;
        amr::VolumeHistogram histogram;
    };
    py::class_<Distribution>(m, "_Distribution");
    m.def(
        "_distribution",
        [](const PyVolume& v) {
            return Distribution{v.volume->percentiles, v.volume->volumeHistogram};
        },
        py::arg("volume"), "a volume's percentiles and volume histogram (what the fitted presets follow)");
    m.def(
        "_series_preset",
        [](const std::string& name, const std::vector<Distribution>& parts) {
            std::vector<amr::Percentiles> ps;
            std::vector<amr::VolumeHistogram> hs;
            for (const Distribution& d : parts) {
                ps.push_back(d.percentiles);
                hs.push_back(d.histogram);
            }
            return PyTf{scene::TfChannels::split(
                scene::makePreset(name, amr::pooledPercentiles(ps), amr::pooledVolumeHistograms(hs)))};
        },
        py::arg("name"), py::arg("parts"));
}

}  // namespace

PYBIND11_MODULE(_amrvk, m) {
    m.doc() = "amrvk: unbiased volumetric path tracing of AMR data on any Vulkan device (compiled part)";
    // Whether an object of a bound class holds its C++ value: not after T.__new__(T) without
    // __init__, where pybind11 would call a method on a null object (one_line_errors.py asks first).
    m.def("_initialized", [](const py::handle& o) {
        auto* inst = reinterpret_cast<py::detail::instance*>(o.ptr());
        return py::isinstance(o, py::handle(reinterpret_cast<PyObject*>(py::detail::get_internals().instance_base))) &&
               inst->get_value_and_holder(nullptr, false).value_ptr() != nullptr;
    });
    bindErrors();
    bindCamera(m);
    bindLight(m);
    bindTransferFunction(m);
    bindVolume(m);
    auto renderer = bindRenderer(m);
    bindRendererSettings(renderer);
    bindRendererLegend(renderer);
    bindDevices(m);
    bindSeries(m);
}
