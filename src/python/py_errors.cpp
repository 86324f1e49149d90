#include "python/py_errors.h"

#include <exception>
#include <new>
#include <string>

#include "gpu/shader_compiler.h"

namespace amrvk::python {

namespace {

// The message as Python text: bytes that are not UTF-8 (a name from a file, bytes passed for a
// str) are shown as \xNN instead of emptying the message (PyErr_SetString's decode fails).
void raise(PyObject* type, const std::string& message) {
    PyObject* text = PyUnicode_DecodeUTF8(message.data(), Py_ssize_t(message.size()), "backslashreplace");
    PyErr_SetObject(type, text);
    Py_XDECREF(text);
}

}  // namespace

void bindErrors() {
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const gpu::ShaderCompileError& e) {
            raise(PyExc_RuntimeError, e.what());
        } catch (const Error& e) {
            raise(PyExc_ValueError, python::keywordMessage(e.what()));
        } catch (const std::bad_alloc&) {
            PyErr_SetString(PyExc_MemoryError, "out of memory");
        } catch (const py::cast_error& e) {  // a value that keywordArg did not name: still one line, a TypeError
            raise(PyExc_TypeError, strCat("a value of the wrong type (", e.what(), ")"));
        }
    });
}

}  // namespace amrvk::python
