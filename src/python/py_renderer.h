#pragma once
// amrvk.Renderer: a picture (picture::makePicture) with its session kept in step with every edit.
// The GIL is released while the device works, and device calls are served one at a time in the
// order they came (python/fair_mutex.h); long work runs in chunks of about a quarter of a second,
// serving Ctrl-C and a progress callback between chunks.
#include "python/arguments.h"

namespace amrvk::python {

// Binds amrvk.Renderer: construction, accumulation, the image and the structure, then the
// picture's settings as properties, output (files, PNG bytes, the session file), close, and the
// colour legend's settings.
void bindRendererClass(py::module_& m);

}  // namespace amrvk::python
