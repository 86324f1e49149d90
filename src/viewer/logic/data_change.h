#pragma once
// What a change of session means for the data a viewer holds (window-free, unit-tested): the
// same data (nothing to read), the same data on another scale (read again with the new
// read.scale / read.logFloor: the viewer does it beside its event loop, keeping the camera), or
// other data (another input, field, format, NaN policy or raw-volume option: refused with the
// reason, since a viewer shows one data set; `amrvk view --session FILE` opens it).
#include <string>

#include "scene/transfer_function.h"
#include "scene/volume.h"
#include "session/session.h"

namespace amrvk::viewer {

enum class DataChange { None, Rescale, Other };

struct DataChangeCheck {
    DataChange kind = DataChange::None;
    std::string reason;  // Other: what differs, one line (names the input/option and both values)
};

// How `next` (a session to load, or the viewer's state after a panel or script edit) differs
// from `shown` in what is read. Inputs are compared as absolute, normalised paths; the log floor
// counts on the log scale only.
DataChangeCheck dataChange(const session::Session& shown, const session::Session& next);

// `tf` with its value range moved onto [lo, hi] (the shape kept: every node at the same relative
// position); lo == hi (a constant field) gives [lo, lo + 1]. Throws for non-finite or lo > hi.
scene::TfChannels refitTfRange(const scene::TfChannels& tf, float lo, float hi);

// `tf` for the same data read again on another scale (the viewer's log-scale checkbox, a script's
// `scale` or `log-floor`): `shown` is the data as it was shown, `next` as read on the new scale.
// A preset that follows the data (spiky, foggy, layers), exactly as it was fitted to `shown`, is
// fitted again to `next` (scene::makePreset(name, percentiles, histogram)): spiky and foggy sit at
// the same percentiles, so they mark the same cells on both scales, and layers are sized by the
// new scale's histogram, as `amrvk render --scale ...` fits them. Any other TF (edited, from a file,
// over a given range) keeps its shape over the new range (refitTfRange).
scene::TfChannels tfOnNewScale(const scene::TfChannels& tf, const scene::Volume& shown, const scene::Volume& next);

}  // namespace amrvk::viewer
