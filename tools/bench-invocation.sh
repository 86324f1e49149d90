#!/usr/bin/env bash
# Work per dispatch (issue 12, point 4; docs/benchmarks.md section 10): the same render with 1, 2,
# 4, 8 and 16 samples per GPU thread and dispatch (--samples-per-invocation), interleaved and
# repeated (REPEATS, default 3); median GPU time and paths/s against 1 per invocation in the same
# run; the counters must agree (the same samples, regrouped). With AMRVK_BIN_OPT (a binary built
# with -DAMRVK_SPIRV_OPT=ON) the runs at 1 and 8 are repeated with spirv-opt's SPIR-V. Then the
# viewer's responsiveness on Enzo with 1 and 8 per invocation (300 frames of the section-6 script,
# headless): interaction and idle frame times.
# Usage: tools/bench-invocation.sh [OUT_DIR] (default out/bench-invocation). Environment: AMRVK_BIN
# (default build/bin/amrvk), AMRVK_BIN_OPT, SIZE (default 128x128), SPP (default 64), REPEATS.
set -euo pipefail
source "$(dirname "$0")/bench-env.sh"
out="${1:-$here/out/bench-invocation}"
bin_opt="${AMRVK_BIN_OPT:-}"
mkdir -p "$out"
rm -f "$out"/*.json

common=(--mode ms --size "${SIZE:-128x128}" --spp "${SPP:-64}" --backend sw --light-dir 1 -1 2 3 3 3)
declare -A scenes=(
  [cloud]="$here/assets/samples/cloud.cells --tf ramp --tf-range 0 1 --grid 64"
  [enzo]="$enzo --field Density --tf ramp --tf-range 0 3 --density-scale 0.05"
)
# variant = SPIR-V form (plain | opt) and samples per invocation.
variants=(plain:1 plain:2 plain:4 plain:8 plain:16)
[ -n "$bin_opt" ] && variants+=(opt:1 opt:8)
for r in $(seq 1 "$repeats"); do
  for scene in cloud enzo; do
    read -r -a args <<<"${scenes[$scene]}"
    [ -e "${args[0]}" ] || { echo "skipping $scene: ${args[0]} not found" >&2; continue; }
    for v in "${variants[@]}"; do
      form="${v%%:*}" s="${v##*:}"
      exe="$bin"; [ "$form" = opt ] && exe="$bin_opt"
      "$exe" render "${args[@]}" "${common[@]}" --samples-per-invocation "$s" -o "$out/$scene.exr" \
        --json "$out/$scene-$form-$s-$r.json" >/dev/null 2>&1
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
python3 - "$out" "$repeats" "${variants[@]}" <<'PY'
import json, statistics, sys, pathlib
out, repeats, variants = pathlib.Path(sys.argv[1]), int(sys.argv[2]), sys.argv[3:]
print("| scene | SPIR-V | samples / invocation | GPU s (median of %d) | x plain, 1 per invocation | M paths/s | first sample s | same counters | device |" % repeats)
print("|---|---|---|---|---|---|---|---|---|")
keys = ("densityLookups", "realCollisions", "nullCollisions", "traversalSteps")
for scene in ("cloud", "enzo"):
    runs = {v: [json.load(open(p)) for p in sorted(out.glob(f"{scene}-{v.replace(':', '-')}-*.json"))] for v in variants}
    if not runs.get("plain:1"): continue
    ref = runs["plain:1"]
    base = statistics.median(j["seconds"] for j in ref)
    for v, js in runs.items():
        if not js: continue
        form, s = v.split(":")
        t = statistics.median(j["seconds"] for j in js); j = js[0]
        first = statistics.median(j["firstSampleSeconds"] for j in js)
        same = all(j[k] == ref[0][k] for k in keys)
        name = "spirv-opt -O" if form == "opt" else "unoptimised"
        print(f"| {scene} | {name} | {s} | {t:.3f} | {t / base:.2f} | {j['paths'] / t / 1e6:.3f} | {first:.2f} | {'yes' if same else 'NO'} | {j['device']} |")
views = {s: out / f"view-{s}.json" for s in (1, 8)}
if all(p.exists() for p in views.values()):
    print()
    print("| viewer, samples / invocation | stats |")
    print("|---|---|")
    for s, p in views.items():
        print(f"| {s} | {json.dumps(json.load(open(p)))[:400]} |")
PY
