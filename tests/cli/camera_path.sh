#!/usr/bin/env bash
# Usage: camera_path.sh AMRVK SCRATCH. Camera paths (issue 53, docs/movies.md "Camera paths"): a
# headless viewer script adds three keyframes, shows one path frame, plays the path and saves the
# session; `render --session` of it writes the path's frames, whose cameras (--json) equal the
# cameras the viewer reported for each path frame (--stats) within 1e-5, shown to tell neighbouring
# frames apart; a frame's image equals a single `render --camera` of its camera (same seed, spp and
# code path: the same samples, so to 1e-6; a neighbouring frame does not); one picture of the
# session is the path's frame 0; a series of three outputs over the path (output floor(3k/7) in
# frame k), by render and by the viewer playing the path; the movie at the path's fps and at --fps, its frame count; a re-run renders nothing, an
# edited path everything; contradicting options and bad script lines are one-line errors.
set -u
amrvk="$1"; dir="$2"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail=0
source "$here/lib.sh"
py=/usr/bin/python3
export AMRVK_PROGRESS=0
"$amrvk" gen cloud --cells 3000 --seed 3 -o c >/dev/null || { echo "FAIL: gen"; exit 1; }
# The first picture's older defaults: the medium lies where the cloud is (see series.sh).
pic=(--size 32x32 --spp 4 --grid 8 --scale linear --tf ramp --background 1 1 1)

# ---- the viewer: keyframes, one path frame shown, the path played, the session saved ----
cat >path.txt <<'EOF'
0 keyframe-add 0
1 orbit 150 0
2 keyframe-add 3
3 orbit 120 40
3 zoom 2
4 keyframe-add 6
5 path-fps 12
5 path-frame 4
6 path-play
16 save-session path.json
16 quit
EOF
"$amrvk" view c.cells "${pic[@]}" --headless --script path.txt --stats stats.json --state-file state.json \
  >view.out 2>view.err || { echo "FAIL: viewer: $(tail -2 view.err)"; fail=1; }
check grep -q '"path": {"keyframes":3,"frames":7,"frame":6,"playing":false}' state.json

# ---- the session's path rendered: frame k with the camera the viewer showed for path frame k ----
"$amrvk" render --session path.json -o 'frames/f_%02d.pfm' --json f.json >f.out 2>f.err \
  || { echo "FAIL: render --session: $(cat f.err)"; fail=1; }
check grep -q "wrote frames/f_%02d.pfm (7 frames: 7 rendered" f.out
cam=$("$py" - <<'PY'
import json
j, st, s = json.load(open("f.json")), json.load(open("stats.json")), json.load(open("path.json"))
keys = s["cameraPath"]["keyframes"]
assert [k["frame"] for k in keys] == [0, 3, 6] and s["cameraPath"]["fps"] == 12, s["cameraPath"]
assert j["frameCount"] == 7 and j["cameraPath"] == {"frames": 7, "fps": 12}, (j["frameCount"], j["cameraPath"])
shown = st["pathFramesShown"]
# path-frame 4, then the play: 0, 1, ..., 6, one path frame a viewer frame.
assert [f["frame"] for f in shown] == [4, 0, 1, 2, 3, 4, 5, 6], [f["frame"] for f in shown]
def flat(c):
    return c["eye"] + c["target"] + c["up"] + [c.get("fovY", c.get("fovYDegrees"))]
def gap(a, b):
    return max(abs(x - y) for x, y in zip(flat(a), flat(b)))
movie = {f["pathFrame"]: f["camera"] for f in j["frames"]}
assert sorted(movie) == list(range(7)), sorted(movie)
for f in shown:
    assert gap(f["camera"], movie[f["frame"]]) <= 1e-5, (f["frame"], f["camera"], movie[f["frame"]])
# The check can tell neighbouring frames apart, and the keyframes are the cameras the viewer saved.
for k in range(6):
    assert gap(movie[k], movie[k + 1]) > 1e-3, ("frames %d and %d share a camera" % (k, k + 1))
for key in keys:
    assert gap(key["camera"], movie[key["frame"]]) == 0, key
print(" ".join(repr(v) for v in flat(movie[2])))
PY
) || { echo "FAIL: path cameras"; fail=1; }
echo "ok: the movie's cameras are the viewer's, frame for frame"

# ---- a frame's picture against a single render of its camera (same seed, spp, code path) ----
set -- $cam
"$amrvk" render --session path.json --camera "$1" "$2" "$3" "$4" "$5" "$6" "$7" "$8" "$9" --fov "${10}" \
  -o single.pfm >single.out 2>single.err || { echo "FAIL: single render: $(cat single.err)"; fail=1; }
"$amrvk" render --session path.json -o first.pfm >first.out 2>first.err || fail=1
check grep -q "the session's camera path has 7 frames: rendering its frame 0" first.err
check "$py" - <<'PY'
import numpy as np
def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"; w, h = map(int, f.readline().split()); scale = float(f.readline())
        return np.fromfile(f, "<f4" if scale < 0 else ">f4").reshape(h, w, 3)
single, first = pfm("single.pfm"), pfm("first.pfm")
f0, f1, f2, f3 = (pfm("frames/f_%02d.pfm" % k) for k in range(4))
# The same seed, spp, camera and code path (Picture::render): the same samples, so the same pixels.
assert np.abs(f2 - single).max() <= 1e-6, ("frame 2 is not the single render of its camera", np.abs(f2 - single).max())
assert np.abs(f0 - first).max() <= 1e-6, ("one picture of the session is not frame 0", np.abs(f0 - first).max())
for other in (f1, f3):  # power: the neighbouring frames' pictures differ
    assert np.abs(other - single).mean() > 1e-3, np.abs(other - single).mean()
