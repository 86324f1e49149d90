#!/usr/bin/env bash
# Usage: render.sh AMRVK SOURCE_DIR SCRATCH. The render CLI end to end on the bundled sample:
# JSON statistics with every documented key, shaders loaded from --shader-dir (compiled from GLSL
# at run time), each image format, and one-line errors that leave no output behind.
set -u
amrvk="$1"; src="$2"; dir="$3"
rm -rf "$dir"; mkdir -p "$dir"
sample="$src/assets/samples/cloud.cells"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

common=(--size 16x12 --spp 2 --grid 16 --tf-range 0 1)
"$amrvk" render "$sample" "${common[@]}" -o "$dir/a.png" --json "$dir/a.json" || fail=1
check test -s "$dir/a.png"
check python3 - "$dir/a.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
keys = ["device", "width", "height", "spp", "mode", "traversal", "sampler", "seconds", "pathsPerSecond",
        "densityLookups", "realCollisions", "nullCollisions", "traversalSteps", "majorantViolations",
        "deviceMemoryBytes", "deviceMemoryPeakBytes", "meanRGB"]
missing = [k for k in keys if k not in j]
assert not missing, missing
assert j["width"] == 16 and j["height"] == 12 and j["spp"] == 2 and j["mode"] == "ms", j
assert j["majorantViolations"] == 0 and j["densityLookups"] > 0, j
assert len(j["meanRGB"]) == 3 and all(0 <= v < 10 for v in j["meanRGB"]), j
assert j["deviceMemoryPeakBytes"] >= j["deviceMemoryBytes"] > 0, j
assert j["backend"] in ("sw", "rq") and "hostMemoryPerStructure" in j, j
PY
# A box traversal with the kd-tree: its build time and per-structure bytes are reported, and a
# control extinction it cannot use (minorants are the macrocells') is said to be off, in one line.
"$amrvk" render "$sample" "${common[@]}" --traversal kdtree --kd-leaves 64 --backend sw -o "$dir/k.png" \
  --json "$dir/k.json" --control-extinction minorant >/dev/null 2>"$dir/k.err" || fail=1
check grep -q "^amrvk: --control-extinction minorant is off: the traversal is kdtree (minorants need grid-dda or grid-bvh)" "$dir/k.err"
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["traversal"] == "kdtree" and j["activeTraversalBoxes"] > 0 and j["structureBuildSecondsPer"]["kdTree"] > 0 and j["hostMemoryPerStructure"]["kdTree"] > 0 and j["majorantViolations"] == 0, j' "$dir/k.json"
for ext in exr pfm; do
  "$amrvk" render "$sample" "${common[@]}" --mode ae --sampler abr -o "$dir/a.$ext" >/dev/null || fail=1
  check test -s "$dir/a.$ext"
done
"$amrvk" render "$sample" "${common[@]}" --mode ss --shader-dir "$src/shaders/passes" -o "$dir/s.pfm" >/dev/null || fail=1
check test -s "$dir/s.pfm"
"$amrvk" devices | grep -q "^0: " || { echo "FAIL: amrvk devices lists no device"; fail=1; }
# The dvr baseline (with gradient shading), the dense sampler, and the automatic structure choice.
"$amrvk" render "$sample" "${common[@]}" --mode dvr --dt 0.25 --dvr-shading --light-dir 1 0 0 1 1 1 \
  -o "$dir/d.pfm" --json "$dir/d.json" >/dev/null || fail=1
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["mode"] == "dvr" and j["densityLookups"] > 0, j' "$dir/d.json"
"$amrvk" render "$sample" "${common[@]}" --sampler dense --traversal grid-bvh --backend sw -o "$dir/n.pfm" \
  --json "$dir/n.json" >/dev/null || fail=1
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["sampler"] == "dense" and j["majorantViolations"] == 0 and j["hostMemoryPerStructure"]["denseGrid"] > 0 and "denseGrid" in j["deviceMemoryPerResource"] and "bricks" not in j["deviceMemoryPerResource"], j' "$dir/n.json"
"$amrvk" render "$sample" "${common[@]}" --traversal auto --sampler abr --backend sw -o "$dir/auto.png" \
  --json "$dir/auto.json" >/dev/null 2>"$dir/auto.err" || fail=1
