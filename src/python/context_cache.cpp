#include "python/context_cache.h"

#include <map>
#include <mutex>
#include <string>

namespace amrvk::python {

std::shared_ptr<gpu::Context> contextFor(const gpu::ContextOptions& o) {
    static std::mutex mutex;
    static std::map<std::string, std::weak_ptr<gpu::Context>> contexts;
    const std::string key = o.device + "|" + std::to_string(o.validation) + "|" + std::to_string(o.gpuTimeoutSeconds) +
                            "|" + std::to_string(o.samplesPerInvocation) + "|" + std::to_string(o.pathRegeneration);
    std::lock_guard lock(mutex);
    if (auto ctx = contexts[key].lock()) return ctx;
    auto ctx = std::make_shared<gpu::Context>(o);
    contexts[key] = ctx;
    return ctx;
}

gpu::ContextOptions contextOptions(const py::kwargs& kw) {
    gpu::ContextOptions o;
    auto has = [&](const char* k) { return kw.contains(k) && !kw[k].is_none(); };
    if (has("device")) o.device = py::str(kw["device"]);
    if (has("validation")) o.validation = keywordArg<bool>(kw["validation"], "validation", "True or False");
    if (has("gpu_timeout")) o.gpuTimeoutSeconds = keywordArg<double>(kw["gpu_timeout"], "gpu_timeout", kNumber);
    if (has("samples_per_invocation"))
        o.samplesPerInvocation =
            uint32_t(wholeArg(kw["samples_per_invocation"], "samples_per_invocation", 1, UINT32_MAX));
    if (has("path_regeneration"))
        o.pathRegeneration = keywordArg<bool>(kw["path_regeneration"], "path_regeneration", "True or False");
    return o;
}

}  // namespace amrvk::python
