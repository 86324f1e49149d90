#pragma once
// `amrvk render` options as text: the exact command line that reproduces a picture (the viewer's
// "copy as command", the bench's reference commands: session::renderCommandLine). Numbers are written with enough digits to
// read back the same double; arguments are quoted for a POSIX shell where needed.
#include <string>

#include "scene/render_settings.h"
#include "scene/structure_config.h"

namespace amrvk::scene {

std::string shellQuote(const std::string& text);
std::string formatNumber(double v);

// " --mode M --size WxH --seed S [--camera ... --fov F] [--density-scale ...] --background ..." for
// every setting that differs from the default (the camera and fov always when withCamera; the
// background always, since render's default is not RenderSettings').
std::string settingsOptions(const RenderSettings& settings, bool withCamera);
// " --traversal T --sampler S --backend B [--grid G] [--kd-leaves N] [--dense-max-mib M]".
std::string structureOptions(const StructureConfig& config);

}  // namespace amrvk::scene
