#!/usr/bin/env bash
# Usage: sample_parallel.sh AMRVK MPIRUN DATA_DIR SOURCE_DIR SCRATCH. Sample-parallel rendering
# (docs/mpi.md): N = 1, 2, 3 ranks give the single-process image of the same seed and spp to float
# rounding (each sample is seeded by its index; the ranks' double sums are added on rank 0), on
# real data (Enzo, ms) and the bundled cloud (ae, and fewer samples than ranks); the comparison
# rejects another seed's image; --json reports every rank and the bytes moved; only rank 0 writes;
# bench on 2 ranks measures the error curves of one process.
set -u
amrvk="$1"; mpirun="$2"; data="${AMRVK_DATA_DIR:-$3}"; src="$4"; dir="$5"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
enzo="$data/enzo_tiny_cosmology/DD0018/DD0018"
cloud="$src/assets/samples/cloud.cells"
[ -f "$enzo" ] || { echo "FAIL: no Enzo sample at $enzo"; exit 1; }

common=(--size 32x24 --spp 12 --tf-range 0 4 --density-scale 2 --seed 7)
other=(--size 32x24 --spp 12 --tf-range 0 4 --density-scale 2 --seed 8)
"$amrvk" render "$enzo" "${common[@]}" -o "$dir/one.pfm" >/dev/null 2>&1 || { echo "FAIL: single-process render"; fail=1; }
for n in 1 2 3; do
  "${mpi[@]}" -n $n "$amrvk" render "$enzo" "${common[@]}" -o "$dir/n$n.pfm" --json "$dir/n$n.json" >"$dir/n$n.out" 2>"$dir/n$n.err" \
    || { echo "FAIL: mpirun -n $n: $(cat "$dir/n$n.err")"; fail=1; continue; }
  pfm_compare "$dir/one.pfm" "$dir/n$n.pfm" 1e-6
  check grep -q "^wrote $dir/n$n.pfm" "$dir/n$n.out"
  check test "$(grep -c '^wrote' "$dir/n$n.out")" = 1   # rank 0 alone speaks
  check /usr/bin/python3 - "$dir/n$n.json" $n <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); n = int(sys.argv[2]); m = j["mpi"]
assert m["ranks"] == n and m["distribute"] == "samples" and len(m["perRank"]) == n, m
ranks = m["perRank"]
assert [r["rank"] for r in ranks] == list(range(n)), ranks
# contiguous, disjoint ranges covering [0, spp)
at = 0
for r in ranks:
    assert r["firstSample"] == at, ranks
    at += r["samples"]
assert at == j["spp"] == 12, (at, j["spp"])
assert sum(r["paths"] for r in ranks) == j["paths"] == 32 * 24 * 12, j["paths"]
assert all(r["device"] and r["gpuSeconds"] > 0 and r["hostPeakBytes"] > 0 for r in ranks), ranks
assert (m["bytesMoved"] > 32 * 24 * 8 * 8 * (n - 1)) if n > 1 else m["bytesMoved"] >= 0, m["bytesMoved"]
assert j["width"] == 32 and j["height"] == 24 and j["majorantViolations"] == 0, j
PY
done
# The comparison has power: the image of another seed (or of samples counted twice) is rejected.
"$amrvk" render "$enzo" "${other[@]}" -o "$dir/seed8.pfm" >/dev/null 2>&1 || fail=1
pfm_differ "$dir/one.pfm" "$dir/seed8.pfm" 1e-3
"${mpi[@]}" -n 2 "$amrvk" render "$enzo" --size 32x24 --spp 6 --seed 7 --tf-range 0 4 --density-scale 2 \
  -o "$dir/half.pfm" >/dev/null 2>&1 || fail=1
pfm_differ "$dir/one.pfm" "$dir/half.pfm" 1e-3

# Another mode and data set, and fewer samples than ranks (rank 2 renders none).
for spp in 2 9; do
  c=(--size 24x24 --spp $spp --mode ae --tf-range 0 1 --seed 3)
  "$amrvk" render "$cloud" "${c[@]}" -o "$dir/cloud$spp.pfm" >/dev/null 2>&1 || fail=1
  "${mpi[@]}" -n 3 "$amrvk" render "$cloud" "${c[@]}" -o "$dir/cloud$spp-3.pfm" >/dev/null 2>"$dir/cloud.err" \
    || { echo "FAIL: cloud spp $spp: $(cat "$dir/cloud.err")"; fail=1; }
  pfm_compare "$dir/cloud$spp.pfm" "$dir/cloud$spp-3.pfm" 1e-6
done
# bench: the same protocol on 2 ranks (each render's samples split, the reference too) measures
# the same error curves as one process, and rank 0 alone writes the reports.
tiny=(--size 16x16 --frames 8 --warmup 1 --reference-spp 32 --tfs foggy --samplers grid --backends sw --modes ms
      --traversals grid-dda --no-dense --dvr-steps none --grid-sweep none)
"$amrvk" bench "$cloud" -o "$dir/bench1" "${tiny[@]}" >/dev/null 2>&1 || { echo "FAIL: bench on one process"; fail=1; }
"${mpi[@]}" -n 2 "$amrvk" bench "$cloud" -o "$dir/bench2" "${tiny[@]}" >"$dir/bench2.out" 2>"$dir/bench2.err" \
  || { echo "FAIL: bench on 2 ranks: $(cat "$dir/bench2.err")"; fail=1; }
check test "$(grep -c '^wrote' "$dir/bench2.out")" = 1
check test "$(cd "$dir/bench1" && find . -type f | sort)" = "$(cd "$dir/bench2" && find . -type f | sort)"
check /usr/bin/python3 - "$dir/bench1/results.json" "$dir/bench2/results.json" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
ra, rb = a["runs"], b["runs"]
assert len(ra) == len(rb) >= 1 and all(isinstance(r["error"], list) for r in ra + rb), (ra, rb)  # a list: no failure
for x, y in zip(ra, rb):
    ca, cb = [e["rmse"] for e in x["error"]], [e["rmse"] for e in y["error"]]
    assert len(ca) == len(cb) >= 3, (ca, cb)
    assert all(abs(p - q) <= 1e-4 * max(p, q) for p, q in zip(ca, cb)), (ca, cb)
print("ok: bench on 2 ranks measures the curves of one process:", [round(e, 6) for e in cb])
PY
expect_line() {  # FRAGMENT -- ARGS: exit 1 with exactly one stderr line containing FRAGMENT
  local frag="$1"; shift 2
  "$@" >/dev/null 2>"$dir/line.err"; local rc=$?
  if [ "$rc" = 1 ] && [ "$(grep -c . "$dir/line.err")" = 1 ] && grep -qF -- "$frag" "$dir/line.err"; then
    echo "ok: $(cat "$dir/line.err")"; else echo "FAIL: rc=$rc: $(cat "$dir/line.err")"; fail=1; fi
}
expect_line "--auto: not under mpirun" -- "${mpi[@]}" -n 2 "$amrvk" bench "$cloud" -o "$dir/bench3" "${tiny[@]}" --auto
expect_line "only 'amrvk render', 'amrvk bench' and 'amrvk view' run on several ranks" -- "${mpi[@]}" -n 2 "$amrvk" info "$cloud"
rm -rf "$dir/bench3"

# Nothing but the named outputs (no temporaries, no per-rank files).
extra=$(ls -A "$dir" | grep -vE '^(one|n[123]|seed8|half|cloud[0-9]+(-3)?)\.(pfm|json|out|err)$|^cloud\.err$|^bench[12](\.out|\.err)?$|^line\.err$')
check test -z "$extra"
exit $fail
