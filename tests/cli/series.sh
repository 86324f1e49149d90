#!/usr/bin/env bash
# Usage: series.sh AMRVK SCRATCH. Time series and turntables of `amrvk render` (docs/movies.md) on
# a series made by `amrvk gen --time`: frames in natural order with their names and sizes; the
# union TF range equal to the min/max of every output's range as `amrvk info --json` reports it;
# a re-run that skips every frame (mtimes unchanged) and a changed command that renders anew; the
# turntable's cameras against rotations computed here and its frame 1 against a single render
# with that camera (tile z-test, with the power shown on the wrong frame); spiky over a series
# fitted to the outputs' pooled percentiles (within one percentile of numpy's over all values) or
# the first output's, over a turntable to the output's; a session over a series;
# the memory peak of four outputs against one; SIGINT in the middle leaving only whole frames and
# a run that resumes; one-line errors for bad series.
set -u
amrvk="$1"; dir="$2"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail=0
source "$here/lib.sh"
py=/usr/bin/python3
export AMRVK_PROGRESS=0

# Three outputs at T = 0, 0.15, 0.3, named so that plain order would put out_10 before out_2.
for pair in "1 0" "2 0.15" "10 0.3"; do
  set -- $pair
  "$amrvk" gen cloud --cells 3000 --seed 3 --time "$2" -o "out_$1" >/dev/null || { echo "FAIL: gen --time $2"; fail=1; }
  "$amrvk" info "out_$1.cells" --json >"info_$1.json" || fail=1
done
pic=(--size 32x24 --spp 4 --grid 8)

# ---- a series to numbered frames, union range ----
"$amrvk" render 'out_*.cells' "${pic[@]}" -o 'frames/f_%02d.png' --json s.json >s.out 2>s.err \
  || { echo "FAIL: series render: $(cat s.err)"; fail=1; }
