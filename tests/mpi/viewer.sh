#!/usr/bin/env bash
# Usage: viewer.sh AMRVK MPIRUN SOURCE_DIR SCRATCH. The MPI viewer (mpirun -n N amrvk view,
# sample-parallel; docs/mpi.md): with 2 and 3 ranks a scripted run that edits the TF, steps a
# series and switches the sampler ends at the picture of `render --session` of the session it
# saved (the same samples: equal to float rounding; the comparison rejects the picture before the
# edit), and agrees by a z-test with an independent single-process render (rejecting a 10% denser
# medium); ranks started on different data are refused at start with one line; a hung rank ends
# the job within 30 s with its first line naming it, a killed one is named by mpirun; in a window under
# Xvfb the q key ends every rank, and the state file says how many ranks traced and when the first
# picture came. Every wait is on the viewer's state or the processes, never a fixed pause.
set -u
amrvk="$1"; mpirun="$2"; src="$3"; dir="$4"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail=0
source "$here/lib.sh"
export AMRVK_PROGRESS=0
zcompare() { /usr/bin/python3 "$src/tests/mpi/zcompare.py" "$@"; }
cloud="$src/assets/samples/cloud.cells"
pic=(--size 48x32 --scale linear --tf ramp --tf-range 0 1.2 --density-scale 1 --grid 16 --mode ae --background 0 0 0 --backend sw)

# ---- 2 ranks: a TF edit reaches every rank; the picture is render --session's ----
printf '3 tf-range 0 0.8\n' >edit.txt
timeout 300 "${mpi[@]}" -n 2 "$amrvk" view "$cloud" "${pic[@]}" --spp 64 --headless --frames 60 --script edit.txt \
  --screenshot two.pfm --save-session two.json --stats two-stats.json >two.out 2>two.err || { echo "FAIL: 2 ranks: $(cat two.err)"; fail=1; }
"$amrvk" render --session two.json -o one.pfm --variance one-var.pfm >/dev/null 2>&1 || { echo "FAIL: render --session"; fail=1; }
pfm_compare one.pfm two.pfm 1e-4                      # the same sample indices, split over the ranks
"$amrvk" render --session two.json --tf-range 0 1.2 -o before-edit.pfm >/dev/null 2>&1 || fail=1
pfm_differ before-edit.pfm two.pfm 0.05               # power: the picture before the edit is another
check /usr/bin/python3 - two-stats.json <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert j["ranks"] == 2 and j["spp"] == 64 and j["shown"] == "estimate", j
assert 0 < j["timeToFirstPicture"] < 300, j["timeToFirstPicture"]
PY
# Independent samples of one process (another seed): a z-test that agrees, and rejects 10% more density.
"$amrvk" render --session two.json --seed 99 -o seed99.pfm --variance seed99-var.pfm >/dev/null 2>&1 || fail=1
"$amrvk" render --session two.json --seed 99 --density-scale 1.1 -o denser.pfm --variance denser-var.pfm >/dev/null 2>&1 || fail=1
check zcompare two.pfm one-var.pfm seed99.pfm seed99-var.pfm 2
if zcompare two.pfm one-var.pfm denser.pfm denser-var.pfm 2 >/dev/null; then echo "FAIL: the z-test accepts a 10% denser medium"; fail=1; fi

# ---- 3 ranks: a series step and a structure switch reach every rank ----
for pair in "1 0" "2 0.4"; do
  set -- $pair
  "$amrvk" gen cloud --cells 3000 --seed 3 --time "$2" -o "out_$1" >/dev/null || fail=1
done
printf '2 step 1\n4 sampler abr\n' >series.txt
timeout 300 "${mpi[@]}" -n 3 "$amrvk" view 'out_*.cells' "${pic[@]}" --spp 30 --headless --frames 60 --script series.txt \
  --screenshot three.pfm --save-session three.json >three.out 2>three.err || { echo "FAIL: 3 ranks: $(cat three.err)"; fail=1; }
check grep -q '"input": ".*out_2.cells"' three.json
check grep -q '"sampler": "abr"' three.json
"$amrvk" render --session three.json -o three-one.pfm >/dev/null 2>&1 || fail=1
pfm_compare three-one.pfm three.pfm 1e-4
"$amrvk" render --session three.json "$PWD/out_1.cells" -o step0.pfm >/dev/null 2>&1 || fail=1
pfm_differ step0.pfm three.pfm 0.05                  # power: step 0's picture is another

# ---- ranks on different data: refused at start, one line ----
start=$SECONDS
timeout 120 "${mpi[@]}" -n 1 "$amrvk" view "$cloud" "${pic[@]}" --headless --frames 5 \
  : -n 1 "$amrvk" view "$PWD/out_1.cells" "${pic[@]}" --headless --frames 5 >disagree.out 2>disagree.err
rc=$?
if [ $rc != 0 ] && [ $rc != 124 ] && [ "$(grep -c . disagree.err)" = 1 ] && grep -q "ranks disagree on the picture" disagree.err; then
  echo "ok: different data refused in $((SECONDS - start)) s: $(cat disagree.err)"
else echo "FAIL: different data: rc $rc: $(cat disagree.err)"; fail=1; fi

