#!/usr/bin/env bash
# Usage: check_majorants.sh AMRVK SOURCE_DIR SCRATCH [DATA_DIR]. `amrvk info --check-majorants`
# (issue 31, point 1) on every real sample beside the checkout and on a 10^6-cell cloud, for every
# TF preset: every traversal's boxes (macrocells, ABRs, brick bounds and domains, kd leaves per TF,
# the sub-boxes of the macrocells each TF makes loose, issue 51)
# hold the exact reconstruction with room for the GPU's float error. Its power against planted
# defects is shown in tests/cpu/majorant_check_test.cpp. Samples that are absent are skipped.
set -u
amrvk="$1"; src="$2"; dir="$3"; data="${4:-${AMRVK_DATA_DIR:-$src/../shared/data/amr}}"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# One data set: the check passes (exit 0), reports every box set, each "ok", and its JSON agrees.
# Where spiky makes macrocells loose enough (the clouds, Enzo), its sub-boxes are among them.
checkSet() {
  local name="$1"; shift
  if ! "$amrvk" info "$@" --check-majorants --json >"$dir/$name.json" 2>"$dir/$name.err"; then
    echo "FAIL: amrvk info $* --check-majorants: $(tail -3 "$dir/$name.err")"; fail=1; return
  fi
  local needSub=0
  case "$name" in cloud1e6|bundled|enzo*) needSub=1 ;; esac
  if python3 - "$dir/$name.json" "$needSub" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
sets = j["majorantCheck"]
names = {s["boxes"].split()[0] for s in sets}
assert {"macrocells", "abrs", "brick", "kd"} <= names <= {"macrocells", "abrs", "brick", "kd", "sub-boxes"}, names
assert j["ok"] and all(s["ok"] for s in sets), [s for s in sets if not s["ok"]]
presets = {"ramp", "grey", "spiky", "foggy", "constant", "empty", "layers"}
assert {s["builtForTf"] for s in sets if s["boxes"] == "kd leaves"} == presets
assert all({t["tf"] for t in s["tfs"]} == presets for s in sets if s["boxes"] not in ("kd leaves", "sub-boxes"))
# Sub-boxes where a TF makes macrocells loose (spiky always does), each checked under its own TF.
sub = [s for s in sets if s["boxes"] == "sub-boxes"]
assert all([t["tf"] for t in s["tfs"]] == [s["builtForTf"]] for s in sub), sub
assert sys.argv[2] == "0" or "spiky" in {s["builtForTf"] for s in sub}, sub
assert all(s["withData"] > 0 and s["vertices"] >= s["withData"] for s in sets), sets
print(f"ok: {j['source']}: {len(sets)} box sets, {sum(s['count'] for s in sets)} boxes, "
      f"{sum(s['vertices'] for s in sets)} values")
PY
  then :; else echo "FAIL: $name: $(cat "$dir/$name.json" | head -c 400)"; fail=1; fi
}

# Under the sanitizers (tools/run.sh sanitize sets AMRVK_SANITIZER_RUN=1) what is tested is the
# check's own memory safety and defined behaviour: the bundled sample and Enzo only. The Release run
# checks every set (the 10^6-cell cloud alone takes 34 s there, several times that under ASan).
quick="${AMRVK_SANITIZER_RUN:-0}"
if [ "$quick" = 0 ]; then
  "$amrvk" gen cloud --cells 1e6 --seed 1 -o "$dir/cloud1e6" >/dev/null || fail=1
  checkSet cloud1e6 "$dir/cloud1e6.cells"
fi
checkSet bundled "$src/assets/samples/cloud.cells"
sets=(
  "enzo|enzo_tiny_cosmology/DD0018/DD0018|--field Density"
  "enzo-log|enzo_tiny_cosmology/DD0018/DD0018|--field Density --scale log"
  "amrex|amrex_pelelm_3d/example_plt_3d|--field temp"
  "chombo-100|chombo_mushy_layer_2d/plt000100.2d.hdf5|--field Temperature"
  "chombo-25000|chombo_mushy_layer_2d/plt025000.2d.hdf5|--field Temperature"
  "carpet|carpet_wavetoy_3d/CarpetWaveToyCheckpoint_test.it_64.h5|--field WAVETOY::phi"
  "ramses-galaxy|ramses_galaxy_3d/output_00010|--field density"
  "ramses-multimat|ramses_multimat_2d/output_00001|--field density"
  "ramses-sedov|ramses_sedov_2d/output_00002|--field density"
)
for s in "${sets[@]}"; do
  IFS='|' read -r name path opts <<<"$s"
  if [ "$quick" != 0 ] && [ "$name" != enzo ]; then continue; fi
  if [ ! -e "$data/$path" ]; then echo "skip: $data/$path is absent"; continue; fi
  # shellcheck disable=SC2086
  checkSet "$name" "$data/$path" $opts
done

# A bad TF list is one line naming it; the check options apply only with --check-majorants.
expect "nosuchpreset" -- info "$src/assets/samples/cloud.cells" --check-majorants --tfs nosuchpreset
expect "--tfs applies only with --check-majorants" -- info "$src/assets/samples/cloud.cells" --tfs spiky
exit $fail
