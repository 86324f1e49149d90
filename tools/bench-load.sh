#!/usr/bin/env bash
# Time to the first sample and peak host memory against the cell count (issue 12, point 3):
# synthetic clouds of 10^6, 10^7 and 10^8 cells (`amrvk gen cloud --seed 1`, generated once into
# OUT_DIR), each rendered with the defaults at 64x64 x 1 spp (ms) after a warm-up read (so the files
# are in the page cache: this measures the program, not the disk). Reports the command's wall time
# to the first sample, reading + per-cell validation, the structure build (bricks, brick grid,
# macrocell ranges), peak resident memory (lavapipe: device memory is host memory and counted)
# and bytes per cell. Usage: tools/bench-load.sh [OUT_DIR] (default out/bench-load); CELLS
# overrides the list (e.g. CELLS="1e6 1e7"); AMRVK_BIN the binary (default build/bin/amrvk).
set -euo pipefail
source "$(dirname "$0")/bench-env.sh"
out="${1:-$here/out/bench-load}"
read -r -a counts <<<"${CELLS:-1e6 1e7 1e8}"
mkdir -p "$out"

for n in "${counts[@]}"; do
  base="$out/cloud-$n"
  [ -e "$base.cells" ] || "$bin" gen cloud --cells "$n" --seed 1 -o "$base" >/dev/null 2>&1
  cat "$base.cells" "$base.scalars" >/dev/null  # warm the page cache
  "$bin" render "$base.cells" --size 64x64 --spp 1 --mode ms -o "$out/cloud-$n.png" --json "$out/cloud-$n.json" \
    >/dev/null 2>&1
done
python3 - "$out" "${counts[@]}" <<'PY'
import json, sys, pathlib
out = pathlib.Path(sys.argv[1])
print("| cells | first sample s | read + validate s | bricks s | brick grid s | macrocell ranges s | peak host MB | B/cell | device |")
print("|---|---|---|---|---|---|---|---|---|")
for n in sys.argv[2:]:
    j = json.load(open(out / f"cloud-{n}.json"))
    per = j["structureBuildSecondsPer"]
    cells = (out / f"cloud-{n}.cells").stat().st_size // 16
    print(f"| {cells:,} | {j['firstSampleSeconds']:.1f} | {j['readSeconds']:.2f} | {per['bricks']:.2f} | "
          f"{per['brickGrid']:.2f} | {per['macrocells']:.2f} | {j['peakHostBytes'] / 1e6:.0f} | "
          f"{j['peakHostBytes'] / cells:.1f} | {j['device']} |")
PY