check "$py" - <<'PY'
import json, os, struct
j = json.load(open("s.json"))
names = [os.path.basename(f["input"]) for f in j["frames"]]
assert names == ["out_1.cells", "out_2.cells", "out_10.cells"], names
assert sorted(os.listdir("frames")) == ["f_00.png", "f_01.png", "f_02.png", "f_manifest.json"], os.listdir("frames")
for k in range(3):
    data = open("frames/f_%02d.png" % k, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[-12:-8] == b"\0\0\0\0" and data[-8:-4] == b"IEND", k
    w, h = struct.unpack(">II", data[16:24])
    assert (w, h) == (32, 24), (k, w, h)
assert j["rendered"] == 3 and j["frameCount"] == 3 and j["rangeSource"] == "union", j
# The union range against every output's range from `amrvk info --json`, taken independently.
ranges = [json.load(open("info_%d.json" % n))["valueRange"] for n in (1, 2, 10)]
lo, hi = min(r[0] for r in ranges), max(r[1] for r in ranges)
assert abs(j["tfRange"][0] - lo) <= 1e-6 * abs(lo) and abs(j["tfRange"][1] - hi) <= 1e-6 * abs(hi), (j["tfRange"], ranges)
# The outputs' ranges differ, so union differs from first (the test can tell them apart).
assert abs(ranges[0][1] - hi) > 1e-3 * hi, ranges
print("ok: union range", j["tfRange"], "over", ranges)
PY
check grep -q "wrote frames/f_%02d.png (3 frames: 3 rendered, 0 already written" s.out

# ---- a legend in every frame (one range for the series, so every frame's legend is the same) and a cut ----
"$amrvk" render 'out_*.cells' --size 96x64 --spp 2 --grid 8 --legend --crop 0 0 0 256 256 128 -o 'leg/l_%d.png' >/dev/null 2>leg.err || { echo "FAIL: legend series: $(tail -1 leg.err)"; fail=1; }
check "$py" - <<'PY'
import struct
sizes = []
for k in range(3):
    d = open("leg/l_%d.png" % k, "rb").read()
    sizes.append(struct.unpack(">II", d[16:24]))
assert len(set(sizes)) == 1 and sizes[0][0] > 96 and sizes[0][1] == 64, sizes  # the picture, and a strip beside it
print("ok: legend frames", sizes[0])
PY
expect "--legend: only PNG frames get a legend" -- render 'out_*.cells' "${pic[@]}" --legend -o 'x/x_%d.pfm'
expect "too small for a legend" -- render 'out_*.cells' "${pic[@]}" --legend -o 'small/s_%d.png'
check test ! -e small/s_0.png

# ---- the first output's range ----
"$amrvk" render 'out_*.cells' "${pic[@]}" --series-range first -o 'first/f_%d.png' --json first.json >/dev/null 2>&1 || fail=1
check "$py" -c '
import json
j = json.load(open("first.json")); r = json.load(open("info_1.json"))["valueRange"]
assert j["rangeSource"] == "first" and all(abs(a - b) <= 1e-6 * abs(b) for a, b in zip(j["tfRange"], r)), (j["tfRange"], r)'

# ---- a re-run of the same command skips every frame; another command renders anew ----
mtimes() { "$py" -c 'import os,sys; print(" ".join(str(os.stat(f).st_mtime_ns) for f in sys.argv[1:]))' frames/f_0*.png; }
before=$(mtimes)
sleep 0.05
"$amrvk" render "${pic[@]}" 'out_*.cells' -o 'frames/f_%02d.png' --json s2.json >s2.out 2>s2.err || fail=1
check grep -q "(3 frames: 0 rendered, 3 already written by this command" s2.out
check test "$before" = "$(mtimes)"
check "$py" -c 'import json; j = json.load(open("s2.json")); assert j["rendered"] == 0 and not any(f["rendered"] for f in j["frames"]), j'
rm frames/f_01.png  # a frame removed by hand is rendered again, alone
"$amrvk" render 'out_*.cells' "${pic[@]}" -o 'frames/f_%02d.png' >s3.out 2>&1 || fail=1
check grep -q "(3 frames: 1 rendered, 2 already written" s3.out
"$amrvk" render 'out_*.cells' --size 32x24 --spp 2 --grid 8 -o 'frames/f_%02d.png' >s4.out 2>s4.err || fail=1
check grep -q "(3 frames: 3 rendered, 0 already written" s4.out
check grep -q "f_manifest.json records another command: rendering all 3 frames anew" s4.err
rm frames/f_manifest.json  # frames without their record: replaced, and said
"$amrvk" render 'out_*.cells' "${pic[@]}" -o 'frames/f_%02d.png' >s5.out 2>s5.err || fail=1
check grep -q "(3 frames: 3 rendered, 0 already written" s5.out
check grep -q "3 of the frames exist without a manifest (frames/f_manifest.json): rendering all 3 anew" s5.err

# ---- a turntable: cameras against rotations computed here, frame 1 against a single render ----
# As before the first picture's defaults (linear values, the ramp, a white background): the medium
# lies only where the cloud is, so no tile holds a hit too rare for the single render's variance.
old=(--scale linear --tf ramp --background 1 1 1)
"$amrvk" render out_1.cells --size 32x32 --spp 16 --grid 8 "${old[@]}" --frames 4 --orbit 360 -o 't_%d.pfm' --json t.json \
  >/dev/null 2>t.err || { echo "FAIL: turntable: $(cat t.err)"; fail=1; }
cam=$("$py" - <<'PY'
import json, math
j = json.load(open("t.json")); info = json.load(open("info_1.json"))
lo, hi = info["worldBounds"]["lower"], info["worldBounds"]["upper"]
centre = [(a + b) / 2 for a, b in zip(lo, hi)]
assert all(abs(a - b) < 1e-9 for a, b in zip(j["orbitCentre"], centre)), (j["orbitCentre"], centre)
c0 = j["frames"][0]["camera"]
up = c0["up"]; n = math.sqrt(sum(u * u for u in up)); k = [u / n for u in up]
def turn(p, deg):  # Rodrigues about the line through centre along up
    v = [a - b for a, b in zip(p, centre)]; t = math.radians(deg); c, s = math.cos(t), math.sin(t)
    kv = sum(a * b for a, b in zip(k, v)); kx = [k[1]*v[2]-k[2]*v[1], k[2]*v[0]-k[0]*v[2], k[0]*v[1]-k[1]*v[0]]
    return [centre[i] + v[i]*c + kx[i]*s + k[i]*kv*(1-c) for i in range(3)]
for f in j["frames"]:
    assert f["azimuthDegrees"] == 90 * f["index"], f
    for key in ("eye", "target"):
        want = turn(c0[key], f["azimuthDegrees"])
        assert all(abs(a - b) < 1e-9 for a, b in zip(f["camera"][key], want)), (f["index"], key, f["camera"][key], want)
c1 = j["frames"][1]["camera"]
print(" ".join(repr(v) for v in c1["eye"] + c1["target"] + c1["up"]))
PY
) || { echo "FAIL: turntable cameras"; fail=1; }
"$amrvk" render out_1.cells --size 32x32 --spp 16 --grid 8 "${old[@]}" --seed 2 --camera $cam -o single.pfm --variance single_var.pfm \
  >/dev/null 2>&1 || { echo "FAIL: single render"; fail=1; }
check "$py" - <<'PY'
import numpy as np
def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"; w, h = map(int, f.readline().split()); scale = float(f.readline())
        return np.fromfile(f, "<f4" if scale < 0 else ">f4").reshape(h, w, 3)
frame1, frame0, single, var = pfm("t_1.pfm"), pfm("t_0.pfm"), pfm("single.pfm"), pfm("single_var.pfm")
def worst_z(a):  # 8x8 tiles: mean difference over its standard error (both images' variance ~ the single's)
    d = (a - single).reshape(4, 8, 4, 8, 3).mean(axis=(1, 3))
    se = np.sqrt(2 * var.reshape(4, 8, 4, 8, 3).sum(axis=(1, 3)) / 64**2)
    return np.max(np.abs(d) / np.maximum(se, 1e-12))
# 48 tile-channels: Sidak at 1e-3 overall gives |z| < 4.1.
z1, z0 = worst_z(frame1), worst_z(frame0)
assert z1 < 4.1, ("frame 1 differs from the single render with its camera", z1)
assert z0 > 4.1, ("the test cannot tell frame 0 from frame 1", z0)
print("ok: turntable frame 1 vs single render: worst |z| %.2f (frame 0: %.1f)" % (z1, z0))
PY

# ---- spiky over a series: one TF for every output, fitted to the outputs' pooled percentiles
# ---- (union) or the first output's; a turntable of one output: fitted like a single picture ----
sp=(--size 32x24 --spp 4 --grid 8 --mode ae --tf spiky)
"$amrvk" render 'out_*.cells' "${sp[@]}" -o 'sp/f_%d.pfm' --json sp.json >/dev/null 2>sp.err || { echo "FAIL: spiky series: $(cat sp.err)"; fail=1; }
check grep -q "tf spiky: alpha-1 peaks at the 75th, 90th and 97th percentiles of the series' cell values" sp.err
# The series' TF (its --json) given as a file to a single render of the first output: frame 0.
"$py" -c 'import json; json.dump([json.load(open("sp.json"))["transferFunction"]], open("sp_tf.json", "w"))' || fail=1
"$amrvk" render out_1.cells "${sp[@]/spiky/sp_tf.json}" -o sp_series_tf.pfm >/dev/null 2>&1 || fail=1
# The old rule, for power: spiky's range-fixed shape over the union range.
range=$("$py" -c 'import json; print(*json.load(open("sp.json"))["tfRange"])')
"$amrvk" render out_1.cells "${sp[@]}" --tf-range $range -o sp_fixed.pfm >/dev/null 2>&1 || fail=1
# --series-range first: every frame (frame 0 too) fitted to the first output, as a single render is.
"$amrvk" render 'out_*.cells' "${sp[@]}" --series-range first -o 'sp_first/f_%d.pfm' --json sp_first.json >/dev/null 2>&1 || fail=1
"$amrvk" render out_1.cells "${sp[@]}" -o sp_fitted.pfm >/dev/null 2>sp_fitted.err || fail=1
# The default TF (layers, sized by the volume histogram) over first: frame 0 is the single picture;
# layers' range-fixed shape over the same range (the old rule) is not.
ly=(--size 32x24 --spp 4 --grid 8 --mode ae)
"$amrvk" render 'out_*.cells' "${ly[@]}" --series-range first -o 'ly_first/f_%d.pfm' >/dev/null 2>&1 || fail=1
"$amrvk" render out_1.cells "${ly[@]}" -o ly_single.pfm >/dev/null 2>&1 || fail=1
first=$("$py" -c 'import json; print(*json.load(open("info_1.json"))["valueRange"])')
"$amrvk" render out_1.cells "${ly[@]}" --tf layers --tf-range $first -o ly_fixed.pfm >/dev/null 2>&1 || fail=1
"$amrvk" render out_1.cells "${sp[@]}" --frames 2 --orbit 90 -o 'sp_tt/f_%d.pfm' >/dev/null 2>sp_tt.err || fail=1
check grep -q "tf spiky: alpha-1 peaks at the 75th, 90th and 97th percentiles of the cell values" sp_fitted.err
check grep -q "tf spiky: alpha-1 peaks" sp_tt.err
check "$py" - <<'PY'
import json
import numpy as np
def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"; w, h = map(int, f.readline().split()); scale = float(f.readline())
        return np.fromfile(f, "<f4" if scale < 0 else ">f4").reshape(h, w, 3)
series0, seriesTf, fixed, fitted, turn0 = (pfm(p) for p in ("sp/f_0.pfm", "sp_series_tf.pfm", "sp_fixed.pfm",
                                                             "sp_fitted.pfm", "sp_tt/f_0.pfm"))
first0 = pfm("sp_first/f_0.pfm")
layers0, layersSingle, layersFixed = pfm("ly_first/f_0.pfm"), pfm("ly_single.pfm"), pfm("ly_fixed.pfm")
assert np.abs(layers0 - layersSingle).max() <= 1e-6, ("first: frame 0's layers are not the single picture's",
                                                      np.abs(layers0 - layersSingle).max())
assert np.abs(layersFixed - layersSingle).mean() > 1e-4, "fitted and range-fixed layers render alike: no power"
j, jf = json.load(open("sp.json")), json.load(open("sp_first.json"))
# Union: the pooled percentiles against every output's values together (log10, the auto scale here),
# by rank: each within one percentile of its k (plus one value per output).
values = np.concatenate([np.log10(np.fromfile("out_%d.scalars" % n, "<f4").astype(np.float64)) for n in (1, 2, 10)])
values.sort()
n, p = len(values), np.array(j["tfPercentiles"])
below = np.searchsorted(values, p, "left") / n - 1e-6
atOrBelow = np.searchsorted(values, p, "right") / n + 1e-6
k = np.arange(101) / 100
err = np.maximum(0, np.maximum(below - k, k - atOrBelow))
assert err.max() <= 0.01 + 3 / n, ("pooled percentiles off by more than one percentile", err.max(), np.argmax(err))
assert abs(p[0] - values[0]) < 1e-5 and abs(p[100] - values[-1]) < 1e-5, (p[0], p[100], values[0], values[-1])
# The TF's alpha-1 apexes sit at the pooled P75, P90 and P97.
rgb = j["transferFunction"]["RGBPoints"]; op = j["transferFunction"]["Points"]
apexes = [op[i] for i in range(0, len(op), 4) if op[i + 1] == 1.0]
assert np.allclose(apexes, p[[75, 90, 97]], rtol=0, atol=1e-6), (apexes, p[[75, 90, 97]])
# First: the first output's own percentiles (amrvk info), so frame 0 is the single render's fitted spiky.
info1 = json.load(open("info_1.json"))
assert np.allclose(jf["tfPercentiles"], info1["valuePercentiles"], rtol=0, atol=0), "first: not the first output's percentiles"
# Same seed, camera and TF: the same samples.
assert np.abs(series0 - seriesTf).max() <= 1e-6, ("series frame 0 is not the series' TF", np.abs(series0 - seriesTf).max())
assert np.abs(first0 - fitted).max() <= 1e-6, ("--series-range first: frame 0 is not fitted to the first output",
                                               np.abs(first0 - fitted).max())
assert np.abs(turn0 - fitted).max() <= 1e-6, ("turntable frame 0 is not the fitted spiky", np.abs(turn0 - fitted).max())
assert np.abs(fixed - series0).mean() > 1e-4, "the pooled and the range-fixed spiky render alike: the test cannot tell them"
assert np.abs(fitted - series0).mean() > 1e-4, "pooled and first-output spiky render alike: the test cannot tell them"
print("ok: spiky over a series fitted to the pooled percentiles (largest rank error %.4f), differs from range-fixed by %.4f"
      % (err.max(), np.abs(fixed - series0).mean()))
PY

# ---- a session (the viewer's) over the series, and over its own input as a turntable ----
"$amrvk" view out_1.cells "${pic[@]}" --tf spiky --headless --frames 1 --save-session sess.json >/dev/null 2>&1 || fail=1
"$amrvk" render --session sess.json 'out_*.cells' -o 'sess/f_%d.png' --json sj.json >/dev/null 2>&1 || fail=1
"$amrvk" render --session sess.json --frames 2 --orbit 180 -o 'sess2/f_%d.png' --json sj2.json >/dev/null 2>&1 || fail=1
check "$py" - <<'PY'
import json, os
s, j, t = json.load(open("sess.json")), json.load(open("sj.json")), json.load(open("sj2.json"))
assert [os.path.basename(f["input"]) for f in j["frames"]] == ["out_1.cells", "out_2.cells", "out_10.cells"], j
# The session's own TF (no range fitted) and its camera for every frame.
assert j["rangeSource"] == "session" and j["tfRange"] is None, j
assert all(f["camera"]["eye"] == s["camera"]["eye"] and f["camera"]["target"] == s["camera"]["target"] for f in j["frames"])
assert all(f["stats"]["width"] == 32 and f["stats"]["spp"] == 4 for f in j["frames"]), j["frames"][0]["stats"]
# Without inputs the session's own is the turntable's; frame 1 is 90 degrees round.
assert [os.path.basename(f["input"]) for f in t["frames"]] == ["out_1.cells"] * 2 and t["frames"][1]["azimuthDegrees"] == 90
assert t["frames"][0]["camera"]["eye"] == s["camera"]["eye"] and t["frames"][1]["camera"]["eye"] != s["camera"]["eye"]
print("ok: --session over a series and as a turntable")
PY

# ---- memory: one output at a time (the peak does not grow with the outputs rendered) ----
for i in 0 1 2 3; do "$amrvk" gen cloud --cells 1e6 --seed 3 --time 0.$i -o big_$i >/dev/null || fail=1; done
"$amrvk" render big_0.cells --size 16x16 --spp 1 -o one.png --json one.json >/dev/null 2>&1 || fail=1
"$amrvk" render 'big_*.cells' --size 16x16 --spp 1 -o 'big/f_%d.png' --json big.json >/dev/null 2>&1 || fail=1
check "$py" - <<'PY'
import json, os
one, big = json.load(open("one.json")), json.load(open("big.json"))
# What one more output in memory would add: its cells and values and its device copy (host memory on lavapipe).
per_output = os.path.getsize("big_0.cells") + os.path.getsize("big_0.scalars") + one["deviceMemoryBytes"]
peaks = [f["stats"]["peakHostBytes"] for f in big["frames"]]
assert big["peakResidentBytes"] - one["peakHostBytes"] < 0.75 * per_output, (big["peakResidentBytes"], one["peakHostBytes"], per_output)
assert peaks[-1] - peaks[0] < 0.5 * per_output, (peaks, per_output)
print("ok: 4 outputs peak at %.0f MB, one alone at %.0f MB (an output holds %.0f MB)" %
      (big["peakResidentBytes"] / 1e6, one["peakHostBytes"] / 1e6, per_output / 1e6))
PY

# ---- SIGINT in the middle leaves whole frames only; the same command resumes ----
turn=(out_2.cells --size 48x48 --spp 64 --grid 8 --frames 40 --orbit 360 -o 'int/i_%02d.png')
# Stopped as soon as its manifest exists (before frame 0 is done, where the camera is resolved) ...
"$amrvk" render "${turn[@]}" >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1200); do [ -e int/i_manifest.json ] && break; sleep 0.02; done
kill -INT $pid; wait $pid
# ... then again once a frame is written.
"$amrvk" render "${turn[@]}" >/dev/null 2>&1 &
pid=$!
for _ in $(seq 600); do [ -e int/i_00.png ] && break; sleep 0.1; done
kill -INT $pid; wait $pid; rc=$?
check test "$rc" -gt 128
check test -z "$(ls int | grep -e '\.tmp-' || true)"
kept=$(ls int | grep -c '^i_.*\.png$')
check "$py" -c '
import json, os, sys
done = json.load(open("int/i_manifest.json"))["done"]
for f in sorted(os.listdir("int")):
    if f.endswith(".png"):
        data = open("int/" + f, "rb").read()
        assert data[-8:-4] == b"IEND", f + " is not a whole PNG"
