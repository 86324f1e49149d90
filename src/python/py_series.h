#pragma once
// The series planning of `amrvk render` (session/series.h) for python/amrvk/series.py.
#include "python/arguments.h"

namespace amrvk::python {

// Binds the private functions python/amrvk/series.py plans a series with: which inputs in which
// order, the frames of a turntable, each frame's azimuth and file, MP4s, and the series' fitted TF.
void bindSeries(py::module_& m);

}  // namespace amrvk::python