check grep -q "traversal auto picked .*/abr/sw" "$dir/auto.err"
check python3 - "$dir/auto.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
assert j["sampler"] == "abr" and j["backend"] == "sw" and j["traversal"] in ("grid-dda","grid-bvh","abr","brick","ext-brick","kdtree"), j
# The probes behind the pick: a measured one within 10% of the most efficient (ties go to the
# combination that builds less), with the sampler fixed.
a = j["auto"]
assert a["pick"] == j["traversal"] + "/abr/sw" and a["probes"] == len(a["probeDetails"]) > 0, a
measured = [p for p in a["probeDetails"] if not p["predicted"] and p["efficiency"] > 0]
assert all(p["config"].endswith("/abr/sw") for p in a["probeDetails"]), a
best = max(p["efficiency"] for p in measured)
assert any(p["config"] == a["pick"] and p["grid"] == a["pickGrid"] and p["efficiency"] >= 0.9 * best for p in measured), a
# The contenders (within 0.75 of the best, at most 3, never one alone) were measured twice.
twice = [p for p in a["probeDetails"] if p["note"] == "measured twice: the mean of both"]
assert len(twice) != 1 and len(twice) <= 3 and not any(p["predicted"] for p in twice), twice
PY
# Its macrocell resolutions are 1/4, 1/2 and 2 times auto's (a grid sampler always probes them),
# not 32, 64 and 256 whatever the data: the sample's 32,768 cells get a coarse auto grid; where the
# finest wins, twice it and so on, up to 256 (the rule itself: gpu/auto_select_test).
"$amrvk" render "$sample" --size 16x12 --spp 2 --mode ms -o "$dir/grid-auto.png" --json "$dir/grid-auto.json" >/dev/null || fail=1
# With the back-end left to it, a CPU device (lavapipe) probes sw only, as --backend auto takes.
"$amrvk" render "$sample" --size 16x12 --spp 2 --mode ms --traversal auto --sampler grid \
  -o "$dir/auto-grid.png" --json "$dir/auto-grid.json" >/dev/null 2>&1 || fail=1
check python3 - "$dir/grid-auto.json" "$dir/auto-grid.json" <<'PY'
import json, sys
longest = max(json.load(open(sys.argv[1]))["macrocellDims"])
assert 4 <= longest < 64, longest
grids = {p["grid"] for p in json.load(open(sys.argv[2]))["auto"]["probeDetails"]}
expected = {str(n) for n in (int(longest / 4 + 0.5), int(longest / 2 + 0.5), 2 * longest) if n >= 4 and n != longest}
finer, g = set(), 2 * longest
while 2 * min(2 * g, 256) >= 3 * g:
    g = min(2 * g, 256)
    finer.add(str(g))
assert len(expected) == 3 and {"auto"} | expected <= grids <= {"auto"} | expected | finer, (longest, grids)
auto = json.load(open(sys.argv[2]))
twice = [p for p in auto["auto"]["probeDetails"] if p["note"] == "measured twice: the mean of both"]
assert len(twice) != 1 and len(twice) <= 3 and not any(p["predicted"] for p in twice), twice
if "llvmpipe" in auto["device"]:
    assert all(p["config"].endswith("/sw") for p in auto["auto"]["probeDetails"]), auto["auto"]["probeDetails"]
PY

expect "--mode: 'xyz' is not one of ae|ss|ms|dvr" -- render "$sample" "${common[@]}" --mode xyz -o "$dir/x.png"
expect "unknown image type" -- render "$sample" "${common[@]}" -o "$dir/x.bmp"
expect "--size '0x3'" -- render "$sample" --size 0x3 -o "$dir/x.png"
expect "--sampler: 'bvh' is not one of ext-brick|abr|grid|dense" -- render "$sample" "${common[@]}" --sampler bvh -o "$dir/x.png"
expect "--traversal: 'octree' is not one of" -- render "$sample" "${common[@]}" --traversal octree -o "$dir/x.png"
expect "--backend: 'cuda' is not one of sw|rq|auto" -- render "$sample" "${common[@]}" --backend cuda -o "$dir/x.png"
expect "--kd-leaves: 0 is outside [1, 16777215]" -- render "$sample" "${common[@]}" --traversal kdtree --kd-leaves 0 -o "$dir/x.png"
expect "no such device" -- render "$sample" "${common[@]}" --device 99 -o "$dir/x.png"
expect "--dt: 0 is outside (0, 64]" -- render "$sample" "${common[@]}" --mode dvr --dt 0 -o "$dir/x.png"
expect "--sampler dense needs --traversal grid-dda or grid-bvh" -- render "$sample" "${common[@]}" --sampler dense --traversal abr -o "$dir/x.png"
expect "--dense-max-mib" -- render "$sample" "${common[@]}" --sampler dense --dense-max-mib 0 -o "$dir/x.png"
expect "cannot write" -- render "$sample" "${common[@]}" -o "$dir/missing-dir/x.png"
expect "--ambient: 'nan' is not a finite number" -- render "$sample" "${common[@]}" --ambient nan 1 1 -o "$dir/x.png"
expect "--fov: 0 is outside (0, 180)" -- render "$sample" "${common[@]}" --fov 0 -o "$dir/x.png"
expect "--light-dir: radiance" -- render "$sample" "${common[@]}" --light-dir 1 0 0 -1 1 1 -o "$dir/x.png"
expect "unknown option '--bogus'" -- render "$sample" "${common[@]}" --bogus -o "$dir/x.png"
expect "--json $dir: is a directory" -- render "$sample" "${common[@]}" --json "$dir" -o "$dir/x.png"
check test ! -e "$dir/x.png"
check test ! -e "$dir/x.bmp"

