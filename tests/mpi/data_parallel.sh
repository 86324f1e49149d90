#!/usr/bin/env bash
# Usage: data_parallel.sh AMRVK MPIRUN DATA_DIR SOURCE_DIR SCRATCH. Data-parallel rendering
# (--distribute data, docs/mpi.md): each rank reads and tracks only its box of space, and the
# image equals the single-process one statistically (tests/mpi/zcompare.py: per-pixel and pooled
# z of the means against both variances) with 2 and 3 ranks, in ae, ss and ms, on the bundled
# cloud (ExaBrick, streamed) and real Enzo data, with partition faces through the finest level,
# with a cut-away, and with spiky and foggy fitted to the whole field's percentiles.
# Power: the same test rejects the data-parallel image when the single-process reference is made
# from data with rank 1's part 5% denser, in ae and ss with 2 ranks and in ms with 3 (pooled |z|
# above 4), and when the pixels of variance 0 (the background past the cloud) are 0.1% off. ss
# with 3 ranks and ms with 2 are not rendered: ms casts ss's shadow rays too, and each mode and
# rank count is covered once (they took 39 of this test's 136 s). --json: boxes that tile the data, every cell owned by one rank, halos, bytes moved.
set -u
amrvk="$1"; mpirun="$2"; data="${AMRVK_DATA_DIR:-$3}"; src="$4"; dir="$5"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
zcompare() { /usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/zcompare.py" "$@"; }
cloud="$src/assets/samples/cloud.cells"
enzo="$data/enzo_tiny_cosmology/DD0018/DD0018"
[ -f "$enzo" ] || { echo "FAIL: no Enzo sample at $enzo"; exit 1; }
# An absorber (black, alpha rising with the value) in front of a white background: the image is
# the transmittance, which a density error changes.
cat >"$dir/absorber.json" <<'JSON'
[{"Name": "absorber", "ColorSpace": "RGB", "RGBPoints": [0, 0, 0, 0, 3, 0, 0, 0], "Points": [0, 0, 0.5, 0, 3, 1, 0.5, 0]}]
JSON

# same NAME N INPUT ARGS...: single process (seed 5) and N ranks (seed 7) must agree. The
# single-process render of the same input and arguments is made once (ss and ms with 2 and 3 ranks).
declare -A single
same() {
  local name="$1" n="$2" input="$3"; shift 3
  local key="$input $*"
  if [ -n "${single[$key]:-}" ]; then
    cp "$dir/${single[$key]}.one.pfm" "$dir/$name.one.pfm" && cp "$dir/${single[$key]}.one.var.pfm" "$dir/$name.one.var.pfm"
  else
    "$amrvk" render "$input" "$@" --seed 5 -o "$dir/$name.one.pfm" --variance "$dir/$name.one.var.pfm" >/dev/null 2>&1 \
      || { echo "FAIL: $name: single-process render"; fail=1; return; }
    single[$key]=$name
  fi
  "${mpi[@]}" -n "$n" "$amrvk" render "$input" "$@" --distribute data -o "$dir/$name.pfm" --variance "$dir/$name.var.pfm" \
    --json "$dir/$name.json" >/dev/null 2>"$dir/$name.err" || { echo "FAIL: $name: $(cat "$dir/$name.err")"; fail=1; return; }
  local r; r=$(zcompare "$dir/$name.one.pfm" "$dir/$name.one.var.pfm" "$dir/$name.pfm" "$dir/$name.var.pfm")
  if [ $? = 0 ]; then echo "ok: $name agrees with one process: $r"; else echo "FAIL: $name differs: $r"; fail=1; fi
}
absorb=(--size 40x40 --spp 1024 --tf "$dir/absorber.json" --mode ae --background 1 1 1 --density-scale 0.5)
same cloud-ae-2 2 "$cloud" "${absorb[@]}"
same cloud-ae-3 3 "$cloud" "${absorb[@]}"
# ss and ms (shadow rays through other ranks' parts, roulette) at 2048 spp: enough for the power
# check below to reject a 5% denser part (pooled |z| 7.4 with 2 ranks, 4.4 with 3: fixed seeds).
# As written before the first picture's defaults: linear values, the ramp, the ambient behind.
old=(--scale linear --tf ramp --background 1 1 1)
ss=(--size 32x32 --spp 2048 --mode ss --scale linear --tf ramp --tf-range 0 1 --light-dir 1 1 0 2 2 2 --ambient 0.3 0.3 0.3 --background 0.3 0.3 0.3)
ms=(--size 32x32 --spp 2048 --mode ms "${old[@]}" --tf-range 0 1 --light-dir 1 1 0 2 2 2)
same cloud-ss-2 2 "$cloud" "${ss[@]}"
same cloud-ms-3 3 "$cloud" "${ms[@]}"
same enzo-ms-2 2 "$enzo" --size 32x32 --spp 128 --mode ms "${old[@]}" --tf-range 0 4 --density-scale 2
# Presets fitted to the data (no --tf-range): every rank fits spiky and foggy to the whole field's
# percentiles (the summed counts of the cells each owns), the TF one process fits; the note each
# prints names the percentiles it used.
same enzo-spiky-2 2 "$enzo" --size 32x32 --spp 128 --mode ms --tf spiky --density-scale 2
same cloud-foggy-3 3 "$cloud" --size 32x32 --spp 128 --mode ms --tf foggy --density-scale 4
for fit in "enzo-spiky-2 2 $enzo spiky" "cloud-foggy-3 3 $cloud foggy"; do
  set -- $fit
  "$amrvk" render "$3" --size 8x8 --spp 1 --tf "$4" -o "$dir/$1.fit.pfm" >/dev/null 2>"$dir/$1.fit.err" || fail=1
  one=$(grep "tf $4:" "$dir/$1.fit.err"); many=$(grep "tf $4:" "$dir/$1.err")
  if [ -n "$one" ] && [ "$one" = "$many" ]; then echo "ok: $1 fits $4 as one process does: ${one#amrvk: }"
  else echo "FAIL: $1: one process fits '$one', $2 ranks '$many'"; fail=1; fi
done
# A cut-away (docs/cut-aways.md): a crop box across the partition faces and an oblique clip plane.
same cloud-ms-cut-2 2 "$cloud" --size 32x32 --spp 128 --mode ms "${old[@]}" --tf-range 0 1 --light-dir 1 1 0 2 2 2 \
  --crop 0 0 0 512 512 300 --clip 256 256 256 1 1 0

# The report: boxes that tile the bounds without overlap, each cell owned once, halos held.
for name in cloud-ae-2 cloud-ae-3 enzo-ms-2; do
  check /usr/bin/python3 - "$dir/$name.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); m = j["mpi"]; ranks = m["perRank"]
assert m["distribute"] == "data" and m["ranks"] == len(ranks) >= 2, m
volume = lambda b: (b[1][0] - b[0][0]) * (b[1][1] - b[0][1]) * (b[1][2] - b[0][2])
boxes = [r["ownedBox"] for r in ranks]
for i, a in enumerate(boxes):
    for b in boxes[i + 1:]:
        overlap = [min(a[1][k], b[1][k]) - max(a[0][k], b[0][k]) for k in range(3)]
        assert min(overlap) <= 0, (a, b)
lo = [min(b[0][k] for b in boxes) for k in range(3)]; hi = [max(b[1][k] for b in boxes) for k in range(3)]
assert sum(volume(b) for b in boxes) == volume([lo, hi]), boxes
assert sum(r["ownedCells"] for r in ranks) == m["cells"], (m["cells"], [r["ownedCells"] for r in ranks])
assert all(r["heldCells"] >= r["ownedCells"] > 0 for r in ranks), ranks
assert all(r["heldCells"] < m["cells"] for r in ranks), "a rank holds every cell"
assert m["bytesMoved"] > 0 and m["bytesMovedPerPath"] > 0 and j["majorantViolations"] == 0, m
print("ok: %s: owned %s, held %s, %.1f bytes per path" % (sys.argv[1].split("/")[-1], [r["ownedCells"] for r in ranks],
      [r["heldCells"] for r in ranks], m["bytesMovedPerPath"]))
PY
done

# Power of the exact comparison of constant pixels: the data-parallel image with its pixels of
# variance 0 in both images (the background seen past the cloud) 0.1% brighter, a wrong constant
# background that the z-test alone passes (those pixels have no z), must fail on them alone.
wrong=$(/usr/bin/python3 - "$dir" cloud-ae-2 "$(dirname "${BASH_SOURCE[0]}")" <<'PY'
import sys
import numpy as np
sys.path.insert(0, sys.argv[3])
from zcompare import pfm
d, name = sys.argv[1], sys.argv[2]
image = pfm(f"{d}/{name}.pfm")
constant = (pfm(f"{d}/{name}.var.pfm")[..., 1] == 0) & (pfm(f"{d}/{name}.one.var.pfm")[..., 1] == 0)
image[constant] *= 1.001
h, w, _ = image.shape
with open(f"{d}/{name}.wrong-background.pfm", "wb") as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (w, h) + image.astype("<f4").tobytes())
print(int(np.sum(constant & (image[..., 1] != 0))))  # 0 stays 0
PY
) || { echo "FAIL: wrong background"; fail=1; }
r=$(zcompare "$dir/cloud-ae-2.one.pfm" "$dir/cloud-ae-2.one.var.pfm" "$dir/cloud-ae-2.wrong-background.pfm" "$dir/cloud-ae-2.var.pfm")
if [ $? = 1 ] && /usr/bin/python3 -c 'import json,sys; j = json.loads(sys.argv[1]); sys.exit(not (j["zeroVarianceDiffer"] == int(sys.argv[2]) > 0 and j["maxAbsZ"] < 6 and abs(j["pooledZ"]) < 4 and j["chi2Excess"] < 4))' "$r" "$wrong"
then echo "ok: a background 0.1% too bright on $wrong constant pixels fails (the z-test alone passes it): $r"
else echo "FAIL: a background 0.1% too bright on $wrong constant pixels: $r"; fail=1; fi

