#!/usr/bin/env bash
# Usage: render.sh AMRVK SOURCE_DIR SCRATCH. The render CLI end to end on the bundled sample:
# JSON statistics with every documented key, shaders loaded from --shader-dir (compiled from GLSL
# at run time), each image format, and one-line errors that leave no output behind.
set -u
amrvk="$1"; src="$2"; dir="$3"
rm -rf "$dir"; mkdir -p "$dir"
sample="$src/assets/samples/cloud.cells"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

common=(--size 16x12 --spp 2 --grid 16 --tf-range 0 1)
"$amrvk" render "$sample" "${common[@]}" -o "$dir/a.png" --json "$dir/a.json" || fail=1
check test -s "$dir/a.png"
check python3 - "$dir/a.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
keys = ["device", "width", "height", "spp", "mode", "traversal", "sampler", "seconds", "pathsPerSecond",
        "densityLookups", "realCollisions", "nullCollisions", "traversalSteps", "majorantViolations",
        "deviceMemoryBytes", "deviceMemoryPeakBytes", "meanRGB"]
missing = [k for k in keys if k not in j]
assert not missing, missing
assert j["width"] == 16 and j["height"] == 12 and j["spp"] == 2 and j["mode"] == "ms", j
assert j["majorantViolations"] == 0 and j["densityLookups"] > 0, j
assert len(j["meanRGB"]) == 3 and all(0 <= v < 10 for v in j["meanRGB"]), j
assert j["deviceMemoryPeakBytes"] >= j["deviceMemoryBytes"] > 0, j
assert j["backend"] in ("sw", "rq") and "hostMemoryPerStructure" in j, j
PY
# A box traversal with the kd-tree: its build time and per-structure bytes are reported.
"$amrvk" render "$sample" "${common[@]}" --traversal kdtree --kd-leaves 64 --backend sw -o "$dir/k.png" \
  --json "$dir/k.json" >/dev/null || fail=1
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["traversal"] == "kdtree" and j["activeTraversalBoxes"] > 0 and j["structureBuildSecondsPer"]["kdTree"] > 0 and j["hostMemoryPerStructure"]["kdTree"] > 0 and j["majorantViolations"] == 0, j' "$dir/k.json"
for ext in exr pfm; do
  "$amrvk" render "$sample" "${common[@]}" --mode ae --sampler abr -o "$dir/a.$ext" >/dev/null || fail=1
  check test -s "$dir/a.$ext"
done
"$amrvk" render "$sample" "${common[@]}" --mode ss --shader-dir "$src/shaders/passes" -o "$dir/s.pfm" >/dev/null || fail=1
check test -s "$dir/s.pfm"
"$amrvk" devices | grep -q "^0: " || { echo "FAIL: amrvk devices lists no device"; fail=1; }
# The dvr baseline (with gradient shading), the dense sampler, and the automatic structure choice.
"$amrvk" render "$sample" "${common[@]}" --mode dvr --dt 0.25 --dvr-shading --light-dir 1 0 0 1 1 1 \
  -o "$dir/d.pfm" --json "$dir/d.json" >/dev/null || fail=1
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["mode"] == "dvr" and j["densityLookups"] > 0, j' "$dir/d.json"
"$amrvk" render "$sample" "${common[@]}" --sampler dense --traversal grid-bvh --backend sw -o "$dir/n.pfm" \
  --json "$dir/n.json" >/dev/null || fail=1
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["sampler"] == "dense" and j["majorantViolations"] == 0 and j["hostMemoryPerStructure"]["denseGrid"] > 0 and "denseGrid" in j["deviceMemoryPerResource"] and "bricks" not in j["deviceMemoryPerResource"], j' "$dir/n.json"
"$amrvk" render "$sample" "${common[@]}" --traversal auto --sampler abr --backend sw -o "$dir/auto.png" \
  --json "$dir/auto.json" >/dev/null 2>"$dir/auto.err" || fail=1
check grep -q "traversal auto picked .*/abr/sw" "$dir/auto.err"
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["sampler"] == "abr" and j["backend"] == "sw" and j["traversal"] in ("grid-dda","grid-bvh","abr","brick","ext-brick","kdtree"), j' "$dir/auto.json"

expect "--mode 'xyz'" -- render "$sample" "${common[@]}" --mode xyz -o "$dir/x.png"
expect "unknown image type" -- render "$sample" "${common[@]}" -o "$dir/x.bmp"
expect "--size: '0x3'" -- render "$sample" --size 0x3 -o "$dir/x.png"
expect "--sampler 'bvh'" -- render "$sample" "${common[@]}" --sampler bvh -o "$dir/x.png"
expect "--traversal 'octree'" -- render "$sample" "${common[@]}" --traversal octree -o "$dir/x.png"
expect "--backend 'cuda'" -- render "$sample" "${common[@]}" --backend cuda -o "$dir/x.png"
expect "--kd-leaves: 0 is outside" -- render "$sample" "${common[@]}" --traversal kdtree --kd-leaves 0 -o "$dir/x.png"
expect "no such device" -- render "$sample" "${common[@]}" --device 99 -o "$dir/x.png"
expect "--dt: 0 is outside" -- render "$sample" "${common[@]}" --mode dvr --dt 0 -o "$dir/x.png"
expect "--sampler dense needs --traversal grid-dda or grid-bvh" -- render "$sample" "${common[@]}" --sampler dense --traversal abr -o "$dir/x.png"
expect "--dense-max-mib" -- render "$sample" "${common[@]}" --sampler dense --dense-max-mib 0 -o "$dir/x.png"
expect "cannot write" -- render "$sample" "${common[@]}" -o "$dir/missing-dir/x.png"
check test ! -e "$dir/x.png"
check test ! -e "$dir/x.bmp"
exit $fail
