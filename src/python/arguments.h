#pragma once
// Python values to amrvk's and back, for every binding of the module: each argument checked for
// its type and range, a wrong one raised as one line (TypeError or ValueError) naming the keyword,
// what it takes and what it got (never pybind11's list of signatures). Every file of the module
// includes the pybind11 headers through this one, so all of them see the same type casters
// (stl.h in one file and not in another would cast std::vector differently).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/image_io.h"
#include "python/keyword_messages.h"
#include "scene/cut_away.h"

namespace amrvk::python {

namespace py = pybind11;
namespace fs = std::filesystem;

// A value as a message shows it: its repr where that is one short line, else its type.
std::string shortRepr(const py::handle& o);

// A whole number from Python in [lo, hi], the CLI's range for that option; anything else is one
// line naming the keyword and the value (not pybind11's list of signatures).
long long wholeArg(const py::handle& o, const char* name, long long lo, long long hi);

// A count from Python (spp, n): a whole number in [1, 2^24], the CLI's --spp range.
uint32_t countArg(const py::handle& o, const char* name);

// What a keyword takes, as its TypeError says it.
inline constexpr const char* kNumber = "a number";
inline constexpr const char* kText = "a string";
inline constexpr const char* kThree = "3 numbers";
inline constexpr const char* kLights = "a list of amrvk.Light";
inline constexpr const char* kModes = "one of 'ae', 'ss', 'ms', 'dvr'";
inline constexpr const char* kTransmittances = "'ratio' or 'ubrm'";
inline constexpr const char* kControls = "'none' or 'minorant'";

// A keyword's value as T; a value of another type is one TypeError naming the keyword, what it
// takes and what it got.
template <typename T>
T keywordArg(const py::handle& o, const char* name, const char* expected) {
    if constexpr (std::is_arithmetic_v<T>) {
        // pybind11 would take True as 1 and a numpy array of one element as a number.
        if (py::isinstance<py::bool_>(o) && !std::is_same_v<T, bool>)
            throw py::type_error(strCat(name, ": expected ", expected, ", got ", shortRepr(o)));
    }
    try {
        return o.cast<T>();
    } catch (const std::exception&) {  // cast_error, or reference_cast_error for None as a class
        throw py::type_error(strCat(name, ": expected ", expected, ", got ", shortRepr(o)));
    }
}

// An amrvk error raised while handling `keyword`, with the keyword in front where the message does
// not name it already.
template <typename F>
auto forKeyword(const char* keyword, F f) {
    try {
        return f();
    } catch (const Error& e) {
        const std::string m = python::keywordMessage(e.what());
        throw py::value_error(m.rfind(keyword, 0) == 0 ? m : strCat(keyword, ": ", m));
    }
}

// ---- numpy helpers ---------------------------------------------------------------------------

// A numpy array's element (i, k) as T, whatever its strides (non-contiguous and read-only arrays
// are only read).
template <typename T>
T element(const py::array& a, py::ssize_t i, py::ssize_t k = 0) {
    const char* p = static_cast<const char*>(a.data()) + i * a.strides(0) + (a.ndim() > 1 ? k * a.strides(1) : 0);
    const py::dtype dt = a.dtype();
    switch (dt.kind()) {
        case 'i':
            if (dt.itemsize() == 8) return T(*reinterpret_cast<const int64_t*>(p));
            if (dt.itemsize() == 4) return T(*reinterpret_cast<const int32_t*>(p));
            if (dt.itemsize() == 2) return T(*reinterpret_cast<const int16_t*>(p));
            return T(*reinterpret_cast<const int8_t*>(p));
        case 'u':
            if (dt.itemsize() == 8) return T(*reinterpret_cast<const uint64_t*>(p));
            if (dt.itemsize() == 4) return T(*reinterpret_cast<const uint32_t*>(p));
            if (dt.itemsize() == 2) return T(*reinterpret_cast<const uint16_t*>(p));
            return T(*reinterpret_cast<const uint8_t*>(p));
        case 'f':
            if (dt.itemsize() == 8) return T(*reinterpret_cast<const double*>(p));
            if (dt.itemsize() == 4) return T(*reinterpret_cast<const float*>(p));
            break;
        default:
            break;
    }
    throw py::type_error("unsupported array dtype " + std::string(py::str(py::handle(dt))));
}

// An integer array's element (i, k): its value where it fits int64 (a uint64 above INT64_MAX does
// not), and its text as read, for messages (never a uint64 shown as a negative number).
struct WholeNumber {
    std::optional<int64_t> value;
    std::string text;
};
WholeNumber wholeElement(const py::array& a, py::ssize_t i, py::ssize_t k = 0);

// `a` as an array, checked: `kinds` are the dtype kinds allowed ("iu", "iuf"), ndim and the
// length of axis 1 where it has two.
py::array checkedArray(const py::object& obj, const char* name, const char* kinds, int ndim, py::ssize_t columns = 0);

// 3 finite numbers; one ValueError naming `name` otherwise.
glm::dvec3 vec3(const std::vector<double>& v, const char* name);

// A vector as a Python list of 3 numbers.
std::vector<double> list3(glm::dvec3 v);

// A keyword's 3 finite numbers (a list, tuple or array); one line naming it otherwise.
glm::dvec3 vec3Arg(const py::handle& o, const char* name);

// Numbers in __repr__s: 4 significant digits ("1.235e-27", "0.5"); vectors as "(x, y, z)".
std::string g4(double v);
std::string g4(glm::dvec3 v);

// crop=(lo, hi) (world; None: no crop) and clip=[(point, normal), ...] (world), as --crop and --clip.
std::optional<scene::CropBox> cropOf(const py::object& o);
std::vector<scene::ClipPlane> clipsOf(const py::object& o);
// The same back as Python values: (lo, hi) or None, and [(point, normal), ...] (lists of 3).
py::object cropObject(const std::optional<scene::CropBox>& c);
py::list clipObject(const std::vector<scene::ClipPlane>& clips);

// An image as numpy float32 (H, W, 4), row 0 = top.
py::array_t<float> imageArray(const Image& image);

}  // namespace amrvk::python
