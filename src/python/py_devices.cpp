#include "python/py_devices.h"

#include <vector>

#include "gpu/context.h"

namespace amrvk::python {

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

}  // namespace amrvk::python
