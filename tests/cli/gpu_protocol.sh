#!/usr/bin/env bash
# Usage: gpu_protocol.sh AMRVK SOURCE_DIR SCRATCH. The GPU protocol in one command (issue 31, point
# 8): `tools/gpu-protocol.sh prepare` carries this amrvk (AMRVK_PROTOCOL_BIN: no second build here;
# it has MPI's libraries, hence the 64 MiB limit) with its libraries, then DIR/run.sh runs in a
# clean environment on lavapipe at the tiny scale: once with a 30 s budget (every section written,
# the carried Vulkan loader used, renders measured, later steps cut or skipped with a note) and
# once with 2 s (steps c-g skipped with a note). Skipped without lavapipe's ICD.
set -u
amrvk="$1"; src="$2"; dir="$3"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
icd=/usr/share/vulkan/icd.d/lvp_icd.json
[ -f "$icd" ] || { echo "skip: no lavapipe ICD at $icd"; exit 77; }
prepare() { AMRVK_PROTOCOL_BIN="$amrvk" AMRVK_PROTOCOL_MAX_MIB=64 "$src/tools/gpu-protocol.sh" prepare "$@"; }
# expectFail FRAGMENT CMD...: exit status 1 and one line on stderr containing FRAGMENT.
expectFail() {
  local frag="$1"; shift
  "$@" >"$dir/fail.out" 2>"$dir/fail.err"; local rc=$?
  if [ "$rc" != 1 ] || [ "$(wc -l <"$dir/fail.err")" != 1 ] || ! grep -qF -- "$frag" "$dir/fail.err"; then
    echo "FAIL: $* -> rc=$rc: $(cat "$dir/fail.err")"; fail=1
  else
    echo "ok: $(cat "$dir/fail.err")"
  fi
}

# prepare refuses what it must not touch, leaving nothing behind.
mkdir "$dir/foreign"; touch "$dir/foreign/keep"
expectFail "not made by gpu-protocol.sh prepare" prepare "$dir/foreign"
ln -s "$dir/foreign" "$dir/link"
expectFail "is a symlink" prepare "$dir/link"
expectFail "is a symlink" prepare "$dir/link//"  # trailing slashes do not hide it (issue 52, point 5)
expectFail "looks like an option" prepare -n
expectFail "the root folder" prepare /
expectFail "no such directory" prepare "$dir/nothere/p"
expectFail "over the 1 MiB limit" env AMRVK_PROTOCOL_BIN="$amrvk" \
  AMRVK_PROTOCOL_MAX_MIB=1 "$src/tools/gpu-protocol.sh" prepare "$dir/p"
check [ ! -e "$dir/p" ]
check [ -z "$(ls -d "$dir"/p.* 2>/dev/null)" ]
check [ "$(ls -A "$dir/foreign")" = keep ]

# prepare writes the folder, and again over its own.
check prepare "$dir/p"
check prepare "$dir/p"
# Results written into the folder since are never deleted by a new prepare (issue 52, point 5).
mkdir "$dir/p/results"; echo mine >"$dir/p/results/results.md"
expectFail "holds results that prepare did not write: refused" prepare "$dir/p/"
check grep -q mine "$dir/p/results/results.md"
rm -r "$dir/p/results"
for f in amrvk run.sh README.md BUILD lib/libvulkan.so.1 lib/libGLdispatch.so.0 lib/compat/NEEDS; do
  check [ -s "$dir/p/$f" ]
done
check [ -z "$(ls -d "$dir"/p.* 2>/dev/null)" ]

# run.sh in a clean environment, lavapipe's ICD, tiny scale, from an empty folder that must stay
# empty: every section, the carried loader, renders with figures, steps cut or skipped for time.
mkdir "$dir/cwd"
run() { (cd "$dir/cwd" && env -i PATH=/usr/bin:/bin HOME="$dir" AMRVK_PROTOCOL_ICD="$icd" AMRVK_PROTOCOL_SCALE=tiny "$@"); }
check run AMRVK_PROTOCOL_BUDGET=30 bash "$dir/p/run.sh" "$dir/out"
r="$dir/out/results.md"
for h in "a. Device and machine" "b. Data" "c. Exactness" "d. Speed" "e. \`--traversal auto\`" \
  "f. First sample" "g. 1e5 cells" "Step log"; do
  check grep -qF "## $h" "$r"
done
check grep -qF "Vulkan loader loaded: $dir/p/lib/libvulkan.so.1 (the carried one)" "$r"
check grep -qE '^- Device: llvmpipe' "$r"
check grep -qE '^- Majorant violations summed over the [1-9][0-9]* renders below: \*\*0\*\*' "$r"
check grep -qF "exit status 0, every traversal's majorants hold" "$r"
check grep -qE '^\| spiky \| grid-dda/grid \| [0-9.]+ \| [0-9.]+ \|' "$r"
check grep -qE '^- State: finished; some steps were stopped or skipped' "$r"
check grep -qE '\| (skipped: |stopped at its limit)' "$r"
check [ -s "$dir/out/raw/devices.json" ]
check [ -s "$dir/out/raw/d-spiky-grid-dda-grid.json" ]
# grid-bvh's K as a constant in exported shaders (step d's grid-bvh/grid~K, made even when skipped).
check grep -qF "culled < 8u)" "$dir/out/shaders-k8/lib/traversal.glsl"
check grep -qF "culled < 128u)" "$dir/out/shaders-k128/lib/traversal.glsl"
check [ ! -e "$dir/out/data" ]
check [ -z "$(ls -A "$dir/cwd")" ]

# A 2 s budget: steps a and b, then c-g skipped with a note in the step log.
check run AMRVK_PROTOCOL_BUDGET=2 bash "$dir/p/run.sh" "$dir/out2"
check grep -qE '^\| a \| `amrvk devices --json` \| ok \|' "$dir/out2/results.md"
for s in c d e f g; do check grep -qE "^\| $s \| .* \| skipped: " "$dir/out2/results.md"; done

# run.sh refuses a folder with something in it, and bad settings, in one line.
expectFail "not empty" run bash "$dir/p/run.sh" "$dir/out"
expectFail "AMRVK_PROTOCOL_SCALE: 'huge'" run AMRVK_PROTOCOL_SCALE=huge bash "$dir/p/run.sh" "$dir/out3"
expectFail "AMRVK_PROTOCOL_STEPS: 'xyz'" run AMRVK_PROTOCOL_STEPS=xyz bash "$dir/p/run.sh" "$dir/out3"
[ "$fail" = 0 ] || { echo "results.md:"; cat "$r"; }
exit $fail
