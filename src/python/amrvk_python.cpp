// The Python module `amrvk` (its compiled part, `amrvk._amrvk`; python/amrvk/ adds the yt bridge,
// tqdm progress and Jupyter display). A thin layer over the one entry from a picture description
// to pixels (picture::makePicture): Volume is a scene::Volume (from a file through the readers, or
// from numpy arrays validated as the readers validate), TransferFunction a scene::TfChannels,
// Camera a scene::Camera, and Renderer a picture with its session kept in step with every edit.
// The GIL is released while the device works; long work runs in chunks of about a quarter of a
// second (whole samples, or tiles of rows when one sample takes longer), so Ctrl-C
// (KeyboardInterrupt) and a progress callback are served between chunks. Errors are the CLI's
// one-line messages: amrvk::Error -> ValueError (bad input) or RuntimeError (device, state).
#include "python/arguments.h"
#include "python/py_camera_light.h"
#include "python/py_devices.h"
#include "python/py_errors.h"
#include "python/py_renderer.h"
#include "python/py_series.h"
#include "python/py_transfer_function.h"
#include "python/py_volume.h"
#include "python/renderer_keywords.h"

using namespace amrvk::python;  // py = pybind11, and the bind functions

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
    bindRendererClass(m);
    bindDevices(m);
    bindSeries(m);
    bindSettingTable(m);
}
