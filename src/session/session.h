#pragma once
// A session: everything that makes a picture, in one JSON file that both the viewer (save/load)
// and `amrvk render --session` read, so a picture explored interactively renders the same offline.
// Schema (docs/sessions.md): {"amrvk": "session", "version": 3, "input", "read", "field",
// "camera", "image", "render", "lights", "structure", "transferFunction", "tfColors", "legend",
// "cameraPath"}; "cameraPath" only when the session has one (keyframes: session/camera_path.h).
// Older files load with the meaning they were saved with: version 1 (before "tfColors") linear
// colours; versions 1-2 (before the auto scale and the black background) a missing read.scale is
// linear and a missing render.background the ambient. The input path is
// stored absolute; a relative one in a hand-written file is taken relative to the session file.
#include <cstdint>
#include <filesystem>
#include <string>

#include "amr/readers.h"
#include "scene/render_settings.h"
#include "scene/structure_config.h"
#include "scene/tf_colors.h"
#include "scene/transfer_function.h"
#include "session/camera_path.h"
#include "session/legend.h"

namespace amrvk::session {

struct Session {
    std::string input;  // the data set (file or directory)
    // format, NaN policy, raw-volume options (fields: see `field`); the scale starts as auto (the
    // field decides, amr::autoScaleOf) and a fitted picture holds what it decided
    amr::ReadOptions read = [] {
        amr::ReadOptions r;
        r.scale = amr::FieldScale::Auto;
        return r;
    }();
    std::string field;  // empty: the source's default field
    // camera, image size, mode, seed, medium, lights, dvr; the first picture shows the data lit by
    // the white ambient against a black background (emission-friendly, as yt's and ParaView's)
    scene::RenderSettings settings = [] {
        scene::RenderSettings r;
        r.background = glm::dvec3(0.0);
        return r;
    }();
    uint32_t spp = 64;               // render: samples per pixel; viewer: stop accumulating there (0: run on)
    // the structure asked for; the back-end starts as auto (resolved for the device by the picture)
    scene::StructureConfig structure = [] {
        scene::StructureConfig c;
        c.backend = scene::Backend::Auto;
        return c;
    }();
    scene::TfChannels tf;            // field units (colour and opacity apart, as ParaView keeps them)
    scene::TfColors tfColors = scene::TfColors::Srgb;  // what tf's colours mean (scene/tf_colors.h)
    Legend legend;                   // the colour legend (session/legend.h)
    CameraPath cameraPath;  // keyframed cameras of a movie (empty: none); the picture's camera is `settings.camera`
};

// The JSON text of a session (pretty, keys in schema order).
std::string sessionJson(const Session& s);
// Parses a session; errors are one line naming `where` (the file) and the key.
Session parseSession(const std::string& text, const std::filesystem::path& where);

void saveSession(const std::filesystem::path& path, const Session& s);  // atomic: temp file + rename
Session loadSession(const std::filesystem::path& path);

// The `amrvk render` command line of a session's picture: session::renderCommandLine
// (session/picture_description.h).

}  // namespace amrvk::session
