#!/usr/bin/env bash
# Usage: carpet.sh AMRVK SCRATCH [DATA_DIR]. The Carpet sample through the CLI (issue 33, point 6):
# `amrvk info` detects it as Carpet and reports its levels and points, a small render of it has
# lit pixels and no majorant violation, and --format carpet on another HDF5 file is one line.
set -u
amrvk="$1"; dir="$2"; data="${3:-${AMRVK_DATA_DIR:-}}"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
sample="$data/carpet_wavetoy_3d/CarpetWaveToyCheckpoint_test.it_64.h5"
if [ ! -e "$sample" ]; then echo "skip: $sample is absent"; exit 77; fi

"$amrvk" info "$sample" >"$dir/info.txt" || fail=1
cat "$dir/info.txt"
check grep -q "carpet" "$dir/info.txt"
check grep -q "WAVETOY::phi" "$dir/info.txt"
check grep -q "pointsPerLevel.*8000 15625 15625 15625" "$dir/info.txt"
check grep -q "activePointsPerLevel.*4096 9261 9261 9261" "$dir/info.txt"
check grep -q "22478" "$dir/info.txt"

"$amrvk" render "$sample" --size 32x32 --spp 2 -o "$dir/carpet.png" --json "$dir/carpet.json" >/dev/null || fail=1
check test -s "$dir/carpet.png"
check python3 - "$dir/carpet.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert j["width"] == 32 and j["height"] == 32 and j["spp"] == 2, j
assert j["majorantViolations"] == 0 and j["densityLookups"] > 0 and j["realCollisions"] > 0, j
assert any(v > 0 for v in j["meanRGB"]), j
PY

# A Chombo plotfile is not a Carpet file: one line naming it.
chombo="$data/chombo_mushy_layer_2d/plt000100.2d.hdf5"
if [ -e "$chombo" ]; then
  expect "not a Carpet file" -- info "$chombo" --format carpet
fi
exit $fail