# Hostile-input regressions (robustness issue), each named after its defect.
# SparseDataGetsATraversalThatFitsIt: 20,000 finest cells scattered over a 2^30-wide box ran over
# 300 s with the default grid-dda (macrocells 2^23 cells wide); the default now fits the data.
python3 - "$dir/scatter" <<'PY'
import random, struct, sys
random.seed(1)
cells = sorted({tuple(random.randrange(1 << 30) for _ in range(3)) for _ in range(20000)})
open(sys.argv[1] + '.cells', 'wb').write(b''.join(struct.pack('<4i', *c, 0) for c in cells))
open(sys.argv[1] + '.scalars', 'wb').write(struct.pack('<%df' % len(cells), *[random.random() for _ in cells]))
PY
timeout 120 "$amrvk" render "$dir/scatter.cells" --size 4x4 --spp 1 --mode ae -o "$dir/scatter.png" \
  --json "$dir/scatter.json" >/dev/null 2>"$dir/scatter.err" || fail=1
check grep -q "traversal abr and sampler abr: the cells fill .* of their bounding box" "$dir/scatter.err"
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["traversal"] == "abr" and j["sampler"] == "abr", j' "$dir/scatter.json"
# TrackingThatStallsInFloatIsCountedAndQuick: --density-scale 1e30 gives free paths below float
# resolution; t stalled and each call burned the 2^22-step cap in place (20 s for 8x8 pixels),
# uncounted before the cap was fixed. Now the call ends at once, counted and warned about.
timeout 120 "$amrvk" render "$sample" --size 8x8 --spp 1 --mode ae --tf-range 0 1 --density-scale 1e30 \
  -o "$dir/dense.png" --json "$dir/dense.json" >/dev/null 2>"$dir/dense.err" || fail=1
check grep -q "tracking calls stopped at the step cap or below float resolution" "$dir/dense.err"
check python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["trackingCapHits"] > 0 and j["majorantViolations"] == 0, j' "$dir/dense.json"
# ShaderDirNameIsNeverRunAsACommand: --shader-dir was pasted into a std::system command line; a
# directory named like a command substitution ran it. Shaders now compile in process.
evil="$dir/x'\$(touch $dir/PWNED)'x"
mkdir -p "$evil"
"$amrvk" shaders --export "$evil/src" >/dev/null || fail=1
"$amrvk" render "$sample" "${common[@]}" --mode ae --shader-dir "$evil/src/passes" -o "$dir/evil.pfm" >/dev/null || fail=1
check test -s "$dir/evil.pfm"
check test ! -e "$dir/PWNED"
# AMacrocellGridTooLargeForMemoryIsRefusedByName (--grid 4096 allowed 512 GiB of value ranges).
# The brick lists (grid sampler, and the ranges while they are made) are checked before any of
# their memory is allocated: 512^3 macrocells' counts and offsets alone need 1.6 GB.
AMRVK_MEMORY_BUDGET=100000000 expect "--grid 512x512x512: brick lists: needs 1610612748 bytes" \
  -- render "$sample" --size 8x8 --spp 1 --grid 512x512x512 -o "$dir/x.png"
