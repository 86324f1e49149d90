#!/usr/bin/env bash
# Usage: bad_input.sh AMRVK SCRATCH. Each case must print exactly one line on stderr that
# contains the expected fragment, and exit with status 1.
set -u
amrvk="$1"; dir="$2"
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cells() { python3 - "$@" <<'PY'
import struct, sys
base, spec = sys.argv[1], sys.argv[2]
cells = [tuple(int(v) for v in c.split(',')) for c in spec.split(';')]
open(base + '.cells', 'wb').write(b''.join(struct.pack('<4i', *c) for c in cells))
vals = [float(v) for v in sys.argv[3].split(',')]
open(base + '.scalars', 'wb').write(struct.pack('<%df' % len(vals), *vals))
PY
}
cells good '0,0,0,1;2,0,0,0;3,0,0,0;2,1,0,0;3,1,0,0' 1,2,3,4,5
cells mismatch '0,0,0,1;2,0,0,0' 1
cells misaligned '1,0,0,1' 1
cells overlap '0,0,0,1;1,1,1,0' 1,2
cells nan '0,0,0,0;1,0,0,0' 1,nan
: > empty.cells; : > empty.scalars
head -c 20 good.cells > trunc.cells; cp good.scalars trunc.scalars

expect "no such file" -- info missing.cells
expect "empty file" -- info empty.cells
expect "not a multiple of the 16-byte" -- info trunc.cells
expect "1 values but" -- info mismatch.cells
expect "not aligned" -- info misaligned.cells
expect "overlapping cells" -- info overlap.cells
expect "non-finite" -- info nan.cells
expect "unknown field 'rho'" -- info good.cells --field rho
expect "unknown option '--bogus'" -- info good.cells --bogus
expect "'x' is not a number" -- info good.cells --grid 4 --threshold x
expect "--grid: expected auto, N or NxMxK (got 'big')" -- info good.cells --grid big
expect "cannot write" -- convert good.cells -o /nonexistent-dir/out
expect "input is required" -- info
expect "unexpected argument 'extra'" -- info good.cells extra
expect "--threshold: expects a value (T)" -- info good.cells --threshold
expect "--dims: 0 is outside [1, 1048576]" -- info good.cells --dims 0 4 4
expect "--field: At Most 1" -- info good.cells --field a --field b
# info builds what each --traversal's plan lists, and refuses what render refuses.
expect "--traversal 'warp': expected grid-dda|grid-bvh" -- info good.cells --traversal grid-dda,warp
expect "dense" -- info good.cells --traversal abr --sampler dense
expect "--traversal does not apply with --check-majorants" -- info good.cells --check-majorants --traversal abr
"$amrvk" info good.cells --traversal brick,kdtree --sampler ext-brick --json >built.json || { echo "FAIL: info --traversal"; fail=1; }
/usr/bin/python3 - built.json <<'PY' || { echo "FAIL: info --traversal structures"; fail=1; }
import json, sys
j = json.load(open(sys.argv[1]))
names = [c["combination"] for c in j["combinations"]]
assert names[0].startswith("brick/ext-brick/sw") and names[1].startswith("kdtree/ext-brick/sw"), names
first, second = (set(c["hostBytes"]) for c in j["combinations"])
assert {"samplerBvh", "traversalBoxes"} <= first and "abrs" not in first and "macrocells" not in first, first
assert "supportRangeQuery" in second and "traversalBoxes" not in second, second
assert "abrs" not in j and "macrocellDims" not in j, "no ABRs or macrocells were built"
PY
expect "--cells: 0 is outside" -- gen cloud --cells 0 -o x
expect "--output is required" -- convert good.cells
"$amrvk" info nan.cells --nan drop >/dev/null 2>&1 || { echo "FAIL: --nan drop"; fail=1; }

# Hostile-input regressions (robustness issue), each named after its defect.
# ControlBytesInAnErrorStayOnOneLine: a field name with a line break, a NUL-free escape and a bell.
expect "unknown field 'a\nb\x1b[2J\x07'" -- info good.cells --field "$(printf 'a\nb\033[2J\a')"
# MisleadingCameraAndLightErrors: NaN in --camera said "eye and target coincide", NaN in
# --light-dir "direction is zero", --fov 0 "up vector is parallel"; each now names the option.
expect "--camera: 'nan' is not a finite number" -- render good.cells --camera nan 0 0 0 0 1 0 1 0 -o x.png
expect "--fov: inf is not a finite number" -- render good.cells --fov inf -o x.png
expect "--light-dir: 'nan' is not a finite number" -- render good.cells --light-dir nan 0 0 1 1 1 -o x.png
expect "--light-point: radiance -1 1 1 must be >= 0" -- render good.cells --light-point 0 0 0 -1 1 1 -o x.png
expect "--background: 'inf' is not a finite number" -- render good.cells --background inf 0 0 -o x.png
expect "--tf-colors: 'gamma' is not one of srgb|linear" -- render good.cells --tf-colors gamma -o x.png
# AnImageTooLargeForMemoryIsRefusedByName (--size 16384x16384 used to start allocating 17 GB).
AMRVK_MEMORY_BUDGET=1000000 expect "--size 512x512: the image: needs 9437184 bytes, more than the memory budget" \
  -- render good.cells --size 512x512 -o x.png
check test ! -e x.png
# ConvertLeavesNoScalarsWhenTheCellsFail: BASE.cells cannot be written (a directory holds its
# name); .scalars used to be committed first and stayed behind. Now refused before any writing.
mkdir -p conv.cells/occupied
expect "conv.cells: is a directory" -- convert good.cells -o conv
check test ! -e conv.scalars
check test -z "$(ls | grep tmp- || true)"
# InterruptedGenLeavesNoTemporaries: SIGINT while gen writes gigabytes used to leave
# *.tmp-PID; temporaries now have random names (*.tmp-XXXXXX), created exclusively.
"$amrvk" gen cloud --cells 100000000 --seed 1 -o big 2>/dev/null & gen=$!
for _ in $(seq 300); do ls big.cells.tmp-* >/dev/null 2>&1 && break; sleep 0.1; done
check ls big.cells.tmp-*
kill -INT "$gen"; wait "$gen"; rc=$?
check test "$rc" = 130
check test -z "$(ls | grep '^big\.' || true)"
# RAMSES (docs/formats.md): a missing domain file, a 1-D output, an info file with no ncpu; no
# image is left behind by a failed render.
mkdir -p ramses/output_00001
info='ncpu = 2\nndim = 3\nlevelmin = 1\nlevelmax = 2\nboxlen = 1.0\ntime = 0.0\n'
printf "$info" > ramses/output_00001/info_00001.txt
expect "amr_00001.out00001: no such file (info_00001.txt lists 2 domains)" -- info ramses/output_00001
expect "amr_00001.out00001: no such file" -- render ramses/output_00001/info_00001.txt -o ramses.png
check test ! -e ramses.png
printf "${info/ndim = 3/ndim = 1}" > ramses/output_00001/info_00001.txt
expect "ndim 1 (only 2-D and 3-D RAMSES outputs" -- info ramses/output_00001 --format ramses
printf "${info/ncpu = 2/}" > ramses/output_00001/info_00001.txt
expect "info_00001.txt: no 'ncpu =' line" -- info ramses/output_00001
ls /nonexistent-dir 2>/dev/null && fail=1
exit $fail
