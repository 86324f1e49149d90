#!/usr/bin/env bash
# Usage: faults.sh AMRVK MPIRUN SOURCE_DIR SCRATCH. A rank that fails makes every rank exit within
# 30 s with one line naming the rank and the cause, and no output is written (docs/mpi.md):
# an error on every rank, a rank that cannot read its data (both modes), ranks started with
# different options, ranks whose replicated paths diverge (data-parallel), a rank out of memory,
# a rank that fails while the others still render (it ends the job itself after 20 s), and a
# killed rank (reported by mpirun, which saw it die).
set -u
amrvk="$1"; mpirun="$2"; src="$3"; dir="$4"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cloud="$src/assets/samples/cloud.cells"
head -c 100 "$cloud" >"$dir/truncated.cells"
small=(--size 16x16 --spp 4)

# expect_fault NAME FRAGMENT... -- MPIRUN-ARGS...: the job fails within 30 s (limitMs), stderr holds
# exactly one line, containing every FRAGMENT, and $dir/out.png was not written.
expect_fault() {
  local name="$1"; shift
  local frags=()
  while [ "$1" != "--" ]; do frags+=("$1"); shift; done
  shift
  rm -f "$dir/out.png"
  local start; start=$(date +%s%N)
  local limit=${limitMs:-30000}
  timeout $((limit / 1000 + 30)) "$@" >"$dir/$name.out" 2>"$dir/$name.err"; local rc=$?
  local took=$(( ($(date +%s%N) - start) / 1000000 ))  # ms
  local lines; lines=$(grep -c . "$dir/$name.err")
  local ok=1
  [ "$rc" != 0 ] && [ "$rc" != 124 ] || ok=0
  [ "$lines" = 1 ] || ok=0
  for f in "${frags[@]}"; do grep -qF -- "$f" "$dir/$name.err" || ok=0; done
  [ "$took" -lt "$limit" ] || ok=0
  [ ! -e "$dir/out.png" ] || ok=0
  if [ $ok = 1 ]; then echo "ok: $name (rc $rc, ${took} ms): $(cat "$dir/$name.err")"
  else echo "FAIL: $name: rc=$rc, ${took} ms, out.png $( [ -e "$dir/out.png" ] && echo written || echo absent ), stderr($lines lines): $(cat "$dir/$name.err")"; fail=1; fi
}

expect_fault every-rank "--spp: 0 is outside" "(every rank of 3)" -- \
  "${mpi[@]}" -n 3 "$amrvk" render "$cloud" --spp 0 -o "$dir/out.png"
expect_fault cannot-read "rank 1 of 3" "truncated.cells" "not a multiple of the 16-byte cell record" -- \
  "${mpi[@]}" -n 1 "$amrvk" render "$cloud" "${small[@]}" -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$dir/truncated.cells" "${small[@]}" -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$cloud" "${small[@]}" -o "$dir/out.png"
expect_fault cannot-read-data "rank 1 of 2" "truncated.cells" -- \
  "${mpi[@]}" -n 1 "$amrvk" render "$cloud" "${small[@]}" --distribute data -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$dir/truncated.cells" "${small[@]}" --distribute data -o "$dir/out.png"
# Ranks started with different options would combine unrelated pictures.
expect_fault disagree "ranks disagree on the picture" "(every rank of 2)" -- \
  "${mpi[@]}" -n 1 "$amrvk" render "$cloud" "${small[@]}" -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$cloud" "${small[@]}" --seed 9 -o "$dir/out.png"
expect_fault disagree-data "ranks disagree on the picture" "(every rank of 2)" -- \
  "${mpi[@]}" -n 1 "$amrvk" render "$cloud" "${small[@]}" --distribute data -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$cloud" "${small[@]}" --distribute data --density-scale 2 -o "$dir/out.png"
# A series or turntable (docs/movies.md) is one process's work: refused on every rank, no frame written.
# Ranks whose replicated paths diverge (here rank 1's shaders drop every odd path at birth, as a
# different driver could by rounding) stop before the first reduction combines other paths: on the
# landed code this was MPI_ERR_TRUNCATE in MPI_Allreduce (or, with equal counts, a silent mix-up).
# Rank 1 compiles the edited data-parallel shader first (tens of seconds on a busy lavapipe).
"$amrvk" shaders --export "$dir/diverged" >/dev/null || fail=1
sed -i 's/i, pc.sampleIndex);$/i, pc.sampleIndex); if (i % 2u == 1u) paths.v[i].flags = 0u;/' "$dir/diverged/passes/path_trace_dp.comp"
check grep -q "if (i % 2u == 1u) paths.v\[i\].flags = 0u;" "$dir/diverged/passes/path_trace_dp.comp"
limitMs=150000 expect_fault diverged "ranks disagree on the paths alive before the collision reduction of sample 0, bounce 0" \
  "same driver, device kind and shaders" "(every rank of 2)" -- \
  "${mpi[@]}" -n 1 "$amrvk" render "$cloud" "${small[@]}" --mode ms --distribute data -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$cloud" "${small[@]}" --mode ms --distribute data --shader-dir "$dir/diverged" -o "$dir/out.png"
