#include "python/py_volume.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>

#include "amr/readers.h"
#include "core/checked_size.h"
#include "core/strings.h"
#include "session/picture_description.h"

namespace amrvk::python {

std::string PyVolume::noFileReason() const {
    if (madeBy == "yt")
        return strCat("save_session: this volume came from yt (", volume->model.source,
                      "), not from a file amrvk "
                      "reads: a session needs one (amrvk.Volume(path, field=...) reads Enzo, AMReX, Chombo, RAMSES "
                      "and ExaBrick files), or save the image instead");
    return "save_session: this volume was made from arrays, not read from a file: a session needs a file "
           "(write the cells with amrvk convert, or save the image instead)";
}

std::string PyVolume::repr() const {
    const scene::Volume& v = *volume;
    const size_t levels =
        std::count_if(v.summary.cellsPerLevel.begin(), v.summary.cellsPerLevel.end(), [](uint64_t n) { return n > 0; });
    const std::string& units = v.field().units;
    return strCat("Volume(", v.model.source, ", field '", v.field().name, "'", units.empty() ? "" : " [" + units + "]",
                  ", ", v.model.cellCount(), " cells on ", levels, levels == 1 ? " level" : " levels", ", values ",
                  g4(v.valueLo()), "..", g4(v.valueHi()), ", world ", g4(v.worldLo()), "..", g4(v.worldHi()), ")");
}

py::dict PyVolume::summary() const {
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

namespace {

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
                                           const std::string& nan, const std::string& units,
                                           const std::string& source) {
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

}  // namespace

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
        .def_property_readonly(
            "value_range", [](const PyVolume& v) { return py::make_tuple(v.volume->valueLo(), v.volume->valueHi()); })
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

}  // namespace amrvk::python
