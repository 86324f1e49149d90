#include "python/py_transfer_function.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "core/file_io.h"
#include "scene/tf_files.h"
#include "scene/tf_presets.h"

namespace amrvk::python {

namespace {

// A range a user gives (preset, rescaled), as --tf-range takes it: finite in float32, lo below hi.
void checkTfRange(float lo, float hi, const char* what) {
    if (!std::isfinite(lo) || !std::isfinite(hi))
        throw py::value_error(strCat(what, ": ", lo, " ", hi, " is not a finite float32 range"));
    if (!(lo < hi)) throw py::value_error(strCat(what, ": ", lo, " ", hi, ": LO must be below HI"));
}

}  // namespace

PyTf PyTf::preset(const std::string& name, float lo, float hi) {
    checkTfRange(lo, hi, "preset");
    return {scene::TfChannels::split(scene::makePreset(name, lo, hi))};
}

PyTf PyTf::presetFor(const std::string& name, const PyVolume& v) {
    return {scene::TfChannels::split(scene::makePreset(name, v.volume->percentiles, v.volume->volumeHistogram))};
}

PyTf PyTf::fromFile(const fs::path& path, const std::string& preset, float lo, float hi) {
    return {scene::TfChannels::split(scene::loadTransferFunction(path.string(), lo, hi, preset))};
}

PyTf PyTf::fromNodes(const py::object& positionsObj, const py::object& colorsObj, const std::string& name) {
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

scene::TransferFunction PyTf::merged() const { return channels.merged(); }

PyTf PyTf::rescaled(float lo, float hi) const {
    checkTfRange(lo, hi, "rescaled");
    return {scene::TfChannels::split(merged().rescaled(lo, hi))};
}

py::tuple PyTf::range() const {
    const scene::TransferFunction tf = merged();
    return py::make_tuple(tf.firstPosition(), tf.lastPosition());
}

py::tuple PyTf::nodes() const {
    const scene::TransferFunction tf = merged();
    py::array_t<float> pos(py::ssize_t(tf.nodeCount()));
    py::array_t<float> col({py::ssize_t(tf.nodeCount()), py::ssize_t(4)});
    std::memcpy(pos.mutable_data(), tf.positions().data(), tf.nodeCount() * sizeof(float));
    std::memcpy(col.mutable_data(), tf.colors().data(), tf.nodeCount() * sizeof(glm::vec4));
    return py::make_tuple(pos, col);
}

py::array_t<float> PyTf::evaluate(const py::object& valuesObj) const {
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

std::string PyTf::json() const { return scene::paraViewPresetJson(channels); }

std::string PyTf::repr() const {
    const scene::TransferFunction tf = merged();
    float alpha = 0;
    for (const glm::vec4& c : tf.colors()) alpha = std::max(alpha, c.a);
    return strCat("TransferFunction('", channels.name, "', ", tf.nodeCount(), " nodes over [", g4(tf.firstPosition()),
                  ", ", g4(tf.lastPosition()), "], alpha up to ", g4(alpha), ")");
}

void PyTf::save(const fs::path& path) const { writeFileAtomic(path, json()); }

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
                    py::arg("hi") = 1.0f,
                    "a ParaView JSON preset file (preset: its name) or .xf; lo/hi for .xf alpha tables")
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

}  // namespace amrvk::python
