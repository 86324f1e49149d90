// Buffer references shared by every pass (scalar layout, reached by device address).
#ifndef AMRVK_COMMON_GLSL
#define AMRVK_COMMON_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "shared/amr_gpu.h"
#include "shared/kinds.h"
#include "shared/render_params.h"

layout(buffer_reference, scalar) readonly buffer ParamsRef { RenderParams p; };
layout(buffer_reference, scalar) readonly buffer BrickRef { BrickGpu v[]; };
layout(buffer_reference, scalar) readonly buffer FloatRef { float v[]; };
layout(buffer_reference, scalar) buffer FloatRW { float v[]; };
layout(buffer_reference, scalar) readonly buffer UintRef { uint v[]; };
layout(buffer_reference, scalar) buffer UintRW { uint v[]; };
layout(buffer_reference, scalar) readonly buffer ValueRangeRef { ValueRangeGpu v[]; };
layout(buffer_reference, scalar) readonly buffer Vec4Ref { vec4 v[]; };
layout(buffer_reference, scalar) buffer AccumRW { AccumPixelGpu v[]; };
layout(buffer_reference, scalar) readonly buffer BvhRef { BvhNodeGpu v[]; };
layout(buffer_reference, scalar) readonly buffer AbrRef { AbrGpu v[]; };
layout(buffer_reference, scalar) readonly buffer AabbRef { AabbGpu v[]; };
layout(buffer_reference, scalar) buffer AabbRW { AabbGpu v[]; };

const float kInf = 1.0 / 0.0;

// The pass's RenderParams, read field by field where used (copying the whole struct into every
// invocation costs registers). Each entry point sets gParams first.
ParamsRef gParams;
#define P (gParams.p)

#endif
