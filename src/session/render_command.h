#pragma once
// The `amrvk render` command line that renders a session's picture offline (the viewer's "copy as
// command"). The TF travels as a ParaView JSON file the caller has written (tfFile).
#include <string>

#include "session/session.h"

namespace amrvk::session {

std::string renderCommandLine(const Session& s, const std::string& tfFile, const std::string& output);

}  // namespace amrvk::session
