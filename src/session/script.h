#pragma once
// Viewer automation (`amrvk view --script FILE`): one action per line, "FRAME ACTION ARGS...",
// run when the viewer reaches frame FRAME (0 = before the first frame); '#' starts a comment;
// arguments with spaces go in double quotes (\" and \\ inside). Actions:
//   orbit DX DY | pan DX DY          mouse drags in pixels
//   zoom STEPS                       wheel steps (> 0 closer)
//   tf-preset NAME | tf-range LO HI | density SCALE
//   mode ae|ss|ms|dvr | traversal T | sampler S | backend B | grid G
//   edit-shader FILE FIND REPLACE    replace the first FIND in FILE (under --shader-dir) and save it
//   reload                           recompile the shaders now (the watcher also does on a save)
//   screenshot FILE                  the accumulated image, no UI (.png, .exr, .pfm)
//   capture-window FILE              the window as shown, UI included (.png; no-op with --headless)
//   save-session FILE                the current state as a session file (render it with amrvk render --session)
//   quit
// Parsing checks every action's name and argument count and every number, one line per error
// naming the file and line.
#include <filesystem>
#include <string>
#include <vector>

namespace amrvk::session {

struct ScriptAction {
    uint64_t frame = 0;
    std::string name;               // e.g. "orbit"
    std::vector<std::string> args;  // as written (quotes removed)
    std::string where;              // "FILE:LINE" for messages
    double number(size_t i) const;  // args[i] as a number (checked when parsed)
};

// Actions in file order; frames must not decrease.
std::vector<ScriptAction> parseScript(const std::string& text, const std::string& fileName);
std::vector<ScriptAction> loadScript(const std::filesystem::path& path);

}  // namespace amrvk::session
