#include "session/render_command.h"

#include "scene/command_line.h"

namespace amrvk::session {

std::string renderCommandLine(const Session& s, const std::string& tfFile, const std::string& output) {
    using scene::shellQuote;
    std::string c = "amrvk render " + shellQuote(s.input);
    if (!s.field.empty()) c += " --field " + shellQuote(s.field);
    if (s.read.format != "auto") c += " --format " + shellQuote(s.read.format);
    if (s.read.nanPolicy == amr::NanPolicy::Drop) c += " --nan drop";
    if (s.read.rawDims != glm::ivec3(0))
        c += " --dims " + std::to_string(s.read.rawDims.x) + " " + std::to_string(s.read.rawDims.y) + " " +
             std::to_string(s.read.rawDims.z);
    if (!s.read.rawType.empty()) c += " --type " + shellQuote(s.read.rawType);
    if (s.read.rawThreshold != 0.0) c += " --threshold " + scene::formatNumber(s.read.rawThreshold);
    c += " --tf " + shellQuote(tfFile);
    c += scene::settingsOptions(s.settings, true);
    c += " --spp " + std::to_string(s.spp > 0 ? s.spp : 64);
    c += scene::structureOptions(s.structure);
    c += " -o " + shellQuote(output);
    return c;
}

}  // namespace amrvk::session
