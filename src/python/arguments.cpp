#include "python/arguments.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

#include "scene/limits.h"
#include "scene/structure_config.h"

namespace amrvk::python {

std::string shortRepr(const py::handle& o) {
    std::string shown = py::repr(o).cast<std::string>();
    if (shown.size() > 64 || shown.find('\n') != std::string::npos) shown = strCat("a ", Py_TYPE(o.ptr())->tp_name);
    return shown;
}

long long wholeArg(const py::handle& o, const char* name, long long lo, long long hi) {
    const std::string shown = shortRepr(o);
    if (!py::isinstance<py::int_>(o) || py::isinstance<py::bool_>(o))
        throw py::type_error(strCat(name, ": expected a whole number in [", lo, ", ", hi, "], got ", shown));
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(o.ptr(), &overflow);
    if (overflow != 0 || v < lo || v > hi)
        throw py::value_error(strCat(name, ": ", shown, " is outside [", lo, ", ", hi, "]"));
    return v;
}

uint32_t countArg(const py::handle& o, const char* name) { return uint32_t(wholeArg(o, name, 1, scene::kMaxSpp)); }

WholeNumber wholeElement(const py::array& a, py::ssize_t i, py::ssize_t k) {
    if (a.dtype().kind() == 'u' && a.dtype().itemsize() == 8) {
        const uint64_t u = element<uint64_t>(a, i, k);
        return {u <= uint64_t(INT64_MAX) ? std::optional<int64_t>(int64_t(u)) : std::nullopt, std::to_string(u)};
    }
    const int64_t v = element<int64_t>(a, i, k);
    return {v, std::to_string(v)};
}

py::array checkedArray(const py::object& obj, const char* name, const char* kinds, int ndim, py::ssize_t columns) {
    if (!py::isinstance<py::array>(obj))
        throw py::type_error(std::string(name) + ": expected a numpy array, got " +
                             std::string(py::str(obj.get_type().attr("__name__"))));
    py::array a = py::reinterpret_borrow<py::array>(obj);
    const char kind = a.dtype().kind();
    if (std::string(kinds).find(kind) == std::string::npos || (kind == 'f' && a.dtype().itemsize() < 4) ||
        a.dtype().itemsize() > 8)
        throw py::type_error(std::string(name) + ": dtype " + std::string(py::str(py::handle(a.dtype()))) + " is not " +
                             (std::string(kinds) == "iu" ? "an integer type" : "an integer or float32/float64 type"));
    if (a.ndim() != ndim || (ndim == 2 && a.shape(1) != columns))
        throw py::value_error(
            std::string(name) + ": expected shape " + (ndim == 1 ? "(N,)" : "(N, " + std::to_string(columns) + ")") +
            ", got " +
            std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim()))))));
    return a;
}

glm::dvec3 vec3(const std::vector<double>& v, const char* name) {
    if (v.size() != 3)
        throw py::value_error(std::string(name) + ": expected 3 numbers, got " + std::to_string(v.size()));
    for (double x : v)
        if (!std::isfinite(x)) throw py::value_error(std::string(name) + ": " + std::to_string(x) + " is not finite");
    return {v[0], v[1], v[2]};
}

std::vector<double> list3(glm::dvec3 v) { return {v.x, v.y, v.z}; }

glm::dvec3 vec3Arg(const py::handle& o, const char* name) {
    return vec3(keywordArg<std::vector<double>>(o, name, kThree), name);
}

std::string g4(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}
std::string g4(glm::dvec3 v) { return "(" + g4(v.x) + ", " + g4(v.y) + ", " + g4(v.z) + ")"; }

std::optional<scene::CropBox> cropOf(const py::object& o) {
    if (o.is_none()) return std::nullopt;
    const auto corners = keywordArg<std::pair<std::vector<double>, std::vector<double>>>(
        o, "crop", "(lo, hi): two lists of 3 numbers, or None");
    return scene::CropBox{vec3(corners.first, "crop lo"), vec3(corners.second, "crop hi")};
}
std::vector<scene::ClipPlane> clipsOf(const py::object& o) {
    std::vector<scene::ClipPlane> out;
    if (o.is_none()) return out;
    for (const auto& [point, normal] : keywordArg<std::vector<std::pair<std::vector<double>, std::vector<double>>>>(
             o, "clip", "a list of (point, normal) pairs of 3 numbers each"))
        out.push_back({vec3(point, "clip point"), vec3(normal, "clip normal")});
    return out;
}
py::object cropObject(const std::optional<scene::CropBox>& c) {
    return c ? py::object(py::make_tuple(list3(c->lo), list3(c->hi))) : py::object(py::none());
}
py::list clipObject(const std::vector<scene::ClipPlane>& clips) {
    py::list out;
    for (const scene::ClipPlane& c : clips) out.append(py::make_tuple(list3(c.point), list3(c.normal)));
    return out;
}

py::array_t<float> imageArray(const Image& image) {
    py::array_t<float> out({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(4)});
    std::memcpy(out.mutable_data(), image.pixels.data(), image.pixels.size() * sizeof(glm::vec4));
    return out;
}

}  // namespace amrvk::python