print("ok: frame 2 equals the single render of its camera; frames 1 and 3 differ by %.3g, %.3g"
      % (np.abs(f1 - single).mean(), np.abs(f3 - single).mean()))
PY

# ---- a re-run renders nothing; an edited path renders every frame anew ----
"$amrvk" render --session path.json -o 'frames/f_%02d.pfm' >rerun.out 2>&1 || fail=1
check grep -q "(7 frames: 0 rendered, 7 already written by this command" rerun.out
"$py" -c '
import json
s = json.load(open("path.json")); s["cameraPath"]["keyframes"][1]["camera"]["fovY"] = 30
json.dump(s, open("edited.json", "w"), indent=2)' || fail=1
"$amrvk" render --session edited.json -o 'frames/f_%02d.pfm' >edited.out 2>edited.err || fail=1
check grep -q "records another command: rendering all 7 frames anew" edited.err
check grep -q "(7 frames: 7 rendered, 0 already written" edited.out

# ---- a series over the path: frame k shows output floor(3k/7) ----
for pair in "1 0" "2 0.15" "3 0.3"; do
  set -- $pair
  "$amrvk" gen cloud --cells 3000 --seed 3 --time "$2" -o "out_$1" >/dev/null || fail=1
done
"$amrvk" render --session path.json 'out_*.cells' -o 'series/f_%d.png' --json s.json >/dev/null 2>s.err \
  || { echo "FAIL: series over the path: $(cat s.err)"; fail=1; }
check "$py" -c '
import json, os
j = json.load(open("s.json"))
names = [os.path.basename(f["input"]) for f in j["frames"]]
assert names == ["out_1.cells"] * 3 + ["out_2.cells"] * 2 + ["out_3.cells"] * 2, names'
# The viewer over the same series plays the same path with the same step per frame: the session's
# path, played, and the steps it showed (--stats "steps") are those render showed (0 first).
printf '1 path-play\n14 quit\n' >series-path.txt
"$amrvk" view --session path.json 'out_*.cells' --headless --script series-path.txt --stats series-stats.json \
  >series-view.out 2>series-view.err || { echo "FAIL: viewer over the series: $(tail -2 series-view.err)"; fail=1; }
check "$py" -c '
import json
j = json.load(open("series-stats.json"))
assert [f["frame"] for f in j["pathFramesShown"]] == list(range(7)), j["pathFramesShown"]
assert [s["step"] for s in j["steps"]] == [1, 2], j["steps"]  # frames 3 and 5: floor(3k/7) goes 0 -> 1 -> 2'

# ---- movies: the path's fps, or --fps; the frame count ----
if command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null; then
  frames() { ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$1"; }
  rate() { ffprobe -v error -select_streams v:0 -show_entries stream=r_frame_rate -of csv=p=0 "$1"; }
  "$amrvk" render --session path.json -o movie.mp4 >m.out 2>m.err || { echo "FAIL: movie: $(cat m.err)"; fail=1; }
  check test "$(frames movie.mp4)" = 7
  check test "$(rate movie.mp4)" = 12/1
  "$amrvk" render --session path.json --fps 5 -o movie5.mp4 --frames-dir kept >/dev/null 2>&1 || fail=1
  check test "$(rate movie5.mp4)" = 5/1
  check test "$(ls kept | grep -c '^frame_.*\.png$')" = 7
else
  echo "skip: the movie checks (no ffmpeg/ffprobe)"
fi

# ---- contradictions and bad scripts: one line, exit 1 ----
expect "--orbit: the session's camera path (7 frames) moves the camera" -- render --session path.json --orbit 90 -o 'x/f_%d.png'
expect "--frames: the session's camera path (7 frames) sets the frame count" -- render --session path.json --frames 3 -o 'x/f_%d.png'
expect "--camera: the session's camera path (7 frames) sets every frame's camera" -- render --session path.json --camera 1 1 1 0 0 0 0 0 1 -o 'x/f_%d.png'
for i in 1 2 3 4 5 6 7 8; do "$amrvk" gen cloud --cells 500 --seed 3 --time 0.$i -o "many_$i" >/dev/null || fail=1; done
expect "8 inputs over the session's camera path (7 frames): some outputs would show in no frame" -- render --session path.json 'many_*.cells' -o 'x/f_%d.png'
check test ! -e x
printf '0 keyframe-add 1.5\n' >bad1.txt
expect "bad1.txt:1: keyframe-add: frame 1.5 is not a whole number in [0, 99999]" -- view c.cells "${pic[@]}" --headless --script bad1.txt
# A line that fails when it runs: after the trace of the lines run before it, one error line.
printf '0 keyframe-add 2\n1 keyframe-add 2\n' >bad2.txt
"$amrvk" view c.cells "${pic[@]}" --headless --script bad2.txt >bad2.out 2>bad2.err; rc=$?
if [ "$rc" != 1 ] || [ "$(grep -c error bad2.err)" != 1 ] || \
   ! tail -1 bad2.err | grep -qF "error: bad2.txt:2: keyframe-add: camera path: frame 2 already has a keyframe"; then
  echo "FAIL: a keyframe twice at one frame: rc=$rc: $(cat bad2.err)"; fail=1
else
  echo "ok: a keyframe twice at one frame -> $(tail -1 bad2.err)"
fi
printf '0 path-play\n' >bad3.txt
expect "bad3.txt:1: path-play: the camera path has no keyframes" -- view c.cells "${pic[@]}" --headless --script bad3.txt
printf '0 path-fps 0\n' >bad4.txt
expect "bad4.txt:1: path-fps: fps 0 is outside (0, 1000]" -- view c.cells "${pic[@]}" --headless --script bad4.txt
exit $fail
