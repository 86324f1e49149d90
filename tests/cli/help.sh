#!/usr/bin/env bash
# Usage: help.sh AMRVK SCRATCH. Every command's --help exits 0 with its usage line and lists each
# of its options; defaults are shown; the options render and bench share are declared once, so
# their help lines are identical in both.
set -u
amrvk="$1"; dir="$2"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

declare -A options=(
  [info]="--format --field --nan --dims --type --threshold --grid --bricks --traversal --sampler --json"
  [gen]="--cells --seed -o,--output --block --levels --field --time"
  [convert]="--format --field --nan --dims --type --threshold -o,--output"
  [render]="--format --field --nan --dims --type --threshold --mode --dt --dvr-shading --transmittance --control-extinction --size --seed --spp --tf --tf-colors
            --tf-preset --tf-range --traversal --sampler --backend --grid --kd-leaves --dense-max-mib
            --density-scale --g --ambient --background --light-dir --light-point --camera --fov -o,--output
            --json --first-frame --device --shader-dir --validation --series-range --orbit --frames --fps --frames-dir
            --legend --legend-place --legend-title --legend-units --legend-font"
  [bench]="--field -o,--output --tfs --tf-colors --tf-range --modes --traversals --samplers --backends --transmittances --control-extinctions --size --seed --frames
           --warmup --reference-spp --target-rmse --dvr-steps --grid-sweep --no-dense --auto --grid --kd-leaves
           --dense-max-mib --density-scale --g --ambient --background --light-dir --light-point --camera --fov
           --device --shader-dir --validation"
  [devices]="--json"
)
for command in "${!options[@]}"; do
  "$amrvk" "$command" --help >"$dir/$command.raw" 2>&1 || { echo "FAIL: amrvk $command --help exits $?"; fail=1; }
  # One line per option: wrapped description lines (indented past the names) joined to theirs.
  awk '/^      / && prev != "" { sub(/^ +/, " "); prev = prev $0; next }
       { if (NR > 1) print prev; prev = $0 } END { print prev }' "$dir/$command.raw" >"$dir/$command.txt"
  check grep -q "^usage: amrvk $command " "$dir/$command.txt"
  for option in ${options[$command]}; do
    grep -qE -- "^  $option( |$)" "$dir/$command.txt" || { echo "FAIL: amrvk $command --help lacks $option"; fail=1; }
  done
done
check grep -qE -- "^  --spp N .*default: 64\)" "$dir/render.txt"
check grep -qE -- "^  --size WxH .*default: 512x512\)" "$dir/render.txt"
check grep -qE -- "^  --backend .*default: auto\)" "$dir/render.txt"
check grep -qE -- "^  --frames N .*default: 100\)" "$dir/bench.txt"
check grep -qE -- "^  --block B .*default: 8\)" "$dir/gen.txt"
# Shared declarations: the same help line in render and bench.
for option in --density-scale --g --ambient --background --light-dir --light-point --camera --fov --grid \
              --kd-leaves --dense-max-mib --tf-range --seed --device --shader-dir --validation; do
  a=$(grep -E -- "^  $option( |$)" "$dir/render.txt")
  b=$(grep -E -- "^  $option( |$)" "$dir/bench.txt")
  [ -n "$a" ] && [ "$a" = "$b" ] || { echo "FAIL: $option differs: render '$a' / bench '$b'"; fail=1; }
done
exit $fail