check test ! -e "$dir/x.png"
# --scale log: the TF's range and info's value range are log10 of the field's (numpy computes them
# here independently); a render, the session field and the render line carry it; bad values are
# one line.
"$amrvk" info "$sample" --scale log --json >"$dir/log.json" || fail=1
check /usr/bin/python3 - "$dir/log.json" "${sample%.cells}.scalars" <<'PY'
import json, sys
import numpy as np
v = np.fromfile(sys.argv[2], dtype="<f4").astype(np.float64)
lo, hi = np.log10(v[v > 0].min()), np.log10(v.max())
got = json.load(open(sys.argv[1]))["valueRange"]
assert abs(got[0] - lo) < 1e-5 and abs(got[1] - hi) < 1e-5, (got, lo, hi)
PY
"$amrvk" render "$sample" --size 16x12 --spp 2 --scale log -o "$dir/log.png" --json "$dir/logr.json" >/dev/null || fail=1
check test -s "$dir/log.png"
expect "--scale: ln not in {auto,linear,log}" -- render "$sample" --scale ln -o "$dir/x.png"
expect "--log-floor: -1 is outside" -- render "$sample" --scale log --log-floor -1 -o "$dir/x.png"
# A long structure build states the memory it is about to take and shows progress (issue 34,
# point 8): a 170^3 raw volume's dense grid (4.9M samples, 19 MiB) with progress forced on.
/usr/bin/python3 -c 'import numpy as np, sys; (np.arange(170**3) % 251).astype(np.uint8).tofile(sys.argv[1])' \
  "$dir/v_170x170x170_uint8.raw"
AMRVK_PROGRESS=1 "$amrvk" render "$dir/v_170x170x170_uint8.raw" --sampler dense --size 8x8 --spp 1 \
  -o "$dir/dense.png" 2>"$dir/dense.err" >/dev/null || fail=1
check grep -q "dense grid of 170^3 samples: 18.7 MiB of memory" "$dir/dense.err"
check grep -q "dense grid \[#* *\] 170/170 slices" "$dir/dense.err"
# --until-error E: the render stops at the first check (16 spp, then each doubling) whose noise is
# at most E, and --spp caps it; the noise printed and in --json is the image's, recomputed here
# from --variance and the PFM independently.
"$amrvk" render "$sample" --size 24x24 --grid 16 --scale linear --tf ramp --background 1 1 1 --tf-range 0.3 2 --spp 4096 --until-error 0.03 \
  -o "$dir/until.pfm" --variance "$dir/until_var.pfm" --json "$dir/until.json" >"$dir/until.out" || fail=1
check grep -q "at or below --until-error" "$dir/until.out"
check /usr/bin/python3 - "$dir/until.json" "$dir/until.pfm" "$dir/until_var.pfm" <<'PY'
import json, sys
import numpy as np
def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split()); scale = float(f.readline())
        return np.fromfile(f, dtype="<f4" if scale < 0 else ">f4").reshape(h, w, 3)
j = json.load(open(sys.argv[1]))
spp, err = j["spp"], j["meanRelativeError"]
assert 16 < spp < 4096 and (spp & (spp - 1)) == 0, spp  # 32, 64, ...: doubled, then stopped early
assert err <= 0.03, err
m, v = pfm(sys.argv[2]).mean(axis=2), pfm(sys.argv[3]).mean(axis=2)
n = m.size
vis = (m > 0) & (m >= np.sort(m.ravel())[min(n - 1, int(0.99 * n))] / 256)
mine = float(np.mean(np.sqrt(v[vis]) / m[vis]))
assert abs(mine - err) < 1e-3 * max(err, 1e-3) + 1e-4, (mine, err)
PY
"$amrvk" render "$sample" --size 16x12 --grid 16 --spp 8 --until-error 1e-6 -o "$dir/capped.png" \
  --json "$dir/capped.json" >"$dir/capped.out" || fail=1
