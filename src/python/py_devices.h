#pragma once
// amrvk.devices(): the Vulkan devices amrvk sees.
#include "python/arguments.h"

namespace amrvk::python {

// Binds amrvk.devices(): every Vulkan device (index, name, type, driver, features), and why an
// unusable one is rejected.
void bindDevices(py::module_& m);

}  // namespace amrvk::python
