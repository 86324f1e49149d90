#!/usr/bin/env bash
# Samples per invocation (issue 12, point 4): the same render with 1, 2, 4, 8 and 16 samples per
# GPU thread and dispatch (--samples-per-invocation), interleaved and repeated (REPEATS, default
# 3), median GPU time and paths/s against 1 per invocation in the same run; counters must agree
# (the same samples, regrouped). Then the viewer's responsiveness on Enzo with 1 and 8 per
# invocation (300 frames of the section-6 script, headless): interaction and idle frame times.
# Usage: tools/bench-invocation.sh [OUT_DIR] (default out/bench-invocation); AMRVK_BIN overrides
# the binary (default build/bin/amrvk).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:-$here/out/bench-invocation}"
bin="${AMRVK_BIN:-$here/build/bin/amrvk}"
data="${AMRVK_DATA_DIR:-$here/../shared/data/amr}"
repeats="${REPEATS:-3}"
mkdir -p "$out"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/amrvk-xdg-$UID}"
mkdir -p "$XDG_RUNTIME_DIR"

enzo="$data/enzo_tiny_cosmology/DD0018/DD0018"
common=(--mode ms --size 128x128 --spp 64 --backend sw --light-dir 1 -1 2 3 3 3)
declare -A scenes=(
  [cloud]="$here/assets/samples/cloud.cells --tf ramp --tf-range 0 1 --grid 64"
  [enzo]="$enzo --field Density --tf ramp --tf-range 0 3 --density-scale 0.05"
)
counts=(1 2 4 8 16)
for r in $(seq 1 "$repeats"); do
  for scene in cloud enzo; do
    read -r -a args <<<"${scenes[$scene]}"
    [ -e "${args[0]}" ] || { echo "skipping $scene: ${args[0]} not found" >&2; continue; }
    for s in "${counts[@]}"; do
      "$bin" render "${args[@]}" "${common[@]}" --samples-per-invocation "$s" -o "$out/$scene-$s.exr" \
        --json "$out/$scene-$s-$r.json" >/dev/null 2>&1
    done
  done
done
if [ -e "$enzo" ]; then
  printf '40 orbit 30 0\n41 orbit 30 0\n42 orbit 30 0\n43 orbit 30 0\n44 orbit 30 0\n45 orbit 30 0\n46 orbit 30 0\n47 orbit 30 0\n48 orbit 30 0\n49 orbit 30 0\n130 tf-range 0 3\n220 orbit 30 0\n221 orbit 30 0\n222 orbit 30 0\n' >"$out/orbit.txt"
  for s in 1 8; do
    "$bin" view "$enzo" --headless --field Density --tf ramp --tf-range 0 4 --density-scale 0.06 --mode ms \
      --light-dir 1 -1 2 5 4.5 3.8 --size 384x384 --frames 300 --script "$out/orbit.txt" \
      --samples-per-invocation "$s" --stats "$out/view-$s.json" >/dev/null 2>&1
  done
fi
python3 - "$out" "$repeats" <<'PY'
import json, statistics, sys, pathlib
out, repeats = pathlib.Path(sys.argv[1]), int(sys.argv[2])
print("| scene | samples / invocation | GPU s (median of %d) | x 1 per invocation | M paths/s | same counters | device |" % repeats)
print("|---|---|---|---|---|---|---|")
for scene in ("cloud", "enzo"):
    runs = {s: [json.load(open(p)) for p in sorted(out.glob(f"{scene}-{s}-*.json"))] for s in (1, 2, 4, 8, 16)}
    if not runs[1]: continue
    base = statistics.median(j["seconds"] for j in runs[1])
    keys = ("densityLookups", "realCollisions", "nullCollisions", "traversalSteps")
    for s, js in runs.items():
        t = statistics.median(j["seconds"] for j in js); j = js[0]
        same = all(j[k] == runs[1][0][k] for k in keys)
        print(f"| {scene} | {s} | {t:.3f} | {t / base:.2f} | {j['paths'] / t / 1e6:.3f} | {'yes' if same else 'NO'} | {j['device']} |")
views = {s: out / f"view-{s}.json" for s in (1, 8)}
if all(p.exists() for p in views.values()):
    print()
    print("| viewer, samples / invocation | stats |")
    print("|---|---|")
    for s, p in views.items():
        print(f"| {s} | {json.dumps(json.load(open(p)))[:400]} |")
PY