# The processes of this script's long viewer: "PID RANK" per line (no procps needed).
viewers() {
  local p
  for p in /proc/[0-9]*; do
    { tr '\0' ' ' <"$p/cmdline"; } 2>/dev/null | grep -qF "view $cloud --size 40x40 --frames 1000000" || continue
    echo "${p#/proc/} $({ tr '\0' '\n' <"$p/environ"; } 2>/dev/null | sed -n 's/^OMPI_COMM_WORLD_RANK=//p')"
  done
}
rank_pid() {  # rank_pid R: waits (up to 60 s) for rank R's process and prints its pid
  local pid=""
  for _ in $(seq 600); do
    pid=$(viewers | awk -v r="$1" '$2 == r {print $1}')
    [ -n "$pid" ] && break
    sleep 0.1
  done
  echo "$pid"
}
long=(view "$cloud" --size 40x40 --frames 1000000 --headless --state-file state.json)
state_frames() { sed -n 's/^  "frame": \([0-9]*\),$/\1/p' state.json 2>/dev/null; }
wait_frames() {  # wait_frames N: rank 0 has drawn N frames (its state file), up to 120 s
  for _ in $(seq 1200); do [ "$(state_frames)" -ge "$1" ] 2>/dev/null && return 0; sleep 0.1; done
  return 1
}

# ---- a hung rank: the job ends within 30 s with one line naming it ----
rm -f state.json
timeout 180 "${mpi[@]}" -n 3 "$amrvk" "${long[@]}" >hung.out 2>hung.err &
job=$!
victim=$(rank_pid 2)
wait_frames 5 || echo "FAIL: no frames before the hang"
stopped_at=$SECONDS
[ -n "$victim" ] && kill -STOP "$victim"
wait $job; rc=$?
took=$((SECONDS - stopped_at))
[ -n "$victim" ] && kill -9 "$victim" 2>/dev/null
# The first line is rank 0's; the stopped rank, continued by the job's end, may add its own note that
# its GPU work stalled (its adaptive deadline saw the 20 s stop) before it is ended.
if [ -n "$victim" ] && [ $rc != 0 ] && [ $rc != 124 ] && [ $took -lt 30 ] && [ "$(grep -c . hung.err)" -le 2 ] &&
   head -1 hung.err | grep -q "amrvk view: error: rank 2 of 3 did not answer" && [ -z "$(viewers)" ]; then
  echo "ok: hung rank 2: ended ${took} s after the stop: $(head -1 hung.err)"
else echo "FAIL: hung rank (victim '$victim'): rc $rc, ${took} s, left: '$(viewers)': $(cat hung.err)"; fail=1; fi

# ---- a killed rank: mpirun (without -q) names it and ends the others ----
rm -f state.json
timeout 180 "$mpirun" --oversubscribe -n 2 "$amrvk" "${long[@]}" >killed.out 2>killed.err &
job=$!
victim=$(rank_pid 1)
wait_frames 5 || echo "FAIL: no frames before the kill"
killed_at=$SECONDS
[ -n "$victim" ] && kill -9 "$victim"
wait $job; rc=$?
took=$((SECONDS - killed_at))
if [ -n "$victim" ] && [ $rc != 0 ] && [ $rc != 124 ] && [ $took -lt 30 ] && grep -q "process rank 1 .*signal 9" killed.err &&
   [ -z "$(viewers)" ]; then
  echo "ok: killed rank 1: ended ${took} s after the kill: $(grep 'process rank 1' killed.err)"
else echo "FAIL: killed rank (victim '$victim'): rc $rc, ${took} s, left: '$(viewers)': $(cat killed.err)"; fail=1; fi

# ---- a window under Xvfb with 2 ranks: the q key ends every rank ----
if command -v Xvfb >/dev/null && command -v xdotool >/dev/null; then
  cat >drive.sh <<EOF
set -u
. '$src/tests/viewer_drive.sh'
STATE="$dir/state.json"
rm -f "\$STATE"
timeout 180 ${mpi[*]} -n 2 "$amrvk" view "$cloud" --size 40x40 --frames 1000000 --window 640x400 --state-file "\$STATE" --validation &
VIEWER=\$!
spp_at_least() { local n; n=\$(state spp) && [ "\$n" -ge "\$1" ]; }
wait_until "8 spp over 2 ranks" spp_at_least 8
[ "\$(state ranks)" = 2 ] || { echo "drive: ranks \$(state ranks)" >&2; kill \$VIEWER; exit 1; }
quit
EOF
  bash "$src/tests/with_xvfb.sh" 800x600x24 bash drive.sh >window.out 2>window.err; rc=$?
  if [ $rc = 0 ] && [ -z "$(viewers)" ] && [ -z "$(for p in /proc/[0-9]*; do tr '\0' ' ' <"$p/cmdline" 2>/dev/null | grep -qF -- "--window 640x400 --state-file $dir" && echo "$p"; done)" ]; then
    echo "ok: window with 2 ranks: q ended every rank (first picture after $(sed -n 's/^  "firstPictureSeconds": \(.*\),$/\1/p' state.json) s)"
  else echo "FAIL: window with 2 ranks: rc $rc: $(tail -5 window.err)"; fail=1; fi
else
  echo "skip: window test (no Xvfb or xdotool)"
fi
exit $fail
