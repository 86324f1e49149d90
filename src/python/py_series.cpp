#include "python/py_series.h"

#include <optional>
#include <string>
#include <vector>

#include "core/movie_io.h"
#include "python/py_transfer_function.h"
#include "python/py_volume.h"
#include "scene/tf_presets.h"
#include "session/camera_path.h"
#include "session/series.h"
#include "session/session.h"

namespace amrvk::python {

// The series planning of `amrvk render` (session/series.h), for python/amrvk/series.py: which
// inputs in which order, the frames of a turntable, each frame's azimuth and file, a session's
// camera path (session/camera_path.h) and the output of each of its frames, and MP4s.
void bindSeries(py::module_& m) {
    m.def("_expand_inputs", &session::expandInputs, py::arg("inputs"),
          "paths as they are, glob patterns expanded; all in natural order (output_2 before output_10)");
    m.def(
        "_plan_frames",
        [](const std::vector<std::string>& inputs, std::optional<uint32_t> frames, bool orbitGiven) {
            return session::planFrames(inputs, frames, orbitGiven);
        },
        py::arg("inputs"), py::arg("frames"), py::arg("orbit_given"));
    m.def("_frame_azimuth", &session::frameAzimuth, py::arg("k"), py::arg("n"), py::arg("degrees"));
    // A session's camera path as amrvk render takes it: the camera of every frame (cameraAt(k)) and
    // the fps; None when the session has no path.
    m.def(
        "_session_camera_path",
        [](const fs::path& file) -> py::object {
            const session::Session s = session::loadSession(file);
            if (s.cameraPath.empty()) return py::none();
            std::vector<scene::Camera> cameras;
            for (uint32_t k = 0; k < s.cameraPath.frameCount(); ++k)
                cameras.push_back(s.cameraPath.cameraAt(double(k)));
            return py::make_tuple(cameras, s.cameraPath.fps());
        },
        py::arg("session"));
    m.def("_step_of_frame", &session::stepOfFrame, py::arg("frame"), py::arg("frames"), py::arg("steps"));
    m.def(
        "_frame_files",
        [](const std::string& text, uint32_t count) {
            const session::FrameOutput out = session::frameOutput("out", text, count);
            std::vector<std::string> files;
            for (uint32_t k = 0; k < count; ++k) files.push_back(out.frame(k).string());
            return py::make_tuple(out.pattern, files);
        },
        py::arg("out"), py::arg("count"), "(printf pattern, the file of each frame) of an -o of numbered frames");
    m.def(
        "_encode_mp4",
        [](const std::string& pattern, uint32_t count, double fps, const fs::path& output) {
            requireFfmpeg("out", output);
            py::gil_scoped_release release;
            encodeMp4(pattern, count, fps, output);
        },
        py::arg("pattern"), py::arg("count"), py::arg("fps"), py::arg("output"));
    // The TF of a series as `amrvk render` fits it: spiky and foggy over the outputs' pooled
    // percentiles (amr::pooledPercentiles), layers over their pooled volume histograms
    // (amr::pooledVolumeHistograms); one output: its own. A part is what _distribution returns.
    struct Distribution {
        amr::Percentiles percentiles;
        amr::VolumeHistogram histogram;
    };
    py::class_<Distribution>(m, "_Distribution");
    m.def(
        "_distribution",
        [](const PyVolume& v) {
            return Distribution{v.volume->percentiles, v.volume->volumeHistogram};
        },
        py::arg("volume"), "a volume's percentiles and volume histogram (what the fitted presets follow)");
    m.def(
        "_series_preset",
        [](const std::string& name, const std::vector<Distribution>& parts) {
            std::vector<amr::Percentiles> ps;
            std::vector<amr::VolumeHistogram> hs;
            for (const Distribution& d : parts) {
                ps.push_back(d.percentiles);
                hs.push_back(d.histogram);
            }
            return PyTf{scene::TfChannels::split(
                scene::makePreset(name, amr::pooledPercentiles(ps), amr::pooledVolumeHistograms(hs)))};
        },
        py::arg("name"), py::arg("parts"));
}

}  // namespace amrvk::python
