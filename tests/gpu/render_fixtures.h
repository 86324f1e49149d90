#pragma once
// Scenes for GPU tests: simple analytic media and their structures.
#include <glm/glm.hpp>

#include <string>
#include <utility>
#include <vector>

#include <memory>
#include <string_view>

#include "amr/model.h"
#include "gpu/context.h"
#include "render/renderer.h"
#include "scene/structure_config.h"
#include "scene/transfer_function.h"
#include "scene/volume.h"

namespace amrvk::test {

// A box of level-`level` cells over [lower, lower + dims * width) with one field, all values v.
inline amr::Model makeUniformBox(glm::ivec3 dims, int level, float v, glm::ivec3 lower = glm::ivec3(0)) {
    amr::Model m;
    m.source = "uniform-box";
    m.format = "test";
    const int w = 1 << level;
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) m.cells.push_back({lower + glm::ivec3(x, y, z) * w, level});
    m.fields.push_back({"v", std::vector<float>(m.cells.size(), v)});
    m.availableFields = {"v"};
    return m;
}

// grid-dda with `sampler` over macrocells `grid`, software back-end.
inline scene::StructureConfig gridDda(scene::SamplerKind sampler, const std::string& grid) {
    scene::StructureConfig c;
    c.sampler = sampler;
    c.grid = grid;
    return c;
}

// A renderer over `model` (the volume takes it: read the cells back from renderer->volume().model,
// which is in brick order) with `config` (back-end resolved).
inline std::unique_ptr<render::Renderer> makeRenderer(gpu::Context& ctx, amr::Model model,
                                                      const scene::StructureConfig& config,
                                                      std::string_view field = {}) {
    return std::make_unique<render::Renderer>(ctx, scene::makeVolume(std::move(model), field), config);
}

// Constant albedo and alpha for every value.
inline scene::TransferFunction constantTf(glm::vec3 albedo, float alpha) {
    return scene::TransferFunction({0.0f}, {glm::vec4(albedo, alpha)}, "constant-test");
}

// Zero alpha below the middle of the field's range, rising to `top` at its maximum: under it
// many macrocells, blocks and traversal boxes are empty (culled).
inline scene::TransferFunction zeroBelowMiddleTf(const scene::Volume& v, float top = 1.0f,
                                                 glm::vec3 albedo = glm::vec3(1.0f)) {
    const amr::FieldStats& st = v.fieldStats;
    const float mid = 0.5f * (st.minValue + st.maxValue);
    return scene::TransferFunction({st.minValue, mid, st.maxValue},
                                   {glm::vec4(1, 1, 1, 0), glm::vec4(1, 1, 1, 0), glm::vec4(albedo, top)}, "half");
}

// Back-ends this device can run: sw always, rq where the device has VK_KHR_ray_query.
inline std::vector<scene::Backend> availableBackends(const gpu::Context& ctx) {
    std::vector<scene::Backend> out{scene::Backend::Sw};
    if (ctx.hasRayQuery()) out.push_back(scene::Backend::Rq);
    return out;
}

// Every traversal x sampler x available back-end, with the given grid and kd-tree size.
inline std::vector<scene::StructureConfig> allStructureConfigs(const gpu::Context& ctx, const std::string& grid,
                                                                uint32_t kdLeaves) {
    std::vector<scene::StructureConfig> out;
    for (scene::TraversalKind t : scene::allTraversals())
        for (scene::SamplerKind s : scene::allSamplers())
            for (scene::Backend b : availableBackends(ctx)) {
                scene::StructureConfig c;
                c.traversal = t;
                c.sampler = s;
                c.backend = b;
                c.grid = grid;
                c.kdLeaves = kdLeaves;
                out.push_back(c);
            }
    return out;
}

// Every sampler x available back-end.
inline std::vector<std::pair<scene::SamplerKind, scene::Backend>> samplerBackendCombos(const gpu::Context& ctx) {
    std::vector<std::pair<scene::SamplerKind, scene::Backend>> out;
    for (scene::SamplerKind s : scene::allSamplers())
        for (scene::Backend b : availableBackends(ctx)) out.emplace_back(s, b);
    return out;
}

}  // namespace amrvk::test
