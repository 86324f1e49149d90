#pragma once
// Transfer function files: ParaView colour-map preset JSON (read and written) and `.xf` (read),
// and loadTransferFunction, which takes a preset name or either file. The TF itself:
// scene/transfer_function.h; presets: scene/tf_presets.h.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "amr/value_percentiles.h"
#include "amr/volume_histogram.h"
#include "scene/transfer_function.h"

namespace amrvk::scene {

// Magic of the owlExaStitcher / cuteeOwl / barney `.xf` format.
inline constexpr uint64_t kXfMagic = 0x0000001235abc000ull;

// ParaView colour-map preset JSON: an array of presets or one preset object with "Name",
// "RGBPoints" [x, r, g, b, ...] and optional "Points" [x, opacity, midpoint, sharpness, ...].
// Colour and opacity nodes are merged into the union of their positions (each channel evaluated
// there, which is exact since each is linear between its own nodes). Without "Points", opacity
// rises linearly 0 -> 1 over the colour range. Midpoint and sharpness are ignored: opacity is
// always linear between its nodes. An empty presetName picks the first preset in the file.
TransferFunction loadParaViewPreset(const std::filesystem::path& path, std::string_view presetName = {});

// Every preset of a ParaView JSON file that amrvk can use; the others (e.g. indexed colour maps)
// are listed in `skipped` with the reason, one line each.
struct ParaViewPresets {
    std::vector<TfChannels> presets;
    std::vector<std::string> skipped;
};
ParaViewPresets loadParaViewPresets(const std::filesystem::path& path);
// One preset object given as JSON text (a session's "transferFunction"); errors name `where`.
TfChannels parseParaViewPreset(const std::string& jsonText, const std::string& where);
// One preset as a ParaView JSON file's text (an array of one object; opacity midpoint 0.5 and
// sharpness 0, which is linear). loadParaViewPreset reads it back to the same TF.
std::string paraViewPresetJson(const TfChannels& channels);

// `.xf` transfer function, either format:
// - magic 0x1235abc000: uint64 magic, float opacityScale, float absDomain[2], float relDomain[2]
//   (percent), int32 N, float rgba[N][4]. The N nodes are spaced uniformly over
//   [absLo + relLo/100 (absHi - absLo), absLo + relHi/100 (absHi - absLo)]: relDomain is applied
//   once (exaStitcher's headless viewer applies it twice, a bug not reproduced here). Alpha is
//   multiplied by 1.1^(opacityScale - 100) as exaStitcher/cuteeOwl do (file value 100 => 1).
// - owlExaBrick: exactly 512 bytes, float alpha[128]; albedo grey 0.8, the nodes spaced
//   uniformly over [dataLo, dataHi].
TransferFunction loadXf(const std::filesystem::path& path, float dataLo, float dataHi);

// A preset name, or a file: `.xf` (by magic or extension) or ParaView JSON (by extension or a
// leading '[' / '{'). Presets are mapped onto [dataLo, dataHi] (makePreset(name, lo, hi)); files
// keep their own positions. presetName selects a preset inside a ParaView JSON file.
TransferFunction loadTransferFunction(std::string_view spec, float dataLo, float dataHi,
                                      std::string_view presetName = {});
// The same fitted to the data: presets through makePreset(name, percentiles, volumes), files as
// above over [P0, P100] (the field's range; an owlExaBrick alpha table spans it).
TransferFunction loadTransferFunction(std::string_view spec, const amr::Percentiles& data,
                                      const amr::VolumeHistogram& volumes, std::string_view presetName = {});

}  // namespace amrvk::scene