check grep -q "above --until-error; --spp capped it" "$dir/capped.out"
check /usr/bin/python3 -c 'import json, sys; assert json.load(open(sys.argv[1]))["spp"] == 8' "$dir/capped.json"
# Every render of 2 spp or more states its noise (the --json's, rounded), and says when it shows
# as grain, with what to do; a ray-marched picture is not called grainy.
"$amrvk" render "$sample" --size 16x12 --grid 16 --spp 4 -o "$dir/noisy.png" --json "$dir/noisy.json" >"$dir/noisy.out" || fail=1
check /usr/bin/python3 - "$dir/noisy.out" "$dir/noisy.json" <<'PY'
import json, re, sys
line = open(sys.argv[1]).read()
e = json.load(open(sys.argv[2]))["meanRelativeError"]
m = re.search(r", noise ([0-9.e+-]+)(: grainy; more --spp, --until-error E, or --first-frame \(ray-marched\) for less)?$", line.strip())
assert m and abs(float(m.group(1)) - e) <= 0.01 * e, (line, e)
assert (m.group(2) is not None) == (e > 0.1), (line, e)
assert e > 0.1, "4 spp of the sample: grainy"
PY
"$amrvk" render "$sample" --size 16x12 --grid 16 --spp 4 --mode dvr -o "$dir/dvr.png" >"$dir/dvr.out" || fail=1
check grep -q ", noise [0-9.e+-]*$" "$dir/dvr.out"
"$amrvk" render "$sample" --size 16x12 --grid 16 --spp 1 -o "$dir/one.png" >"$dir/one.out" || fail=1
check bash -c '! grep -q "noise" "$1"' _ "$dir/one.out"
# --first-frame: what Python and the viewer show first, as a file; the step it reports renders
# the same picture as --mode dvr --spp 2 --dt that step (the same samples), and it is finer than
# the default 0.5 where the 0.5 frame is noisier than 0.05.
"$amrvk" render "$sample" --size 32x24 --grid 16 --first-frame -o "$dir/ff.pfm" --json "$dir/ff.json" >"$dir/ff.out" || fail=1
dt=$(sed -n 's/^first frame: dvr at dt \([0-9.e+-]*\) after .*/\1/p' "$dir/ff.out")
check test -n "$dt"
"$amrvk" render "$sample" --size 32x24 --grid 16 --mode dvr --spp 2 --dt "${dt:-0.5}" -o "$dir/ffdvr.pfm" --json "$dir/ffdvr.json" >/dev/null || fail=1
"$amrvk" render "$sample" --size 32x24 --grid 16 --mode dvr --spp 2 -o "$dir/ff05.pfm" --json "$dir/ff05.json" >/dev/null || fail=1
check /usr/bin/python3 - "$dir" "${dt:-0}" <<'PY'
import json, sys
import numpy as np
d, dt = sys.argv[1], float(sys.argv[2])
def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split()); scale = float(f.readline())
        return np.fromfile(f, dtype="<f4" if scale < 0 else ">f4").reshape(h, w, 3)
ff, same = pfm(f"{d}/ff.pfm"), pfm(f"{d}/ffdvr.pfm")
j, j05 = json.load(open(f"{d}/ff.json")), json.load(open(f"{d}/ff05.json"))
assert j["mode"] == "dvr" and j["spp"] == 2, j["mode"]
assert j["firstFrame"]["dt"] == dt and j["firstFrame"]["frames"] >= 1, (j["firstFrame"], dt)
assert j["firstFrame"]["gpuSeconds"] >= j["seconds"] - 1e-9, j["firstFrame"]
assert np.max(np.abs(ff - same)) <= 1e-6 * max(1.0, float(np.abs(same).max())), "the reported step renders it"
n05 = j05["meanRelativeError"]
assert (dt < 0.5) == (n05 > 0.05), (dt, n05)  # refined exactly where dt 0.5 is noisy (cheap here)
assert dt == 0.5 or j["meanRelativeError"] < n05, (j["meanRelativeError"], n05)
PY
# The default picture: one picture with nothing said about how it is made is that first frame;
# any of --mode, --spp, --dt or --until-error path-traces it as before (ms, 64 spp by default).
"$amrvk" render "$sample" --size 32x24 --grid 16 -o "$dir/def.pfm" --json "$dir/def.json" >"$dir/def.out" || fail=1
check grep -q "^the default picture is this first frame; path-trace it with --mode ms" "$dir/def.out"
# Above the target only where its budget or finest step stopped it, and then it says so.
check /usr/bin/python3 - "$dir/def.out" "$dir/def.json" <<'PY'
import json, sys
out, noise = open(sys.argv[1]).read(), json.load(open(sys.argv[2]))["meanRelativeError"]
assert ("first frame: stopped at noise" in out) == (noise > 0.05), (noise, out)
PY
"$amrvk" render "$sample" --size 16x12 --grid 16 --mode ae -o "$dir/ae.png" --json "$dir/ae.json" >"$dir/ae.out" || fail=1
"$amrvk" render "$sample" --size 16x12 --grid 16 --spp 3 -o "$dir/s3.png" --json "$dir/s3.json" >/dev/null || fail=1
check bash -c '! grep -q "default picture" "$1"' _ "$dir/ae.out"
check /usr/bin/python3 - "$dir" <<'PY'
import json, sys
import numpy as np
d = sys.argv[1]
def pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split()); scale = float(f.readline())
        return np.fromfile(f, dtype="<f4" if scale < 0 else ">f4").reshape(h, w, 3)
