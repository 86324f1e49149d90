#!/usr/bin/env bash
# Usage: hostile_versions.sh AMRVK SCRATCH. Hostile input, round 3 (issue 34, docs/fuzzing.md):
# sessions and viewer scripts from other amrvk versions. Older files (the session as the first
# session module wrote it, before cut-aways, legends and log scales; a script with only the first
# actions) are read as they were meant; a newer file (another version number, a key or an action
# this amrvk does not know, a value of a newer enum) is refused with one line naming the file and
# the key or line, never misread with a setting silently dropped. Parse errors come before any
# device work, so the whole script takes seconds.
set -u
amrvk="$1"; dir="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir"
fail=0
source "$here/lib.sh"  # expect1, ok: one case each
python3 - <<'PY'
import struct
cells = [(0,0,0,1),(2,0,0,0),(3,0,0,0),(2,1,0,0),(3,1,0,0)]
open('good.cells','wb').write(b''.join(struct.pack('<4i', *c) for c in cells))
open('good.scalars','wb').write(struct.pack('<5f', 1, 2, 3, 4, 5))
PY
pic=(--size 8x8 --spp 1 --grid 4 --mode ae)

# ---- sessions written by earlier amrvk versions ----
# sess NAME PYTHON: the session as the first session module (287e648) wrote it, edited by PYTHON on
# the dict `s`, written to NAME.
sess() {
  python3 - "$1" "$2" "$dir/good.cells" <<'PY'
import json, sys
s = {"amrvk": "session", "version": 1, "input": sys.argv[3],
     "read": {"format": "auto", "nan": "reject"}, "field": "scalars",
     "camera": {"eye": [9.5, -7.5, 8.5], "target": [2, 1, 0.5], "up": [0, 0, 1], "fovY": 40},
     "image": {"width": 8, "height": 8},
     "render": {"mode": "ae", "spp": 1, "seed": 1, "densityScale": 1, "g": 0, "ambient": [1, 1, 1],
                "dvrStep": 0.5, "dvrShading": False},
     "lights": [{"type": "directional", "direction": [1, -1, 2], "radiance": [5, 4.5, 3.8]}],
     "structure": {"traversal": "grid-dda", "sampler": "ext-brick", "backend": "auto", "grid": "4",
                   "kdLeaves": 4096, "denseMaxMiB": 2048},
     "transferFunction": {"Name": "ramp", "ColorSpace": "RGB", "RGBPoints": [1, 0.267, 0.004, 0.329, 5, 0.992, 0.906, 0.145],
                          "Points": [1, 0, 0.5, 0, 5, 1, 0.5, 0]}}
exec(sys.argv[2])
open(sys.argv[1], "w").write(json.dumps(s))
PY
}
# The oldest layout renders, and the viewer saves it again as today's (the same picture: nothing
# read from the old file was dropped or changed on the way).
sess old.json 'pass'
ok render --session old.json -o old.png --json old.stats.json
ok view --session old.json --headless --frames 1 --save-session resaved.json
cases=$((cases + 1))
check python3 - old.json resaved.json <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for k in ("camera", "image", "lights", "field"):
    assert a[k] == b[k], (k, a[k], b[k])
# Keys added since are written with today's default: structure.subMajorants "8" (the same picture
# as without them: delta tracking decides every collision as before).
assert {k: b["structure"][k] for k in a["structure"]} == a["structure"], (a["structure"], b["structure"])
assert b["structure"]["subMajorants"] == "8", b["structure"]
assert {k: b["read"][k] for k in a["read"]} == a["read"], (a["read"], b["read"])
assert {k: b["render"][k] for k in a["render"]} == a["render"], (a["render"], b["render"])
# What a missing key meant in version 1 is stated when written again (version 3 defaults differ).
assert b["read"]["scale"] == "linear" and b["render"]["background"] == "ambient", (b["read"], b["render"])
assert "cut" not in b and "legend" not in b, b
PY
# Earlier versions wrote fewer keys (each later key optional, with the old behaviour as default).
sess old-noread.json 'del s["read"]'
ok render --session old-noread.json -o x.png
sess old-nostructure.json 'del s["structure"]; del s["lights"]'
ok render --session old-nostructure.json -o x.png
sess old-norender.json 'del s["render"]; s["image"] = {"width": 8, "height": 8}'
ok render --session old-norender.json --spp 1 -o x.png
sess old-nofield.json 'del s["field"]'
ok render --session old-nofield.json -o x.png

# ---- sessions from other or newer versions: refused with one line, never misread ----
for v in 0 4 -1 1.5 '"1"' 1e300 9223372036854775808 null true '[1]'; do
  sess "v.json" "s['version'] = json.loads('$v')"
  shown=$v; case $v in 1e300) shown=1e+300;; 9223372036854775808) shown=9.223372036854776e+18;; '"1"') shown=string;;
    null|true|'[1]') shown=expected;; esac
  expect1 "v.json" -- render --session v.json -o x.png
  check grep -qF -- "$shown" expect.err  # part of the case: the version as written
