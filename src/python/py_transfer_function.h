#pragma once
// amrvk.TransferFunction: a piecewise-linear map from field values to albedo (rgb) and alpha, its
// colour and opacity channels kept apart as ParaView does (a scene::TfChannels).
#include <string>

#include "python/arguments.h"
#include "python/py_volume.h"
#include "scene/transfer_function.h"

namespace amrvk::python {

struct PyTf {
    scene::TfChannels channels;
    // A built-in preset in its range-fixed shape over [lo, hi] (finite in float32, lo below hi).
    static PyTf preset(const std::string& name, float lo, float hi);
    // Fitted to a volume's data as `amrvk render --tf NAME` fits it (spiky and foggy over its percentiles,
    // layers over its volume histogram).
    static PyTf presetFor(const std::string& name, const PyVolume& v);
    // A ParaView JSON preset file (`preset`: its name) or .xf; lo and hi for .xf alpha tables.
    static PyTf fromFile(const fs::path& path, const std::string& preset, float lo, float hi);
    // Nodes: positions (N,) and colors (N, 4) numpy arrays, validated as scene::TransferFunction does.
    static PyTf fromNodes(const py::object& positionsObj, const py::object& colorsObj, const std::string& name);
    scene::TransferFunction merged() const;   // the channels as one function
    PyTf rescaled(float lo, float hi) const;  // the nodes mapped onto [lo, hi] (checked as preset's)
    py::tuple range() const;                  // (first node's position, last node's position)
    py::tuple nodes() const;                  // float32 (positions (N,), colors (N, 4)) of merged()
    py::array_t<float> evaluate(const py::object& valuesObj) const;  // float32 rgba (N, 4) at each value
    std::string json() const;                                        // a ParaView JSON preset
    // "TransferFunction('ramp', 5 nodes over [-31, -26.5], alpha up to 1)".
    std::string repr() const;
    void save(const fs::path& path) const;  // json(), written atomically
};

// Binds amrvk.TransferFunction.
void bindTransferFunction(py::module_& m);

}  // namespace amrvk::python
