// Lets the headers in shaders/shared compile as both C++20 and GLSL 460, so every type and enum
// the GPU reads is defined once. C++: GLSL vector names map to GLM; AMRVK_STATIC_ASSERT checks
// layouts; an AMRVK_ENUM is an `enum class Name : uint32_t`. GLSL: no-ops, and each enum value
// becomes a constant k<Prefix><Value> (e.g. kTraversalGridDda) for specialization constants.
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
using uvec3 = glm::uvec3;
using uvec4 = glm::uvec4;
}  // namespace amrvk::shared
#define AMRVK_NAMESPACE_BEGIN namespace amrvk::shared {
#define AMRVK_NAMESPACE_END }
#define AMRVK_STATIC_ASSERT(cond) static_assert(cond, #cond)
#define AMRVK_CONST inline constexpr
#define AMRVK_ENUM_BEGIN(Name) enum class Name : uint32_t {
#define AMRVK_ENUM_VALUE(Prefix, Value, number) Value = number,
#define AMRVK_ENUM_END() };
#else
#define AMRVK_NAMESPACE_BEGIN
#define AMRVK_NAMESPACE_END
#define AMRVK_STATIC_ASSERT(cond)
#define AMRVK_CONST const
#define AMRVK_ENUM_BEGIN(Name)
#define AMRVK_ENUM_VALUE(Prefix, Value, number) const uint k##Prefix##Value = number;
#define AMRVK_ENUM_END()
#endif

#endif
