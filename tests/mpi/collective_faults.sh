#!/usr/bin/env bash
# Usage: collective_faults.sh AMRVK MPIRUN SOURCE_DIR SCRATCH. Hostile input, round 3 (issue 34,
# docs/fuzzing.md): a rank that fails at each of World's collectives (the test hook
# AMRVK_TEST_MPI_FAIL=CALL:RANK[:NTH] makes that rank throw instead of joining it, as if MPI had
# returned an error there), sample- and data-parallel. Every run must end within 60 s, exit
# non-zero, print exactly one line naming the rank (or every rank) and the injected fault, and
# write no image.
set -u
amrvk="$1"; mpirun="$2"; src="$3"; dir="$4"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
cases=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
python3 - "$dir" <<'PY2'
import struct, sys
cells = [(0,0,0,1),(2,0,0,0),(3,0,0,0),(2,1,0,0),(3,1,0,0)]
open(sys.argv[1] + '/five.cells','wb').write(b''.join(struct.pack('<4i', *c) for c in cells))
open(sys.argv[1] + '/five.scalars','wb').write(struct.pack('<5f', 1, 2, 3, 4, 5))
PY2
data="$dir/five.cells"
small=(--size 8x8 --spp 2 --grid 4)

# fault NAME SPEC FRAGMENT -- AMRVK-ARGS...: two ranks, the fault SPEC on one of them.
# (written=1: the image may have been written: the fault comes after it.)
fault() {
  local name="$1" spec="$2" frag="$3"; shift 4
  cases=$((cases + 1))
  rm -f "$dir/out.png"
  local start; start=$(date +%s%N)
  timeout 90 "${mpi[@]}" -x AMRVK_TEST_MPI_FAIL="$spec" -x AMRVK_TEST_MPI_FAILED_WAIT_S=3 -n 2 "$amrvk" render "$data" "${small[@]}" "$@" \
    -o "$dir/out.png" >"$dir/$name.out" 2>"$dir/$name.err"; local rc=$?
  local took=$(( ($(date +%s%N) - start) / 1000000 ))
  local lines; lines=$(grep -c . "$dir/$name.err")
  if [ "$rc" != 0 ] && [ "$rc" != 124 ] && [ "$lines" = 1 ] && grep -qF -- "$frag" "$dir/$name.err" &&
     grep -qF "injected fault" "$dir/$name.err" && { [ "${written:-0}" = 1 ] || [ ! -e "$dir/out.png" ]; } &&
     [ "$took" -lt 60000 ]; then
    echo "ok: $name (rc $rc, ${took} ms): $(cat "$dir/$name.err")"
  else
    echo "FAIL: $name: rc=$rc, ${took} ms, out.png $( [ -e "$dir/out.png" ] && echo written || echo absent )," \
         "stderr($lines lines): $(head -c 2000 "$dir/$name.err")"; fail=1
  fi
}

# Sample-parallel (docs/mpi.md): checkpoint (agree 1), fingerprints (requireSame 1, 2), the
# render's agreement (agree 2), the image sums (sumEverywhere 1, 2), the statistics
# (maxOverRanks), the per-rank reports (gatherToRoot) and the final agreement (agree 3).
# Data-parallel: the checkpoint, the per-step reductions (nearest collision with its rank, shadow
# products, sums) and the paths-alive fingerprints. Rank 1 fails at each; rank 0 (the root, the
# one that prints and writes) at those where it differs. AMRVK_MPI_ALL_CASES=1: both ranks at
# every one (28 cases, about 2.5 minutes on the 2-core machine; the default 16 take 80 s).
all=${AMRVK_MPI_ALL_CASES:-0}
for r in 1 0; do
  first=$([ "$r" = 1 ] || [ "$all" = 1 ] && echo 1 || echo 0)
  [ "$first" = 1 ] && fault "samples-checkpoint-r$r" "agree:$r:1" "rank $r of 2" --
  [ "$first" = 1 ] && fault "samples-fingerprint-r$r" "requireSame:$r:1" "rank $r of 2" --
  [ "$all" = 1 ] && fault "samples-cellcount-r$r" "requireSame:$r:2" "rank $r of 2" --
  [ "$first" = 1 ] && fault "samples-render-agreement-r$r" "agree:$r:2" "rank $r of 2" --
  fault "samples-image-sum-r$r" "sumEverywhere:$r:1" "rank $r of 2" --
  [ "$all" = 1 ] && fault "samples-counter-sum-r$r" "sumEverywhere:$r:2" "rank $r of 2" --
  [ "$first" = 1 ] && fault "samples-gpu-seconds-r$r" "maxOverRanks:$r:1" "rank $r of 2" --
  fault "samples-reports-r$r" "gatherToRoot:$r:1" "rank $r of 2" --
  # The final agreement comes after rank 0 wrote the image (every rank had rendered its share).
  written=1 fault "samples-final-agreement-r$r" "agree:$r:3" "rank $r of 2" --
  [ "$first" = 1 ] && fault "data-checkpoint-r$r" "agree:$r:1" "rank $r of 2" -- --distribute data --mode ms
  fault "data-minloc-r$r" "minLocEverywhere:$r:1" "rank $r of 2" -- --distribute data --mode ms
  [ "$first" = 1 ] && fault "data-product-r$r" "productEverywhere:$r:1" "rank $r of 2" -- --distribute data --mode ms --light-dir 1 -1 2 1 1 1
  [ "$first" = 1 ] && fault "data-sum-r$r" "sumEverywhere:$r:1" "rank $r of 2" -- --distribute data --mode ms
  [ "$first" = 1 ] && fault "data-alive-r$r" "requireSame:$r:3" "rank $r of 2" -- --distribute data --mode ms
done
echo "collective_faults.sh: $cases cases"
exit $fail
