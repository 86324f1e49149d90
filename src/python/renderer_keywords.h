#pragma once
// The keywords of a Python Renderer(volume, tf, camera, **options) call: amrvk render's options
// with underscores (docs/python.md), read into the picture description `amrvk render` makes.
#include <optional>

#include "python/arguments.h"
#include "python/py_transfer_function.h"
#include "python/py_volume.h"
#include "scene/camera.h"
#include "session/picture_description.h"
#include "session/setting_table.h"

namespace amrvk::python {

// The description a Python Renderer(...) call makes, as `amrvk render` makes one from its options.
// An unknown keyword is a TypeError; each value is checked as its option is (one line naming the
// keyword), and the settings as the CLI validates them. None for a keyword = not given. The
// context's keywords (device, validation, ...) are read by contextOptions (context_cache.h).
session::PictureDescription describe(const PyVolume& v, const std::optional<PyTf>& tf,
                                     const std::optional<scene::Camera>& camera, const py::kwargs& kw);

// A setting of session::settingTable() given from Python as `o` (its keyword names it in every
// error), checked as the command line and the session file check it, into `s`.
void setSettingFromPython(const session::Setting& st, const py::handle& o, session::Session& s);
// Its value in `s` as Python gives it back: float, int, bool or str.
py::object settingToPython(const session::Setting& st, const session::Session& s);

// amrvk._amrvk._settings(): the table as a list of dicts (option, keyword, section, key, kind, unit,
// lo, hi, lo_open, hi_open, choices, default, invalidates), for tests and tools.
void bindSettingTable(py::module_& m);

}  // namespace amrvk::python