assert all(os.path.exists("int/i_%02d.png" % k) for k in done), done'
before=$("$py" -c 'import os; print(sorted((f, os.stat("int/" + f).st_mtime_ns) for f in os.listdir("int") if f.endswith(".png")))')
"$amrvk" render "${turn[@]}" --json int.json >int.out 2>&1 || fail=1
check grep -q "(40 frames: $((40 - kept)) rendered, $kept already written" int.out
# The resumed series has the camera of an uninterrupted one (frame 0: the default view of out_2).
"$amrvk" render out_2.cells --size 16x16 --spp 1 --frames 2 --orbit 18 -o 'fresh/f_%d.png' --json fresh.json >/dev/null 2>&1 || fail=1
check "$py" -c '
import json
a, b = json.load(open("int.json"))["frames"], json.load(open("fresh.json"))["frames"]
assert a[0]["camera"] == b[0]["camera"] and a[1]["camera"] == b[1]["camera"], (a[0]["camera"], b[0]["camera"])'
after=$("$py" -c 'import os; print(sorted((f, os.stat("int/" + f).st_mtime_ns) for f in os.listdir("int") if f.endswith(".png")))')
check "$py" -c "b = $before; a = dict($after); assert all(a[f] == t for f, t in b), 'a frame written before the interrupt was rendered again'"
echo "ok: interrupted after $kept of 40 frames; the re-run rendered the rest"

