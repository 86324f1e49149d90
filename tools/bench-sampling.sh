#!/usr/bin/env bash
# Cost per path of every sampler against the dense floor, in one run (issue 12, points 1-2):
# the demo cloud and Enzo DD0018, ms, 128^2 x 8 spp, --grid 64, grid-dda, sw; the samplers are
# interleaved and repeated (REPEATS, default 3) and the median GPU time of each is reported with
# lookups per path, lookups per GPU second, null per real collision, violations and the ratio to
# dense. Usage: tools/bench-sampling.sh [OUT_DIR] (default out/bench-sampling); AMRVK_BIN overrides
# the binary (default build/bin/amrvk).
set -euo pipefail
source "$(dirname "$0")/bench-env.sh"
out="${1:-$here/out/bench-sampling}"
mkdir -p "$out"

common=(--mode ms --size 128x128 --spp 8 --grid 64 --traversal grid-dda --backend sw --light-dir 1 -1 2 3 3 3)
declare -A scenes=(
  [cloud]="$here/assets/samples/cloud.cells --tf ramp --tf-range 0 1"
  [enzo]="$enzo --field Density --tf ramp --tf-range 0 3 --density-scale 0.05"
)
samplers=(dense grid abr ext-brick)
for r in $(seq 1 "$repeats"); do
  for scene in cloud enzo; do
    read -r -a args <<<"${scenes[$scene]}"
    [ -e "${args[0]}" ] || { echo "skipping $scene: ${args[0]} not found" >&2; continue; }
    for s in "${samplers[@]}"; do
      "$bin" render "${args[@]}" "${common[@]}" --sampler "$s" -o "$out/$scene-$s.exr" \
        --json "$out/$scene-$s-$r.json" >/dev/null 2>&1
    done
  done
done
python3 - "$out" "$repeats" <<'EOF'
import json, statistics, sys, pathlib
out, repeats = pathlib.Path(sys.argv[1]), int(sys.argv[2])
print("| scene | sampler | GPU s (median of %d) | x dense | M paths/s | lookups / path | M lookups / GPU s | null / real | violations | device |" % repeats)
print("|---|---|---|---|---|---|---|---|---|---|")
for scene in ("cloud", "enzo"):
    runs = {}
    for s in ("dense", "grid", "abr", "ext-brick"):
        js = [json.load(open(p)) for p in sorted(out.glob(f"{scene}-{s}-*.json"))]
        if js: runs[s] = js
    if "dense" not in runs: continue
    dense = statistics.median(j["seconds"] for j in runs["dense"])
    for s, js in runs.items():
        t = statistics.median(j["seconds"] for j in js); j = js[0]
        print(f"| {scene} | {s} | {t:.3f} | {t / dense:.2f} | {j['paths'] / t / 1e6:.3f} | "
              f"{j['densityLookups'] / j['paths']:.2f} | {j['densityLookups'] / t / 1e6:.2f} | "
              f"{j['nullCollisions'] / max(1, j['realCollisions']):.2f} | {j['majorantViolations']} | {j['device']} |")
EOF