j, ff = json.load(open(f"{d}/def.json")), json.load(open(f"{d}/ff.json"))
assert (j["mode"], j["spp"]) == ("dvr", 2), (j["mode"], j["spp"])
assert abs(j["meanRelativeError"] - ff["meanRelativeError"]) <= 1e-6, "the default is --first-frame's picture"
assert j["firstFrame"]["byDefault"] is True and ff["firstFrame"]["byDefault"] is False
assert j["firstFrame"]["dt"] == ff["firstFrame"]["dt"] and j["firstFrame"]["noiseTarget"] == 0.05, j["firstFrame"]
a, b = pfm(f"{d}/def.pfm"), pfm(f"{d}/ff.pfm")
assert np.max(np.abs(a - b)) <= 1e-6 * max(1.0, float(np.abs(b).max()))
ae, s3 = json.load(open(f"{d}/ae.json")), json.load(open(f"{d}/s3.json"))
assert (ae["mode"], ae["spp"]) == ("ae", 64), (ae["mode"], ae["spp"])
assert "firstFrame" not in ae and "firstFrame" not in s3
assert (s3["mode"], s3["spp"]) == ("ms", 3), (s3["mode"], s3["spp"])
PY
expect "--first-frame chooses the mode (dvr), the samples (2) and the step; leave out --spp" -- render "$sample" --first-frame --spp 8 -o "$dir/x.png"
expect "--first-frame chooses the mode (dvr), the samples (2) and the step; leave out --mode" -- render "$sample" --first-frame --mode ms -o "$dir/x.png"
expect "--until-error: 0 is outside (0, 1]" -- render "$sample" --until-error 0 -o "$dir/x.png"
expect "--until-error needs --spp of at least 2" -- render "$sample" --spp 1 --until-error 0.1 -o "$dir/x.png"
# The other long builds alike (issue 34, point 8): bricks (an upper bound first, a bar over the
# cells, the bricks and memory after), macrocell value ranges (their memory, a bar over the
# macrocells), the kd-tree traversal's support ranges, and the upload (the device memory taken).
"$amrvk" gen cloud --cells 200000 --seed 1 -o "$dir/progress-cloud" >/dev/null 2>&1 || fail=1
AMRVK_PROGRESS=1 "$amrvk" render "$dir/progress-cloud.cells" --traversal grid-bvh --sampler grid --grid 32 \
  --size 8x8 --spp 1 -o "$dir/progress.png" 2>"$dir/progress.err" >/dev/null || fail=1
cells=$(grep -o 'bricks of [0-9]* cells (at most [0-9.]* [KMG]iB of memory) \.\.\.' "$dir/progress.err" | grep -o 'of [0-9]* cells' | tr -dc 0-9)
check test -n "$cells"
check grep -q "bricks \[#* *\] $cells/$cells cells" "$dir/progress.err"
check grep -Eq "bricks of $cells cells done in [0-9.]+ s \([0-9]+ bricks, [0-9.]+ [KMG]?i?B\)" "$dir/progress.err"
check grep -q "macrocell value ranges of 32x32x32 (256.0 KiB of memory) \.\.\." "$dir/progress.err"
check grep -q "macrocell value ranges \[#* *\] 32768/32768 macrocells" "$dir/progress.err"
check grep -Eq "uploading the structures to the device done in [0-9.]+ s \([0-9.]+ [KMG]iB of device memory\)" "$dir/progress.err"
AMRVK_PROGRESS=1 "$amrvk" render "$dir/progress-cloud.cells" --traversal kdtree --size 8x8 --spp 1 \
  -o "$dir/progress.png" 2>"$dir/progress-kd.err" >/dev/null || fail=1
check grep -Eq "support ranges of the bricks done in [0-9.]+ s \([0-9.]+ [KMG]iB\)" "$dir/progress-kd.err"
exit $fail
