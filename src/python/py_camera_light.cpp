#include "python/py_camera_light.h"

#include <vector>

#include "python/py_volume.h"
#include "scene/camera.h"
#include "scene/limits.h"
#include "scene/render_settings.h"
#include "session/setting_table.h"

namespace amrvk::python {

void bindCamera(py::module_& m) {
    py::class_<scene::Camera>(m, "Camera", "eye, target and up in world space; vertical field of view in degrees")
        .def(py::init([](const py::object& eye, const py::object& target, const py::object& up, const py::object& fov) {
                 scene::Camera c{vec3Arg(eye, "eye"), vec3Arg(target, "target"), vec3Arg(up, "up"),
                                 keywordArg<double>(fov, "fov", kNumber)};
                 session::checkSetting(session::settingForOption("--fov"), c.fovYDegrees, "fov");
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
                session::checkSetting(session::settingForOption("--fov"), fov, "fov");
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

}  // namespace amrvk::python
