#!/usr/bin/env bash
# Usage: tools/same_images.sh OLD_AMRVK NEW_AMRVK [DATA_DIR]. A refactor's check (issue 54, point 6):
# the same pictures rendered by two builds of amrvk, compared byte for byte (same seed, same
# samples: a change that claims no behaviour change must give identical files). Covers the modes,
# both shadow estimators, the control extinction, dvr with shading, a kd-tree, the structure options
# (sampler, back-end, grid, sub-majorants), the first frame and
# the Enzo sample where DATA_DIR (default ../shared/data/amr) has it. Exits 1 naming each case that
# differs. An ASan build may be the old side (ASAN_OPTIONS=detect_leaks=0 is set for it).
set -uo pipefail
old=$1 new=$2
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data=${3:-$here/../shared/data/amr}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp} ASAN_OPTIONS=detect_leaks=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
s=$here/assets/samples/cloud.cells
cases=("$s --size 48x32 --spp 8 --seed 3"
       "$s --size 48x32 --spp 8 --mode ss --light-dir 1 -1 2 3 3 3 --density-scale 3"
       "$s --size 48x32 --spp 8 --mode ms --control-extinction minorant --tf spiky"
       "$s --size 48x32 --spp 4 --mode dvr --dt 0.25 --dvr-shading"
       "$s --size 48x32 --spp 8 --traversal kdtree --kd-leaves 512 --g 0.5 --fov 30"
       "$s --size 48x32 --spp 8 --mode ae --transmittance ubrm --tf-colors linear"
       "$s --size 48x32 --spp 8 --sampler abr --backend sw --grid 12x10x8 --sub-majorants off --traversal grid-bvh"
       "$s --size 48x32 --spp 8 --sampler ext-brick --grid 16 --sub-majorants 4 --tf spiky"
       "$s --size 48x32 --first-frame")
enzo=$data/enzo_tiny_cosmology/DD0018/DD0018
[ -e "$enzo" ] && cases+=("$enzo --size 48x32 --spp 4 --mode ss --light-dir 1 1 1 2 2 2")
status=0
for i in "${!cases[@]}"; do
  # shellcheck disable=SC2086  # each case is a word list
  "$old" render ${cases[$i]} -o "$work/old$i.pfm" >/dev/null 2>"$work/old$i.err" || { echo "case $i: the old build failed: $(tail -1 "$work/old$i.err")"; status=1; continue; }
  # shellcheck disable=SC2086
  "$new" render ${cases[$i]} -o "$work/new$i.pfm" >/dev/null 2>"$work/new$i.err" || { echo "case $i: the new build failed: $(tail -1 "$work/new$i.err")"; status=1; continue; }
  if cmp -s "$work/old$i.pfm" "$work/new$i.pfm"; then echo "same: ${cases[$i]#"$here/"}"; else echo "DIFFER: ${cases[$i]}"; status=1; fi
done
exit $status
