#pragma once
// What a transfer function's colours mean (`--tf-colors`, the session's "tfColors", Python's
// tf_colors=): display colours, sRGB encoded, as ParaView, matplotlib and yt mean them (srgb, the
// default), or linear albedo as given (linear, what amrvk did before and what sessions of version
// 1 meant). The renderer is linear inside: albedoOf() turns a TF into the one it renders with,
// once, on the host, when a picture's TF is set; the TF itself (sessions, the editor, Python,
// the side panel's colour bar and histogram) keeps the colours as given.
#include <cstdint>
#include <string_view>

#include <glm/glm.hpp>

#include "scene/transfer_function.h"

namespace amrvk::scene {

enum class TfColors : uint8_t { Linear, Srgb };
// "linear" | "srgb"; else throws naming `option` and the value.
TfColors parseTfColors(std::string_view text, const char* option = "--tf-colors");
const char* tfColorsName(TfColors colors);

// The IEC 61966-2-1 curves on [0, 1] (values outside are clamped), in double.
double srgbToLinear(double display);
double linearToSrgb(double linear);

// The display-to-linear error albedoOf() allows between its nodes, in display units (a quarter
// of an 8-bit step): a picture of an opaque TF colour is within one 8-bit step of it.
inline constexpr double kTfColorTolerance = 0.25 / 255.0;

// The TF the renderer uses: `tf` itself for Linear; for Srgb the same alphas with every colour
// decoded to linear albedo, where the colour between two nodes is decode(mix(c0, c1, t)) (the
// map is interpolated as given, in display space, as ParaView does for RGB colour maps) within
// kTfColorTolerance: a segment gets the fewest uniformly spaced extra nodes (at most 63) that
// keep linear interpolation of the decoded colours that close at 3 points inside each piece. A TF
// of over 2^14 segments gets fewer (2^20 extra nodes in all at most, none past 2^20 segments):
// its segments are too narrow for the curve to show, and the work stays bounded by the input.
// Alpha is linear in the value as before (extra nodes carry mix(a0, a1, t)), so maxAlpha is
// unchanged up to float rounding. Steps (nodes sharing a position) stay steps.
TransferFunction albedoOf(const TransferFunction& tf, TfColors colors);
// The TF a picture renders for colour and opacity channels `tf` whose colours mean `colors`:
// albedoOf(tf.merged(), colors). The one place channels become the renderer's TF (the picture,
// the bench, the PNG legend).
TransferFunction albedoOf(const TfChannels& tf, TfColors colors);

}  // namespace amrvk::scene