done
sess nov.json 'del s["version"]'
expect1 'nov.json: missing "version"' -- render --session nov.json -o x.png
sess amrvk2.json 's["amrvk"] = "session2"'
expect1 "not an amrvk session" -- render --session amrvk2.json -o x.png
# A key a newer amrvk could add (or a typo) at every level is named, not dropped.
newkey() {  # newkey NAME PYTHON KEYPATH
  sess "$1" "$2"
  rm -f x.png
  expect1 "$1.$3: unknown key (this amrvk reads session version 3" -- render --session "$1" -o x.png
  check test ! -e x.png  # part of the case: no picture without the setting
}
newkey k-top.json 's["denoiser"] = {"on": True}' denoiser
newkey k-read.json 's["read"]["units"] = "cgs"' read.units
newkey k-camera.json 's["camera"]["aperture"] = 0.1' camera.aperture
newkey k-image.json 's["image"]["pixelAspect"] = 2' image.pixelAspect
newkey k-render.json 's["render"]["maxBounces"] = 4' render.maxBounces
newkey k-render-typo.json 's["render"]["densityscale"] = 9' render.densityscale
newkey k-light.json 's["lights"][0]["angle"] = 0.5' 'lights[0].angle'
newkey k-light-point.json 's["lights"] = [{"type": "point", "position": [1,1,1], "intensity": [1,1,1], "radius": 2}]' 'lights[0].radius'
newkey k-cut.json 's["cut"] = {"sphere": {"centre": [1,1,1], "radius": 1}}' cut.sphere
newkey k-crop.json 's["cut"] = {"crop": {"lo": [0,0,0], "hi": [2,2,2], "invert": True}}' cut.crop.invert
newkey k-clip.json 's["cut"] = {"clip": [{"point": [1,1,1], "normal": [1,0,0], "soft": 1}]}' 'cut.clip[0].soft'
newkey k-structure.json 's["structure"]["bvhLeafSize"] = 4' structure.bvhLeafSize
newkey k-legend.json 's["legend"] = {"show": True, "ticks": 7}' legend.ticks
# Values of an enum a newer amrvk could extend.
sess e-mode.json 's["render"]["mode"] = "spectral"'
expect1 "e-mode.json.render.mode" -- render --session e-mode.json -o x.png
sess e-traversal.json 's["structure"]["traversal"] = "octree"'
expect1 "e-traversal.json.structure.traversal" -- render --session e-traversal.json -o x.png
sess e-sampler.json 's["structure"]["sampler"] = "vdb"'
expect1 "e-sampler.json.structure.sampler" -- render --session e-sampler.json -o x.png
sess e-backend.json 's["structure"]["backend"] = "cuda"'
expect1 "e-backend.json.structure.backend" -- render --session e-backend.json -o x.png
sess e-light.json 's["lights"][0]["type"] = "area"'
expect1 "e-light.json.lights[0].type: 'area'" -- render --session e-light.json -o x.png
sess e-nan.json 's["read"]["nan"] = "interpolate"'
expect1 "e-nan.json.read.nan" -- render --session e-nan.json -o x.png
sess e-scale.json 's["read"]["scale"] = "asinh"'
expect1 "e-scale.json.read.scale" -- render --session e-scale.json -o x.png
sess e-place.json 's["legend"] = {"show": True, "place": "top"}'
expect1 "e-place.json.legend.place" -- render --session e-place.json -o x.png
sess e-format.json 's["read"]["format"] = "flash"'
expect1 "flash" -- render --session e-format.json -o x.png
# The viewer loads sessions the same way (load-session in a script, --session).
newkey_view() {
  sess "$1" "$2"
  expect1 "$1.$3: unknown key" -- view --session "$1" --headless --frames 1
}
newkey_view kv-render.json 's["render"]["exposure"] = 2' render.exposure
printf '0 load-session kv-render.json\n1 quit\n' > load.txt
expect1 "kv-render.json.render.exposure: unknown key" -- view good.cells "${pic[@]}" --headless --script load.txt

# ---- viewer scripts ----
# Every action of the first script format (287e648) still means what it meant.
cat > old.txt <<'S'
# the first script actions
0 orbit 10 0
1 pan 2 2
2 zoom 1
3 tf-preset ramp
4 tf-range 1 5
5 density 2
6 mode ss
7 traversal abr
8 sampler ext-brick
9 backend sw
10 grid 4
11 reload
12 screenshot old-shot.png
13 quit
S
ok view good.cells "${pic[@]}" --headless --script old.txt
cases=$((cases + 1)); check test -s old-shot.png
# Actions and arguments of a newer script are refused on their line before the first frame, with
# nothing written.
script() {  # script LINE FRAGMENT
  printf '0 orbit 1 1\n%s\n5 screenshot never.png\n' "$1" > new.txt
  expect1 "new.txt:2: $2" -- view good.cells "${pic[@]}" --headless --script new.txt
  cases=$((cases + 1)); check test ! -e never.png
}
script "1 denoise on" "unknown action 'denoise'"
script "1 exposure 2" "unknown action 'exposure'"
script "1 orbit 1 2 3" "orbit"
script "1 zoom 1 smooth" "zoom"
script "1 mode spectral" "mode: --mode 'spectral'"
script "1 traversal octree" "traversal: --traversal 'octree'"
script "1 screenshot shot.webp" "screenshot: 'shot.webp': unknown image type"
script "1 legend maybe" "legend"
script "1 scale asinh" "scale: --scale: 'asinh'"
script "1 tf-preset future-preset" "tf-preset: unknown transfer function preset 'future-preset'"
script "9223372036854775808 quit" "frame '9223372036854775808' is not a whole number"
script "-1 quit" "frame '-1' is not a whole number"
script "1.5 quit" "frame '1.5' is not a whole number"
script "0x10 quit" "frame '0x10' is not a whole number"
echo "hostile_versions.sh: $cases cases"
exit $fail
