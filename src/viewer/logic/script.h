#pragma once
// Viewer automation (`amrvk view --script FILE`): one action per line, "FRAME ACTION ARGS...",
// run when the viewer reaches frame FRAME (0 = before the first frame); '#' starts a comment;
// arguments with spaces go in double quotes (\" and \\ inside). Actions:
//   orbit DX DY | pan DX DY          mouse drags in pixels
//   zoom STEPS                       wheel steps (> 0 closer)
//   tf-preset NAME | tf-range LO HI | density SCALE
//   scale linear|log | log-floor V   the field's scale (read again; the TF as tfOnNewScale)
//   mode ae|ss|ms|dvr | traversal T | sampler S | backend B | grid G
//   edit-shader FILE FIND REPLACE    replace the first FIND in FILE (under --shader-dir) and save it
//   reload                           recompile the shaders now (the watcher also does on a save)
//   screenshot FILE                  the accumulated image, no UI (.png, .exr, .pfm)
//   capture-window FILE              the window as shown, UI included (.png; no-op with --headless)
//   save-session FILE                the current state as a session file (render it with amrvk render --session)
//   load-session FILE                as the panel's "load session": the same data (another scale is read
//                                    again), else refused with the reason
//   legend on|off                    the colour legend over the picture and in PNG screenshots
//   tf-colors srgb|linear            what the TF's colours mean (the "sRGB colours" checkbox)
//   step K | play | pause            a time series: show step K (from 0), play or pause (space)
//   series-fps F                     a time series: steps per second while playing
//   keyframe-add F | keyframe-delete F | keyframe-move F TO
//                                    the camera path: a keyframe of the current camera at path frame F,
//                                    deleted, moved (frames whole numbers in [0, 99999])
//   path-frame K | path-play | path-stop | path-fps FPS
//                                    show path frame K's camera; play the path from frame 0 (one path
//                                    frame a viewer frame, at most FPS a second); stop; the path's fps
//   quit
// Parsing checks every action's name, argument count and value (numbers finite, names of modes,
// structures and presets known, tf-range LO < HI, density >= 0, image types by extension,
// edit-shader paths relative); checkScript then checks what needs the viewer's context (the
// structure combination each line leads to, edit-shader files inside --shader-dir). All before
// frame 0, one line per error naming the file and line.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/structure_config.h"

namespace amrvk::viewer {

struct ScriptAction {
    uint64_t frame = 0;
    std::string name;               // e.g. "orbit"
    std::vector<std::string> args;  // as written (quotes removed)
    std::string where;              // "FILE:LINE" for messages
    double number(size_t i) const;  // args[i] as a number (checked when parsed)
};

// Argument i of a keyframe-* or path-frame action: a path frame, checked (one-line error).
uint32_t pathFrameArgument(const ScriptAction& a, size_t i);

// Actions in file order; frames must not decrease.
std::vector<ScriptAction> parseScript(const std::string& text, const std::string& fileName);
std::vector<ScriptAction> loadScript(const std::filesystem::path& path);

// What checkScript needs of the viewer: its shader directory and starting structure.
struct ScriptContext {
    std::filesystem::path shaderDir;  // --shader-dir (empty: none)
    scene::StructureConfig structure;  // the combination the viewer starts with
};
// Walks the script in order: every structure line must lead to a valid combination, every
// edit-shader line must name a file inside the shader sources. Throws "FILE:LINE: ...".
void checkScript(const std::vector<ScriptAction>& actions, const ScriptContext& context);

// The file edit-shader FILE may change: FILE relative to the shader directory `dir`
// (--shader-dir), resolved with symlinks followed, must be an existing regular file inside the
// shader sources (gpu::shaderSourceRoot(dir): the folder holding passes/, lib/, shared/). Throws a
// one-line error for no --shader-dir, an absolute path, or a path that leads outside (a shared
// script must not edit ~/.bashrc).
std::filesystem::path confinedShaderPath(const std::filesystem::path& dir, const std::string& file);

}  // namespace amrvk::viewer
