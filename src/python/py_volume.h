#pragma once
// amrvk.Volume: one field of an AMR data set (a scene::Volume), read from a file through the
// readers or made from numpy arrays validated as the readers validate.
#include <memory>
#include <string>
#include <vector>

#include "core/file_io.h"
#include "python/arguments.h"
#include "scene/volume.h"
#include "session/session.h"

namespace amrvk::python {

struct PyVolume {
    std::shared_ptr<const scene::Volume> volume;
    session::Session source;       // input, read options and field (sessions name them); input "" for arrays
    std::vector<NamedPath> files;  // the files the data set was read from (none for arrays and yt)
    std::string madeBy = "file";   // "file", "arrays" or "yt" (set by from_yt)

    // Why a session cannot name this volume's file ("" where it has one).
    std::string noFileReason() const;

    // "Volume(DD0018, field 'Density' [g/cm**3], 137502 cells on 4 levels, values 1.2e-31..4.5e-27,
    // world (0, 0, 0)..(1, 1, 1))": what a scientist checks first.
    std::string repr() const;

    // Volume.summary(): cells per level (index = level, 0 = finest), value range, world bounds, bytes.
    py::dict summary() const;
};

// Binds amrvk.Volume (its constructor reads a file, from_arrays takes numpy arrays).
void bindVolume(py::module_& m);

}  // namespace amrvk::python