# ---- bad series: one line, exit 1, nothing written ----
"$amrvk" gen cloud --cells 3000 --seed 3 --time 0.45 --field rho -o out_20 >/dev/null || fail=1
expect "nomatch_*.cells': no file or directory matches the pattern" -- render 'nomatch_*.cells' "${pic[@]}" -o 'x/x_%d.png'
expect "field 'scalars'" -- render 'out_*.cells' "${pic[@]}" -o 'x/x_%d.png'
expect "--frames 3: renders one input 3 times" -- render out_1.cells out_2.cells "${pic[@]}" --frames 3 --orbit 360 -o 'x/x_%d.png'
expect "-o x.png: 3 frames need a numbered name with %d" -- render out_1.cells out_2.cells out_10.cells "${pic[@]}" -o x.png
expect "--frames 3 without --orbit" -- render out_1.cells "${pic[@]}" --frames 3 -o 'x/x_%d.png'
expect "--orbit over one input needs --frames N" -- render out_1.cells "${pic[@]}" --orbit 90 -o 'x/x_%d.png'
expect "--variance v.pfm: one image only" -- render out_1.cells out_2.cells "${pic[@]}" -o 'x/x_%d.png' --variance v.pfm
expect "--frames-dir fd: only with -o MOVIE.mp4" -- render out_1.cells out_2.cells "${pic[@]}" -o 'x/x_%d.png' --frames-dir fd
expect "'%' starts a frame number only as %d" -- render out_1.cells out_2.cells "${pic[@]}" -o 'x/x_%s.png'
expect "input 'out_1.cells' is named twice" -- render out_1.cells 'out_1*.cells' "${pic[@]}" -o 'x/x_%d.png'
check test ! -e x.png
check test ! -e x
check test ! -e fd
check test ! -e v.pfm
exit $fail
