#pragma once
// Vulkan contexts for the Python Renderers: one per device choice, shared by the renderers that
// name it (a second Renderer on the same device reuses the first one's instance and device).
#include <memory>

#include "gpu/context.h"
#include "python/arguments.h"

namespace amrvk::python {

// The context for options `o`: the one a live renderer already holds for the same device,
// validation, gpu_timeout, samples_per_invocation and path_regeneration, else a new one made from
// `o`. Thread-safe; held weakly, so a context is destroyed with the last renderer that uses it.
std::shared_ptr<gpu::Context> contextFor(const gpu::ContextOptions& o);

// The context options of Renderer(...)'s keywords (device, validation, gpu_timeout,
// samples_per_invocation, path_regeneration; None = the default); other keywords are ignored.
gpu::ContextOptions contextOptions(const py::kwargs& kw);

}  // namespace amrvk::python