# A runaway in the staged data-parallel pass (rank 1's path_trace_dp loops forever) is held to the
# adaptive --gpu-timeout as path_trace is (it waited 600 s): rank 1 ends after the floor (2 s here)
# with one line, and mpirun ends rank 0, which waits for it at the first reduction.
"$amrvk" shaders --export "$dir/dp_forever" >/dev/null || fail=1
sed -i 's|void main() {|void main() { float spin = 0.0; for (uint k = 0u; ; ++k) { spin += sin(float(k)); if (spin < -1e30) break; } if (spin == 1.0) return;|' \
  "$dir/dp_forever/passes/path_trace_dp.comp"
AMRVK_TEST_GPU_TIMEOUT_FLOOR=2 limitMs=60000 expect_fault dp-runaway "rank 1 of 2" \
  "GPU work 'path_trace_dp.ae." "from --shader-dir $dir/dp_forever' ran longer than 2 s" "(the adaptive --gpu-timeout" -- \
  "${mpi[@]}" -n 1 "$amrvk" render "$cloud" "${small[@]}" --mode ae --distribute data -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$cloud" "${small[@]}" --mode ae --distribute data --shader-dir "$dir/dp_forever" -o "$dir/out.png"
expect_fault series "is rendered by one process, not under an MPI launcher" "(every rank of 2)" -- \
  "${mpi[@]}" -n 2 "$amrvk" render "$cloud" "${small[@]}" --frames 2 --orbit 90 -o "$dir/f_%d.png"
check test -z "$(ls "$dir" | grep '^f_' || true)"
# Rank 1 under a 600 MB address-space limit runs out while reading, building, mapping buffers or
# compiling (where depends on the driver); each way ends in one line that says so.
expect_fault out-of-memory "rank 1 of 2" "memory" -- \
  "${mpi[@]}" -n 1 "$amrvk" render "$cloud" "${small[@]}" -o "$dir/out.png" \
  : -n 1 sh -c "ulimit -v 600000; exec \"$amrvk\" render \"$cloud\" --size 16x16 --spp 4 -o \"$dir/out.png\""
# Rank 1 fails at once while ranks 0 and 2 render for minutes: it waits 20 s for them at the
# agreement, then ends the job itself.
long=(--size 96x96 --spp 100000)
expect_fault failed-while-others-render "rank 1 of 3" "truncated.cells" -- \
  "${mpi[@]}" -n 1 "$amrvk" render "$cloud" "${long[@]}" -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$dir/truncated.cells" "${long[@]}" -o "$dir/out.png" \
  : -n 1 "$amrvk" render "$cloud" "${long[@]}" -o "$dir/out.png"

# A killed rank cannot speak: mpirun (without -q) names it and the signal, and ends the others.
rm -f "$dir/out.png"
timeout 120 "$mpirun" --oversubscribe -n 3 "$amrvk" render "$cloud" "${long[@]}" -o "$dir/out.png" \
  >"$dir/killed.out" 2>"$dir/killed.err" &
job=$!
# The processes rendering into $dir/out.png (no procps needed): "PID RANK" per line.
renderers() {
  local p
  for p in /proc/[0-9]*; do
    { tr '\0' ' ' <"$p/cmdline"; } 2>/dev/null | grep -qF "render $cloud ${long[*]} -o $dir/out.png" || continue
    echo "${p#/proc/} $({ tr '\0' '\n' <"$p/environ"; } 2>/dev/null | sed -n 's/^OMPI_COMM_WORLD_RANK=//p')"
  done
}
victim=""
for _ in $(seq 1 300); do  # the rank-1 process, once it runs
  victim=$(renderers | awk '$2 == 1 {print $1}')
  [ -n "$victim" ] && break
  sleep 0.1
done
sleep 3  # into its render
killed_at=$(date +%s%N)
[ -n "$victim" ] && kill -9 "$victim"
wait $job; rc=$?
took=$(( ($(date +%s%N) - killed_at) / 1000000 ))
if [ -n "$victim" ] && [ "$rc" != 0 ] && [ "$rc" != 124 ] && [ ! -e "$dir/out.png" ] &&
   grep -q "process rank 1 .*signal 9" "$dir/killed.err" && [ -z "$(renderers)" ] &&
   [ "$took" -lt 30000 ]; then
  echo "ok: killed rank 1: job ended ${took} ms after the kill (rc $rc): $(grep 'process rank 1' "$dir/killed.err")"
else
  echo "FAIL: killed rank (victim '$victim'): rc=$rc, ${took} ms, out.png $( [ -e "$dir/out.png" ] && echo written || echo absent ): $(cat "$dir/killed.err")"; fail=1
fi
exit $fail