# Power: reference data with rank 1's part 5% denser (values x 1.05; under the absorber's linear
# alpha ramp in ae, under the default TF's colour and opacity with a light in ss and ms) must be
# rejected by the comparison that accepts the unperturbed one, for each mode and 2 and 3 ranks.
denser() {
  local name="$1"; shift
  local fine
  fine=$(/usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/perturb_part.py" "$cloud" "$dir/$name.json" 1 1.05 "$dir/$name.denser") \
    || { echo "FAIL: $name: perturb"; fail=1; return; }
  echo "$name: perturbed rank 1's part: $fine"
  check /usr/bin/python3 -c 'import json,sys; assert json.loads(sys.argv[1])["fineCellsAtInteriorFaces"] > 0' "$fine"
  "$amrvk" render "$dir/$name.denser.cells" "$@" --seed 5 -o "$dir/$name.denser.pfm" --variance "$dir/$name.denser.var.pfm" \
    >/dev/null 2>&1 || { echo "FAIL: $name: denser render"; fail=1; return; }
  local r; r=$(zcompare "$dir/$name.denser.pfm" "$dir/$name.denser.var.pfm" "$dir/$name.pfm" "$dir/$name.var.pfm")
  if [ $? = 1 ]; then echo "ok: $name: the test rejects a 5% denser part: $r"; else echo "FAIL: $name: a 5% denser part passed: $r"; fail=1; fi
}
denser cloud-ae-2 "${absorb[@]}"
denser cloud-ss-2 "${ss[@]}"
denser cloud-ms-3 "${ms[@]}"

# Modes it does not do, and --distribute outside mpirun: one line each.
"${mpi[@]}" -n 2 "$amrvk" render "$cloud" --size 8x8 --spp 2 --mode dvr --distribute data -o "$dir/x.png" 2>"$dir/dvr.err"
check grep -q "mode dvr is not supported" "$dir/dvr.err"
check test "$(grep -c . "$dir/dvr.err")" = 1
"$amrvk" render "$cloud" --size 8x8 --spp 2 --distribute data -o "$dir/x.png" 2>"$dir/nompi.err"
check grep -q "only under an MPI launcher" "$dir/nompi.err"
check test ! -e "$dir/x.png"
exit $fail
