// The closed sets of choices a shader is specialised for or reads from a buffer, defined once for
// C++ (shared::Mode::Ae, ...) and GLSL (kModeAe, ...). Values are specialization-constant values.
#ifndef AMRVK_KINDS_H
#define AMRVK_KINDS_H
#include "interop.h"

AMRVK_NAMESPACE_BEGIN

// Render modes (specialization constant kMode).
AMRVK_ENUM_BEGIN(Mode)
AMRVK_ENUM_VALUE(Mode, Ae, 0u)   // absorption + emission
AMRVK_ENUM_VALUE(Mode, Ss, 1u)   // single scattering
AMRVK_ENUM_VALUE(Mode, Ms, 2u)   // multiple scattering
AMRVK_ENUM_VALUE(Mode, Dvr, 3u)  // ray-marching baseline (ExaBrick's DVR): biased by its step
AMRVK_ENUM_END()

// Sample reconstruction structures (specialization constant kSampler).
AMRVK_ENUM_BEGIN(SamplerKind)
AMRVK_ENUM_VALUE(Sampler, ExtBrick, 0u)  // brick basis domains
AMRVK_ENUM_VALUE(Sampler, Abr, 1u)       // active brick regions
AMRVK_ENUM_VALUE(Sampler, Dense, 2u)     // uniform finest-level resampling, clamped trilinear (cost floor)
AMRVK_ENUM_VALUE(Sampler, Grid, 3u)      // macrocell grid of brick lists: no tree descent, ext-brick's values
AMRVK_ENUM_END()

// Majorant traversals (specialization constant kTraversal). grid-dda steps through the macrocell
// grid; the others query a set of boxes ("domains", each with a majorant) for the segment that
// starts at the current t: abr = ABR boxes, brick = strict brick bounds, ext-brick = brick basis
// domains (they overlap: the majorant is the maximum over the boxes covering t), grid-bvh =
// non-empty macrocells, kdtree = leaves of the TF-specific kd-tree.
AMRVK_ENUM_BEGIN(TraversalKind)
AMRVK_ENUM_VALUE(Traversal, GridDda, 0u)
AMRVK_ENUM_VALUE(Traversal, GridBvh, 1u)
AMRVK_ENUM_VALUE(Traversal, Abr, 2u)
AMRVK_ENUM_VALUE(Traversal, Brick, 3u)
AMRVK_ENUM_VALUE(Traversal, ExtBrick, 4u)
AMRVK_ENUM_VALUE(Traversal, KdTree, 5u)
AMRVK_ENUM_END()

// Back-ends of the box hierarchies (specialization constant kBackend): software BVH in GLSL or
// VK_KHR_ray_query over an AABB BLAS (only in the path_trace_rq shader variant). Auto is a host
// request (rq where the device has it), resolved before any shader sees it.
AMRVK_ENUM_BEGIN(Backend)
AMRVK_ENUM_VALUE(Backend, Sw, 0u)
AMRVK_ENUM_VALUE(Backend, Rq, 1u)
AMRVK_ENUM_VALUE(Backend, Auto, 2u)
AMRVK_ENUM_END()

// Shadow-ray transmittance estimators (RenderSettings::transmittance; ubrm: the path tracers'
// _ubrm shader variants, lib/unbiased_march.glsl): ratio tracking, or unbiased ray marching
// (Kettunen et al. 2021).
AMRVK_ENUM_BEGIN(Transmittance)
AMRVK_ENUM_VALUE(Transmittance, Ratio, 0u)
AMRVK_ENUM_VALUE(Transmittance, Ubrm, 1u)
AMRVK_ENUM_END()

// Control extinction of the trackers (RenderSettings::controlExtinction): none, or the exact
// minimum of the TF's extinction over each macrocell's value range (grid traversals; a minorant),
// with which free flight is decomposition tracking (Kutz et al. 2017) and ratio-tracked shadow rays
// residual ratio tracking (Novak et al. 2014). lib/tracking.glsl.
AMRVK_ENUM_BEGIN(ControlExtinction)
AMRVK_ENUM_VALUE(ControlExtinction, None, 0u)
AMRVK_ENUM_VALUE(ControlExtinction, Minorant, 1u)
AMRVK_ENUM_END()

AMRVK_ENUM_BEGIN(LightType)
AMRVK_ENUM_VALUE(Light, Directional, 0u)
AMRVK_ENUM_VALUE(Light, Point, 1u)
AMRVK_ENUM_END()

AMRVK_NAMESPACE_END
#endif
