// Lets the headers in shaders/shared compile as both C++20 and GLSL 460.
// C++: GLSL vector names map to GLM; AMRVK_STATIC_ASSERT checks layouts. GLSL: no-ops.
#ifndef AMRVK_INTEROP_H
#define AMRVK_INTEROP_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace amrvk::shared {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec3 = glm::ivec3;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
}  // namespace amrvk::shared
#define AMRVK_NAMESPACE_BEGIN namespace amrvk::shared {
#define AMRVK_NAMESPACE_END }
#define AMRVK_STATIC_ASSERT(cond) static_assert(cond, #cond)
#define AMRVK_CONST inline constexpr
#else
#define AMRVK_NAMESPACE_BEGIN
#define AMRVK_NAMESPACE_END
#define AMRVK_STATIC_ASSERT(cond)
#define AMRVK_CONST const
#endif

#endif
