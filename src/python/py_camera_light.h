#pragma once
// amrvk.Camera (a scene::Camera) and amrvk.Light (a scene::Light), world space.
#include "python/arguments.h"

namespace amrvk::python {

// Binds amrvk.Camera: eye, target and up (world), vertical field of view in degrees; validated
// as --camera is.
void bindCamera(py::module_& m);

// Binds amrvk.Light: Light.directional(direction, radiance) and Light.point(position, intensity).
void bindLight(py::module_& m);

}  // namespace amrvk::python
