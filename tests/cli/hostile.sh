#!/usr/bin/env bash
# Usage: hostile.sh AMRVK SOURCE_DIR SCRATCH. The second hostile-input campaign (issue 23;
# docs/fuzzing.md "Hostile input, round 2"): files written outside the place the user named,
# outputs that would destroy other files, crashes and hangs from sessions, scripts, shaders and
# big TFs, documented promises; and round 3 (issue 34, section 9). Every case must end in one
# clean error line (exit 1) or in bounded, correct work, and leave nothing behind it should not.
# Tiny inputs: the whole script runs in about two minutes on lavapipe.
set -u
ulimit -c 0  # SIGQUIT below dumps no core
amrvk="$1"; src="$2"; dir="$3"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir"
fail=0
source "$here/lib.sh"  # expect1, check1, ok: one case each
same() { cmp -s "$1" "$2" || { echo "FAIL: $1 changed"; fail=1; }; }  # part of the case before it
no_temporaries() { check1 test -z "$(find . -name '*.tmp-*' | head -1)"; }
section_name=""; section_start=0
section() {  # prints the case count of the section that ends here
  [ -n "$section_name" ] && echo "hostile.sh: $((cases - section_start)) cases: $section_name"
  section_name="$1"; section_start=$cases
}

python3 - <<'PY'
import struct, json
cells = [(0,0,0,1),(2,0,0,0),(3,0,0,0),(2,1,0,0),(3,1,0,0)]
open('good.cells','wb').write(b''.join(struct.pack('<4i', *c) for c in cells))
open('good.scalars','wb').write(struct.pack('<5f', 1, 2, 3, 4, 5))
open('good.rho.scalars','wb').write(struct.pack('<5f', 5, 4, 3, 2, 1))
open('tf.json','w').write(json.dumps([{"Name":"t","RGBPoints":[1,1,1,1,5,1,0,0],"Points":[1,0,0.5,0,5,1,0.5,0]}]))
d = 100000
open('deep.json','w').write('[' * d + ']' * d)
PY
cp good.cells victim.bin
pic=(--size 8x8 --spp 1 --grid 4 --mode ae)
ok view good.cells "${pic[@]}" --headless --frames 1 --save-session s.json
cp s.json s.orig

# ---- 1. Outputs never destroy (special files, links, inputs, each other) ---------------------
section "outputs"
ok render good.cells "${pic[@]}" -o a.png --json /dev/null
check1 test -c /dev/null
ok view good.cells "${pic[@]}" --headless --frames 1 --save-session /dev/null --stats /dev/null
check1 test -c /dev/null
"$amrvk" render good.cells "${pic[@]}" -o a.png --json /dev/stdout >stdout.json 2>/dev/null
check1 python3 -c "import json; json.load(open('stdout.json'))"
check1 test -L /dev/stdout
mkfifo pipe.json
(cat pipe.json > from-pipe.json &) ; ok render good.cells "${pic[@]}" -o a.png --json pipe.json
sleep 0.3; check1 test -p pipe.json
check1 python3 -c "import json; json.load(open('from-pipe.json'))"
echo keep > target.json; ln -s target.json link.json
ok render good.cells "${pic[@]}" -o a.png --json link.json
check1 test -L link.json
check1 python3 -c "import json; json.load(open('target.json'))"
ln -s nowhere/x.json dangling.json
expect1 "dangling.json: a symbolic link to nothing" -- render good.cells "${pic[@]}" -o a.png --json dangling.json
check1 test -L dangling.json
ln -s missing-target.png dangling.png
expect1 "a symbolic link to nothing" -- render good.cells "${pic[@]}" -o dangling.png
mkdir adir.png
expect1 "-o adir.png: is a directory" -- render good.cells "${pic[@]}" -o adir.png
expect1 "--json adir.png: is a directory" -- render good.cells "${pic[@]}" -o b.png --json adir.png
expect1 "directory nodir is missing" -- render good.cells "${pic[@]}" -o nodir/a.png
expect1 "directory nodir is missing" -- render good.cells "${pic[@]}" -o a.png --json nodir/a.json
check1 test ! -e a2.png
expect1 "--json s.json is the input --session s.json" -- render --session s.json --spp 1 -o a2.png --json s.json
same s.json s.orig
check1 test ! -e a2.png
expect1 "--json tf.json is the input --tf tf.json" -- render good.cells "${pic[@]}" --tf tf.json -o a2.png --json tf.json
expect1 "--json good.cells is the input good.cells" -- render good.cells "${pic[@]}" -o a2.png --json good.cells
same good.cells victim.bin
expect1 "good.scalars" -- render good.cells "${pic[@]}" -o a2.png --json good.scalars
expect1 "are the same file" -- render good.cells "${pic[@]}" -o a2.pfm --json a2.pfm
echo old > a3.pfm; ln -s a3.pfm alias.pfm
expect1 "are the same file" -- render good.cells "${pic[@]}" -o a3.pfm --json alias.pfm
# (--save-session back to the --session file is the viewer's ordinary Save: round 4, point 18.)
printf '0 quit\n' > quit.txt
expect1 "--stats quit.txt is the input --script quit.txt" -- view good.cells "${pic[@]}" --headless --script quit.txt --stats quit.txt
expect1 "are the same file" -- view good.cells "${pic[@]}" --headless --frames 1 --screenshot v.png --stats v.png
expect1 "--stats good.cells is the input good.cells" -- view good.cells "${pic[@]}" --headless --frames 1 --stats good.cells
expect1 "unknown image type" -- view good.cells "${pic[@]}" --headless --frames 1 --screenshot good.scalars
check1 test ! -e v.png
expect1 "-o good.cells is the input good.cells" -- convert good.cells -o good
same good.cells victim.bin
expect1 "is the input" -- convert good.cells -o ./good
# A temporary name is not predictable: a link planted at the old name is never followed.
echo precious > victim.txt
for p in $(seq 1 20); do ln -sf victim.txt "out.png.tmp-$p"; done
ok render good.cells "${pic[@]}" -o out.png
check1 test "$(cat victim.txt)" = precious
check1 test -s out.png
rm -f out.png.tmp-*
no_temporaries
# An existing output is replaced with its permissions kept.
cp out.png perm.png; chmod 0640 perm.png
ok render good.cells "${pic[@]}" -o perm.png
check1 test "$(stat -c %a perm.png)" = 640
# Bench's directory is never inside a data set.
mkdir -p plot.d; cp good.cells good.scalars plot.d/
expect1 "lies inside the input plot.d" -- bench plot.d -o plot.d/results --frames 2 --warmup 0
expect1 "exists and is not a directory" -- bench good.cells -o good.scalars --frames 2
# gen and convert check every output before any work.
mkdir taken.scalars
expect1 "taken.scalars: is a directory" -- gen cloud --cells 1000 --seed 1 -o taken
check1 test ! -e taken.cells
mkdir conv2.rho.scalars
expect1 "conv2.rho.scalars: is a directory" -- convert good.cells -o conv2
check1 test ! -e conv2.cells
no_temporaries

# ---- 2. Paths from scripts stay inside the place named ---------------------------------------
section "script paths"
"$amrvk" shaders --export shaders >/dev/null 2>&1
echo precious > victim.txt
sdir=shaders/passes
printf '0 edit-shader ../../victim.txt precious x\n1 quit\n' > esc1.txt
expect1 "esc1.txt:1: edit-shader: '../../victim.txt' leads outside the shader sources" -- view good.cells "${pic[@]}" --headless --shader-dir $sdir --script esc1.txt
printf '0 edit-shader %s precious x\n1 quit\n' "$dir/victim.txt" > esc2.txt
expect1 "esc2.txt:1: edit-shader" -- view good.cells "${pic[@]}" --headless --shader-dir $sdir --script esc2.txt
ln -s ../../victim.txt shaders/lib/evil.glsl
printf '0 edit-shader ../lib/evil.glsl precious x\n1 quit\n' > esc3.txt
expect1 "esc3.txt:1: edit-shader: '../lib/evil.glsl' leads outside" -- view good.cells "${pic[@]}" --headless --shader-dir $sdir --script esc3.txt
ln -s "$dir" shaders/lib/up
printf '0 edit-shader ../lib/up/victim.txt precious x\n1 quit\n' > esc4.txt
expect1 "leads outside" -- view good.cells "${pic[@]}" --headless --shader-dir $sdir --script esc4.txt
printf '0 edit-shader ../lib/missing.glsl a b\n' > esc5.txt
expect1 "esc5.txt:1: edit-shader" -- view good.cells "${pic[@]}" --headless --shader-dir $sdir --script esc5.txt
printf '0 edit-shader path_trace.comp a b\n' > esc6.txt
expect1 "esc6.txt:1: edit-shader: edit-shader needs --shader-dir" -- view good.cells "${pic[@]}" --headless --script esc6.txt
check1 test "$(cat victim.txt)" = precious
printf '0 edit-shader . a b\n' > esc7.txt
expect1 "not a regular file" -- view good.cells "${pic[@]}" --headless --shader-dir $sdir --script esc7.txt

# ---- 3. Scripts keep the docs' promises: every line checked before frame 0 --------------------
section "script values and promises"
script_case() {  # script_case FRAGMENT LINE...: a script of these lines fails with FRAGMENT
  local frag="$1"; shift
  printf '%s\n' "$@" > sc.txt
  expect1 "$frag" -- view good.cells "${pic[@]}" --headless --frames 2 --script sc.txt
}
script_case "sc.txt:1: unknown action 'fly'" "0 fly 1 2"
script_case "sc.txt:2: orbit takes 2 argument(s), not 1" "0 zoom 1" "1 orbit 5"
script_case "sc.txt:1: argument 1 of zoom is not a number" "0 zoom far"
script_case "sc.txt:1: argument 2 of pan is not a number" "0 pan 1 inf"
script_case "sc.txt:1: density: density -2 must be >= 0" "0 density -2"
script_case "sc.txt:1: mode: --mode 'pt'" "0 mode pt"
script_case "sc.txt:1: traversal: --traversal 'octree'" "0 traversal octree"
script_case "sc.txt:1: sampler: --sampler 'cube'" "0 sampler cube"
script_case "sc.txt:1: backend: --backend 'cuda'" "0 backend cuda"
script_case "sc.txt:1: grid: --grid: expected auto, N or NxMxK (got 'huge')" "0 grid huge"
script_case "sc.txt:1: grid: --grid: macrocells must be in [1, 4096] (got 5000)" "0 grid 5000"
script_case "sc.txt:1: grid: --grid: macrocells per axis must be in [1, 4096] (got 0x4x4)" "0 grid 0x4x4"
script_case "sc.txt:1: tf-preset" "0 tf-preset rainbow"
script_case "sc.txt:1: tf-range: LO 2 must be below HI 1" "0 tf-range 2 1"
script_case "sc.txt:1: tf-range: LO 1 must be below HI 1" "0 tf-range 1 1"
script_case "sc.txt:1: screenshot: 'x.jpg': unknown image type" "0 screenshot x.jpg"
script_case "sc.txt:1: capture-window: 'x.pfm': unknown image type" "0 capture-window x.pfm"
script_case "sc.txt:1: edit-shader: '/etc/passwd' must be a path relative" "0 edit-shader /etc/passwd a b"
script_case "sc.txt:1: edit-shader: the text to find is empty" '0 edit-shader lib/tf.glsl "" b'
script_case "sc.txt:2: frame 3 comes before frame 5" "5 zoom 1" "3 zoom 1"
script_case "sc.txt:1: frame '-1'" "-1 zoom 1"
script_case "sc.txt:1: frame '1.5'" "1.5 zoom 1"
script_case "sc.txt:1: frame '1e300'" "1e300 zoom 1"
script_case "sc.txt:1: unterminated quote" '0 screenshot "a.png'
script_case "sc.txt:1: expected FRAME ACTION" "7"
script_case "sc.txt:1: reload takes 0 argument(s), not 1" "0 reload now"
script_case "sc.txt:1: quit takes 0 argument(s), not 1" "0 quit now"
script_case "sc.txt:2: sampler: --sampler dense needs --traversal grid-dda or grid-bvh" "0 traversal abr" "1 sampler dense"
script_case "sc.txt:3: traversal: --sampler dense needs" "0 sampler dense" "1 grid 8" "2 traversal kdtree"
script_case "sc.txt:1: argument 1 of orbit is not a number" "0 orbit 0x10 0"
script_case "sc.txt:1: argument 1 of density is not a number" "0 density 1,5"
printf '0 zoom 1\n' > sc.txt; mkdir scdir
expect1 "scdir" -- view good.cells "${pic[@]}" --headless --frames 1 --script scdir
expect1 "no-such-script.txt" -- view good.cells "${pic[@]}" --headless --frames 1 --script no-such-script.txt
# Every documented action works at every documented frame, 0 included (reload at 0 failed).
printf '0 reload\n0 mode ss\n0 zoom 1\n1 reload\n2 quit\n' > zero.txt
ok view good.cells "${pic[@]}" --headless --shader-dir $sdir --script zero.txt
printf '0 reload\n1 quit\n' > zero2.txt
ok view good.cells "${pic[@]}" --headless --script zero2.txt
# Script outputs never destroy: a device is written through, a directory refused at its line.
printf '0 save-session /dev/null\n1 quit\n' > dn.txt
ok view good.cells "${pic[@]}" --headless --script dn.txt
check1 test -c /dev/null
printf '0 save-session adir.png\n1 quit\n' > sd.txt
expect1 "sd.txt:1: save-session: adir.png: is a directory" -- view good.cells "${pic[@]}" --headless --script sd.txt

# ---- 4. Sessions accept what the schema calls optional; hostile ones give one line ------------
section "sessions"
sess() {  # sess NAME PYTHON-EDIT: s.json edited by the Python expression on dict `s`
  python3 - "$1" "$2" <<'PY'
import json, sys
s = json.load(open('s.orig'))
exec(sys.argv[2])
open(sys.argv[1], 'w').write(json.dumps(s) if not isinstance(s, str) else s)
PY
}
sess norender.json 'del s["render"]'
ok render --session norender.json -o nr.png
sess nolights.json 'del s["lights"]; del s["structure"]; del s["read"]; del s["field"]'
ok render --session nolights.json -o nl.png
sess deep.json 's["transferFunction"]["X"] = 0; s = json.dumps(s).replace("\"X\": 0", "\"X\": " + "[" * 100000 + "]" * 100000)'
expect1 "deep.json: JSON nested deeper than 64 levels" -- render --session deep.json -o d.png
expect1 "deep.json: JSON nested deeper than 64 levels" -- view --session deep.json --headless --frames 1
expect1 "deep.json: JSON nested deeper than 64 levels" -- render good.cells "${pic[@]}" --tf deep.json -o d.png
sess v4.json 's["version"] = 4'
expect1 "v4.json: session version 4" -- render --session v4.json -o x.png
sess notsession.json 's["amrvk"] = "image"'
expect1 "not an amrvk session" -- render --session notsession.json -o x.png
sess noinput.json 'del s["input"]'
expect1 'noinput.json: missing "input"' -- render --session noinput.json -o x.png
sess emptyinput.json 's["input"] = ""'
expect1 "emptyinput.json.input: empty" -- render --session emptyinput.json -o x.png
sess missinginput.json 's["input"] = "nothere.cells"'
expect1 "nothere.cells" -- render --session missinginput.json -o x.png
sess nocam.json 'del s["camera"]'
expect1 'nocam.json: missing "camera"' -- render --session nocam.json -o x.png
sess camstr.json 's["camera"]["eye"] = "up"'
expect1 "camstr.json.camera.eye: expected an array of 3 numbers" -- render --session camstr.json -o x.png
sess camnan.json 's["camera"]["eye"][1] = 1e400'
expect1 "camnan.json" -- render --session camnan.json -o x.png
sess fov.json 's["camera"]["fovY"] = 180'
expect1 "fov.json.camera.fovY: 180 is outside (0, 180)" -- render --session fov.json -o x.png
sess size.json 's["image"]["width"] = 16385'
expect1 "size.json.image.width: 16385 is not an integer in [1, 16384]" -- render --session size.json -o x.png
sess sizef.json 's["image"]["height"] = 2.5'
expect1 "sizef.json.image.height: 2.5 is not an integer" -- render --session sizef.json -o x.png
sess mode.json 's["render"]["mode"] = "pt"'
expect1 "mode.json.render.mode: 'pt' is not one of ae|ss|ms|dvr" -- render --session mode.json -o x.png
sess spp.json 's["render"]["spp"] = 16777217'
expect1 "spp.json.render.spp" -- render --session spp.json -o x.png
sess seed.json 's["render"]["seed"] = -1'
expect1 "seed.json.render.seed" -- render --session seed.json -o x.png
sess dens.json 's["render"]["densityScale"] = -1'
expect1 "dens.json.render.densityScale: -1 is outside [0, inf)" -- render --session dens.json -o x.png
sess g.json 's["render"]["g"] = 2'
expect1 "g.json.render.g: 2 is outside [-1, 1]" -- render --session g.json -o x.png
sess amb.json 's["render"]["ambient"] = [1, -1, 1]'
expect1 "amb.json.render.ambient: radiance must be >= 0" -- render --session amb.json -o x.png
sess dvr.json 's["render"]["dvrStep"] = 0'
expect1 "dvr.json.render.dvrStep: 0 is outside (0, 64]" -- render --session dvr.json -o x.png
sess shading.json 's["render"]["dvrShading"] = "yes"'
expect1 "shading.json.render.dvrShading: expected true or false" -- render --session shading.json -o x.png
sess light.json 's["lights"] = [{"type": "spot"}]'
expect1 "light.json.lights[0].type: 'spot'" -- render --session light.json -o x.png
sess light0.json 's["lights"] = [{"type": "directional", "direction": [0,0,0], "radiance": [1,1,1]}]'
expect1 "light0.json.lights[0].direction: must not be zero" -- render --session light0.json -o x.png
sess lights9.json 's["lights"] = [{"type": "point", "position": [0,0,i], "intensity": [1,1,1]} for i in range(9)]'
expect1 "at most 8 lights" -- render --session lights9.json -o x.png
sess lightsobj.json 's["lights"] = {"type": "point"}'
expect1 "lightsobj.json.lights: expected an array" -- render --session lightsobj.json -o x.png
sess trav.json 's["structure"]["traversal"] = "octree"'
expect1 "trav.json.structure.traversal: 'octree' is not one of" -- render --session trav.json -o x.png
sess densabr.json 's["structure"]["traversal"] = "abr"; s["structure"]["sampler"] = "dense"'
expect1 "--sampler dense needs --traversal grid-dda or grid-bvh" -- render --session densabr.json -o x.png
sess kd.json 's["structure"]["kdLeaves"] = 16777216'
expect1 "kd.json.structure.kdLeaves: 16777216 is outside [1, 16777215]" -- render --session kd.json -o x.png
sess mib.json 's["structure"]["denseMaxMiB"] = 0'
expect1 "mib.json.structure.denseMaxMiB" -- render --session mib.json -o x.png
sess grid.json 's["structure"]["grid"] = "0"'
expect1 "grid.json.structure.grid: macrocells must be in [1, 4096] (got 0)" -- render --session grid.json -o x.png
sess notf.json 'del s["transferFunction"]'
expect1 'notf.json: missing "transferFunction"' -- render --session notf.json -o x.png
sess tfnan.json 's["transferFunction"]["Points"][1] = "x"'
expect1 "tfnan.json.transferFunction" -- render --session tfnan.json -o x.png
sess tfdesc.json 's["transferFunction"]["RGBPoints"] = [5,1,1,1,1,0,0,0]'
expect1 "tfdesc.json.transferFunction" -- render --session tfdesc.json -o x.png
sess array.json 's = [s]'
expect1 "not an amrvk session" -- render --session array.json -o x.png
sess dims.json 's["read"]["dims"] = [0, 1, 1]'
expect1 "dims.json.read.dims[0]: 0 is not an integer in [1, 1048576]" -- render --session dims.json -o x.png
sess nan.json 's["read"]["nan"] = "ignore"'
expect1 "nan.json.read.nan: unknown NaN policy 'ignore'" -- render --session nan.json -o x.png
printf '{"amrvk": "session", "version": 1,' > trunc.json
expect1 "trunc.json: not a session (malformed JSON" -- render --session trunc.json -o x.png
: > empty.json
expect1 "empty.json: not a session (malformed JSON" -- render --session empty.json -o x.png
expect1 "/dev/null: no such session file" -- render --session /dev/null -o x.png
mkdir sessions-dir
expect1 "sessions-dir" -- render --session sessions-dir -o x.png
check1 test ! -e x.png

# ---- 5. User shaders cannot crash or hang amrvk ---------------------------------------------
section "user shaders"
cp -r shaders sh_self
printf '#include "self.glsl"\n' > sh_self/lib/self.glsl
sed -i 's|#include "lib/common.glsl"|#include "lib/common.glsl"\n#include "lib/self.glsl"|' sh_self/passes/path_trace.comp
expect1 "self.glsl:1: error: '#include' : includes nested deeper than 32 levels" -- render good.cells "${pic[@]}" --shader-dir sh_self -o x.png
cp -r shaders sh_dev
sed -i 's|#include "lib/common.glsl"|#include "lib/common.glsl"\n#include "/dev/zero"|' sh_dev/passes/path_trace.comp
expect1 "cannot find '/dev/zero'" -- render good.cells "${pic[@]}" --shader-dir sh_dev -o x.png
cp -r shaders sh_big
head -c 70000000 /dev/zero | tr '\0' ' ' > sh_big/lib/big.glsl
sed -i 's|#include "lib/common.glsl"|#include "lib/common.glsl"\n#include "lib/big.glsl"|' sh_big/passes/path_trace.comp
expect1 "the sources of one shader exceed 64 MiB" -- render good.cells "${pic[@]}" --shader-dir sh_big -o x.png
rm -rf sh_big
cp -r shaders sh_loop
sed -i 's|void main() {|void main() { float spin = 0.0; for (uint k = 0u; k < 0xffffffffu; ++k) spin += sin(float(k)); if (spin == 12345.0) return;|' sh_loop/passes/path_trace.comp
expect1 "ran longer than 3 s (--gpu-timeout): a runaway loop? ending" -- render good.cells "${pic[@]}" --shader-dir sh_loop --gpu-timeout 3 -o loop.png --json loop.json
check1 test ! -e loop.png
check1 test ! -e loop.json
printf '3 quit\n' > q.txt
expect1 "ran longer than 3 s" -- view good.cells "${pic[@]}" --headless --shader-dir sh_loop --gpu-timeout 3 --script q.txt --save-session never.json
check1 test ! -e never.json
cp -r shaders sh_oob
sed -i 's|void main() {|void main() { if (gl_GlobalInvocationID.x == 0u) { FloatRW wild = FloatRW(P.accum + (uint64_t(1) << 46)); wild.v[0] = 1.0; }|' sh_oob/passes/path_trace.comp
expect1 "crashed the process: it read or wrote outside its buffers" -- render good.cells "${pic[@]}" --shader-dir sh_oob -o oob.png --json oob.json
check1 test ! -e oob.png
cp -r shaders sh_syntax
sed -i 's|void main() {|void main() { nonsense here;|' sh_syntax/passes/path_trace.comp
expect1 "path_trace.comp:" -- render good.cells "${pic[@]}" --shader-dir sh_syntax -o x.png
expect1 "no-such-dir" -- render good.cells "${pic[@]}" --shader-dir no-such-dir -o x.png
expect1 "--shader-dir" -- render good.cells "${pic[@]}" --shader-dir good.cells -o x.png
expect1 "--gpu-timeout: -1 is outside" -- render good.cells "${pic[@]}" --gpu-timeout -1 -o x.png
no_temporaries

# ---- 6. Work bounded by the input's meaning, documented limits as enforced ---------------------
section "bounded work and limits"
python3 - <<'PY'
import json, random
random.seed(1)
n = 100000
xs = [1 + 4.0 * i / (n - 1) for i in range(n)]
rgb, pts = [], []
for x in xs:
    rgb += [x, random.random(), random.random(), random.random()]
    pts += [x, random.random(), 0.5, 0.0]
json.dump([{"Name": "big", "RGBPoints": rgb, "Points": pts}], open('big-tf.json', 'w'))
PY
ok render good.cells "${pic[@]}" --tf big-tf.json -o big.png --json big.json
check1 python3 -c "import json; j = json.load(open('big.json')); assert j['majorantSeconds'] < 5, j['majorantSeconds']"
ok render good.cells "${pic[@]}" --tf big-tf.json --traversal kdtree --kd-leaves 256 --backend sw -o bigk.png
expect1 "--kd-leaves: 16777216 is outside [1, 16777215]" -- render good.cells "${pic[@]}" --traversal kdtree --kd-leaves 16777216 -o x.png
expect1 "--kd-leaves: 16777216 is outside [1, 16777215]" -- view good.cells "${pic[@]}" --kd-leaves 16777216 --headless --frames 1
expect1 "--spp: 16777217 is outside [1, 16777216]" -- render good.cells --spp 16777217 -o x.png
expect1 "--size '16385x8': expected WxH with 1 <= W, H <= 16384" -- render good.cells --size 16385x8 -o x.png
expect1 "--size '0x8'" -- render good.cells --size 0x8 -o x.png
expect1 "--size '8x'" -- render good.cells --size 8x -o x.png
expect1 "--grid: macrocells must be in [1, 4096] (got 4097)" -- render good.cells --size 8x8 --grid 4097 -o x.png
expect1 "--dense-max-mib: 0 is outside [1, 1048576]" -- render good.cells --dense-max-mib 0 -o x.png
expect1 "--samples-per-invocation: 65 is outside [0, 64]" -- render good.cells --samples-per-invocation 65 -o x.png
expect1 "--dt: 0 is outside (0, 64]" -- render good.cells --dt 0 -o x.png
expect1 "--g: 1.5 is outside [-1, 1]" -- render good.cells --g 1.5 -o x.png
expect1 "--seed: 4294967296 is outside [0, 4294967295]" -- render good.cells --seed 4294967296 -o x.png
expect1 "--density-scale: -1 is outside" -- render good.cells --density-scale -1 -o x.png
expect1 "--fov: 180 is outside (0, 180)" -- render good.cells --fov 180 -o x.png
expect1 "at most 8 lights" -- render good.cells "${pic[@]}" $(for i in 1 2 3 4 5 6 7 8 9; do printf -- '--light-dir 0 0 1 1 1 1 '; done) -o x.png
expect1 "--tf-range 3 1: LO must be below HI" -- render good.cells "${pic[@]}" --tf-range 3 1 -o x.png
expect1 "--tf-range 1 1: LO must be below HI" -- render good.cells "${pic[@]}" --tf-range 1 1 -o x.png
expect1 "--frames: 0 is outside" -- view good.cells --headless --frames 0
expect1 "--frame-budget-ms: 0 is outside" -- view good.cells --headless --frames 1 --frame-budget-ms 0
expect1 "--window '0x0'" -- view good.cells --headless --frames 1 --window 0x0
expect1 "--headless needs --frames N or a --script" -- view good.cells --headless
expect1 "--traversal auto is for amrvk render" -- view good.cells --traversal auto --headless --frames 1
check1 test ! -e x.png

# ---- 7. Signals leave nothing partial, however many outputs are open -------------------------
section "signals"
for sig in HUP INT TERM QUIT; do
  rm -f sig-*
  "$amrvk" gen cloud --cells 100000000 --seed 1 -o sig-$sig 2>/dev/null & pid=$!
  for _ in $(seq 300); do ls sig-$sig.cells.tmp-* >/dev/null 2>&1 && break; sleep 0.1; done
  check1 ls sig-$sig.cells.tmp-*
  kill -$sig $pid; wait $pid; rc=$?
  check1 test "$rc" -gt 128
  check1 test -z "$(ls | grep '^sig-' || true)"
done
no_temporaries

# ---- 8. Odd names: every message one line, every name written as given ----------------------
section "odd names"
ok render good.cells "${pic[@]}" -o "with space.png"
check1 test -s "with space.png"
ok render good.cells "${pic[@]}" -o "$(printf 'new\nline.png')"
check1 test -s "$(printf 'new\nline.png')"
ok render good.cells "${pic[@]}" -o "ünïcode.png"
check1 test -s "ünïcode.png"
ok render good.cells "${pic[@]}" -o ./-dash.png
check1 test -s ./-dash.png
expect1 "unknown image type" -- render good.cells "${pic[@]}" -o "$(printf 'a\033[2Jb.txt')"
expect1 "no such file" -- render "$(printf 'in\nput.cells')" -o x.png
expect1 "unknown field" -- render good.cells --field "$(printf 'f\ti\rx')" -o x.png
expect1 "unknown field" -- convert good.cells --field "../../etc" -o conv3
check1 test ! -e conv3.cells
ok convert good.cells --field rho -o "conv 4"
check1 test -s "conv 4.rho.scalars"

# ---- 9. Round 3 (issue 34): what round 2 missed --------------------------------------------
section "round 3"
# shaders --export never writes through a link: a link at a file's name is replaced itself, a
# linked folder under DIR is refused (its files would land outside DIR).
"$amrvk" shaders --export exp1 >/dev/null
echo precious > outside.glsl
rm exp1/lib/tf.glsl; ln -s "$dir/outside.glsl" exp1/lib/tf.glsl
ok shaders --export exp1 --force
check1 grep -qx precious outside.glsl
check1 test ! -L exp1/lib/tf.glsl
check1 grep -q "vec4" exp1/lib/tf.glsl
mkdir outside-lib; cp exp1/lib/*.glsl outside-lib/; echo precious > outside-lib/tf.glsl
rm -r exp1/lib; ln -s "$dir/outside-lib" exp1/lib
expect1 "exp1/lib: a symbolic link" -- shaders --export exp1 --force
check1 grep -qx precious outside-lib/tf.glsl
# An export is all or nothing: a write that fails (here a file-size limit of 12 KiB, which the
# largest source exceeds; a full disk fails the same way) leaves no DIR, and over an existing DIR
# with --force leaves it as it was; no temporary either way.
export_limited() {  # export_limited ARGS...: amrvk shaders ARGS with files limited to 12 KiB
  cases=$((cases + 1))
  ( trap '' XFSZ; ulimit -f 12; exec "$amrvk" shaders "$@" ) >"$dir/lim.out" 2>"$dir/lim.err"; local rc=$?
  if [ "$rc" != 1 ] || [ "$(wc -l <"$dir/lim.err")" != 1 ]; then
    echo "FAIL: limited shaders $* -> rc=$rc: $(cat "$dir/lim.err")"; fail=1
  else
    echo "ok: limited shaders $* -> $(cat "$dir/lim.err")"
  fi
}
export_limited --export exp3
check1 test ! -e exp3
"$amrvk" shaders --export exp4 >/dev/null
echo old > exp4/lib/tf.glsl; echo old > exp4/lib/common.glsl
export_limited --export exp4 --force
check1 grep -qx old exp4/lib/tf.glsl
check1 grep -qx old exp4/lib/common.glsl
no_temporaries
# A movie never deletes or replaces a file it did not write: frames no manifest lists are refused
# (a stand-in ffmpeg on PATH: the check comes before any encoding).
mkdir -p fakebin; printf '#!/bin/sh\nexit 0\n' > fakebin/ffmpeg; chmod +x fakebin/ffmpeg
mkdir M.mp4.frames; echo mine > M.mp4.frames/frame_0000.png
PATH="$dir/fakebin:$PATH" expect1 "-o M.mp4: 1 of its frames in M.mp4.frames/ exist and no manifest of amrvk's lists them" -- \
  render good.cells "${pic[@]}" --frames 2 --orbit 90 -o M.mp4
check1 grep -qx mine M.mp4.frames/frame_0000.png
check1 test ! -e M.mp4
mkdir kept.d; echo mine > kept.d/frame_0001.png
PATH="$dir/fakebin:$PATH" expect1 "--frames-dir kept.d/: 1 of the frames exist and no manifest" -- \
  render good.cells "${pic[@]}" --frames 2 --orbit 90 -o K.mp4 --frames-dir kept.d
check1 grep -qx mine kept.d/frame_0001.png
mkdir N.mp4.frames  # the user's (empty) directory: used, and left in place
PATH="$dir/fakebin:$PATH" ok render good.cells "${pic[@]}" --frames 2 --orbit 90 -o N.mp4
check1 test -d N.mp4.frames
check1 test -z "$(ls -A N.mp4.frames)"
PATH="$dir/fakebin:$PATH" ok render good.cells "${pic[@]}" --frames 2 --orbit 90 -o O.mp4
check1 test ! -e O.mp4.frames
# Frames that amrvk's manifest lists are its own: another command over them replaces them.
PATH="$dir/fakebin:$PATH" ok render good.cells "${pic[@]}" --frames 2 --orbit 90 -o P.mp4 --frames-dir kept.p
PATH="$dir/fakebin:$PATH" ok render good.cells "${pic[@]}" --seed 3 --frames 2 --orbit 90 -o P.mp4 --frames-dir kept.p
check1 grep -q "records another command" ok.err
check1 test -s kept.p/frame_0001.png
# A signal between creating a temporary and setting it up (a pause injected there) removes it too.
rm -f sigd*
AMRVK_TEST_TEMPORARY_DELAY_MS=3000 "$amrvk" gen cloud --cells 1000 --seed 1 -o sigd >/dev/null 2>&1 & pid=$!
for _ in $(seq 300); do ls sigd.cells.tmp-* >/dev/null 2>&1 && break; sleep 0.02; done
check1 ls sigd.cells.tmp-*
kill -INT $pid; wait $pid; rc=$?
check1 test "$rc" -gt 128
check1 test -z "$(ls | grep '^sigd' || true)"
# SIGINT while convert holds 101 temporaries at once (100 fields) left some behind in a round-4
# report (point 18; not reproduced at today's main, whose handler has 1024 slots): the signal
# comes once more than 64 exist, and none may stay.
mkdir -p many; "$amrvk" gen cloud --cells 500 --seed 1 -o many/w >/dev/null 2>&1
for i in $(seq -w 0 99); do cp many/w.scalars many/w.f0$i.scalars; done
AMRVK_TEST_TEMPORARY_DELAY_MS=30 "$amrvk" convert many/w.cells -o many/out >/dev/null 2>&1 & pid=$!
for _ in $(seq 1000); do [ "$(ls many | grep -c '\.tmp-')" -gt 80 ] && break; sleep 0.02; done
check1 test "$(ls many | grep -c '\.tmp-')" -gt 64
kill -INT $pid; wait $pid; rc=$?
check1 test "$rc" -gt 128
check1 test -z "$(ls many | grep -e '\.tmp-' -e '^out' || true)"
# A clip plane's normal is normalised without overflow or underflow: 1e308 (and 1e154) and 1e-200
# per component cut as 1 1 1 does; only an exact zero is refused.
clip=(--clip 2 1 1)
ok render good.cells "${pic[@]}" -o clip-none.png
ok render good.cells "${pic[@]}" "${clip[@]}" 1 1 1 -o clip-one.png
check1 eval '! cmp -s clip-none.png clip-one.png'
for n in 1e308 1e154 1e-200; do
  ok render good.cells "${pic[@]}" "${clip[@]}" $n $n $n -o clip-$n.png
  check1 cmp clip-one.png clip-$n.png
done
expect1 "--clip: the normal 0 0 0 points nowhere" -- render good.cells "${pic[@]}" "${clip[@]}" 0 0 0 -o x.png
no_temporaries
# Names from a file are shown escaped, on one line, in every message: a Chombo component name
# holding an escape sequence and a line break (a real plotfile's, rewritten with h5py).
chombo="${AMRVK_DATA_DIR:-$src/../shared/data/amr}/chombo_mushy_layer_2d/plt000100.2d.hdf5"
if [ -f "$chombo" ] && /usr/bin/python3 -c "import h5py" 2>/dev/null; then
  cp "$chombo" esc.hdf5; chmod u+w esc.hdf5
  /usr/bin/python3 -c "import h5py; f = h5py.File('esc.hdf5', 'r+'); f.attrs['component_0'] = b'a\x1b[2J\nb'"
  ok convert esc.hdf5 -o conv-esc
  check1 test "$(wc -l <ok.err)" = 1
  check1 grep -qF "field 'a\x1b[2J\nb' is written as conv-esc.a_[2J_b.scalars" ok.err
  check1 eval "! LC_ALL=C grep -q '[[:cntrl:]]' ok.err"
  ok info esc.hdf5
  check1 grep -qF 'fields        a\x1b[2J\nb, ' ok.out
  check1 eval "! LC_ALL=C grep -q '[[:cntrl:]]' ok.out"
  expect1 "unknown field 'nope' (available: a\x1b[2J\nb, " -- convert esc.hdf5 --field nope -o conv-esc2
else
  echo "hostile.sh: skipped the Chombo name cases (no h5py for /usr/bin/python3 or no $chombo)"
fi
# Messages blame the right thing: the script line of a camera move that fails; two RAMSES info
# files in one folder (not "none"); a --legend-font folder (not an output inside an input); and
# "is the input good.cells" (not "the input input", changed above).
printf '0 pan 1e300 1e300\n' > pan.txt
expect1 "pan.txt:1: pan: eye and target coincide" -- view good.cells "${pic[@]}" --headless --script pan.txt
mkdir two-infos; touch two-infos/info_00001.txt two-infos/info_00002.txt
expect1 "two-infos: 2 RAMSES info files (info_00001.txt, info_00002.txt): name the one to read, e.g. two-infos/info_00001.txt" -- \
  info two-infos
expect1 "--legend-font $dir: not a font file (a directory)" -- render good.cells "${pic[@]}" --legend --legend-font "$dir" -o lf.png

# ---- 10. Round 3 (issue 34, point 7): a runaway shader ends in seconds, honest work never ----
section "round 3: adaptive gpu timeout"
# No --gpu-timeout: a path_trace that never ends is cut after the adaptive floor (10 s; the first
# submission is a small probe), not after 600 s. Run under `timeout 120`, which ends the landed
# code's run (rc 124, a failure here).
printf '#!/bin/sh\nexec timeout 120 "$AMRVK_UNDER_TEST" "$@"\n' > within120.sh; chmod +x within120.sh
export AMRVK_UNDER_TEST="$amrvk"; amrvk="$dir/within120.sh"
cp -r shaders sh_forever
sed -i 's|void main() {|void main() { float spin = 0.0; for (uint k = 0u; ; ++k) { spin += sin(float(k)); if (spin < -1e30) break; } if (spin == 1.0) return;|' sh_forever/passes/path_trace.comp
expect1 "s finishing no path (the adaptive --gpu-timeout, from the measured pace and a floor; --gpu-timeout S waits S s): a runaway loop? ending" -- \
  render good.cells "${pic[@]}" --shader-dir sh_forever -o forever.png --json forever.json
check1 grep -q "GPU work 'path_trace.ae.grid-dda/grid/sw from --shader-dir sh_forever' ran longer than 10 s, the last 1[0-9] s" expect.err
check1 test ! -e forever.png
check1 test ! -e forever.json
# The viewer (tiles and previews) and a larger image (the probe is a strided part of it) alike;
# AMRVK_TEST_GPU_TIMEOUT_FLOOR shortens the floor.
AMRVK_TEST_GPU_TIMEOUT_FLOOR=2 expect1 "finishing no path (the adaptive --gpu-timeout" -- \
  view good.cells "${pic[@]}" --headless --shader-dir sh_forever --script q.txt --save-session never2.json
check1 test ! -e never2.json
AMRVK_TEST_GPU_TIMEOUT_FLOOR=2 expect1 "finishing no path (the adaptive --gpu-timeout" -- \
  render good.cells --size 640x480 --spp 4 --grid 4 --mode ae --shader-dir sh_forever -o forever.png
# An explicit --gpu-timeout keeps its meaning (here longer than the adaptive floor).
AMRVK_TEST_GPU_TIMEOUT_FLOOR=2 expect1 "ran longer than 4 s (--gpu-timeout): a runaway loop? ending" -- \
  render good.cells "${pic[@]}" --shader-dir sh_forever --gpu-timeout 4 -o forever.png
AMRVK_TEST_GPU_TIMEOUT_FLOOR=0 expect1 "AMRVK_TEST_GPU_TIMEOUT_FLOOR: '0' is not a number of seconds" -- \
  render good.cells "${pic[@]}" -o forever.png
# The majorant shaders (run on every TF change) are held to the adaptive timeout too (issue 34's
# leftover: they waited 600 s): majorants.comp, and domain_aabbs.comp of ray-query culling, each
# looping forever, end after the floor with the same line; nothing is written.
cp -r shaders sh_maj_forever
sed -i 's|void main() {|void main() { float spin = 0.0; for (uint k = 0u; ; ++k) { spin += sin(float(k)); if (spin < -1e30) break; } if (spin == 1.0) return;|' \
  sh_maj_forever/passes/majorants.comp sh_maj_forever/passes/domain_aabbs.comp
AMRVK_TEST_GPU_TIMEOUT_FLOOR=2 expect1 "GPU work 'majorants from --shader-dir sh_maj_forever' ran longer than 2 s (the adaptive --gpu-timeout, from the measured pace and a floor; --gpu-timeout S waits S s): a runaway loop? ending" -- \
  render good.cells "${pic[@]}" --shader-dir sh_maj_forever -o maj.png --json maj.json
check1 test ! -e maj.png
check1 test ! -e maj.json
cp shaders/passes/majorants.comp sh_maj_forever/passes/majorants.comp  # only domain_aabbs loops now
AMRVK_TEST_GPU_TIMEOUT_FLOOR=2 expect1 "GPU work 'domain_aabbs from --shader-dir sh_maj_forever' ran longer than 2 s (the adaptive --gpu-timeout" -- \
  render good.cells "${pic[@]}" --traversal abr --backend rq --shader-dir sh_maj_forever -o maj.png
amrvk="$AMRVK_UNDER_TEST"
# An honest render whose last submission (64 spp, about 9 s on lavapipe with 2 cores) runs longer
# than a 4 s floor is never cut: each limit grows with its paths at the pace measured so far, and
# past it paths keep finishing. (Lavapipe compiles a pipeline at its first dispatch: an empty
# dispatch at creation does it, so the probe's time holds no compiling.)
"$amrvk" gen cloud --cells 100000 --seed 1 -o slowcloud >/dev/null 2>&1
AMRVK_TEST_GPU_TIMEOUT_FLOOR=4 ok render slowcloud.cells --size 160x120 --spp 128 --mode ms -o slow.png --json slow.json
check1 test -s slow.png
no_temporaries

# ---- 11. Round 4 (issue 52, points 1, 3, 4, 6, 7 and 9): long text, narrow images, re-runs, cuts -
section "round 4"
# A 40,000-character argument crashed the parser's message (std::regex recursed per character):
# one short line naming it, elided.
long=$(head -c 40000 /dev/zero | tr '\0' x)
"$amrvk" info good.cells "--$long" 2>long.err; rc=$?
check1 test "$rc" = 1 -a "$(wc -l <long.err)" = 1 -a "$(wc -c <long.err)" -lt 200
check1 grep -qF "unknown option '--xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx... (40002 bytes)' for 'amrvk info'" long.err
"$amrvk" info good.cells "$long" 2>long.err; rc=$?
check1 test "$rc" = 1 -a "$(wc -l <long.err)" = 1
check1 grep -qF "unexpected argument 'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx... (40000 bytes)'" long.err
# An image 1 or 2 pixels wide with >= 8192 pixels hung in the first sample's probe (its count of
# bands per submission grew by 4x until it wrapped to 0); `timeout` ends the landed code's run.
check1 timeout 120 "$amrvk" render good.cells --size 1x8192 --spp 1 --mode ae --grid 4 -o tall.png
check1 test -s tall.png
check1 timeout 120 "$amrvk" render good.cells --size 2x4096 --spp 1 --mode ae --grid 4 -o tall2.png
# A series re-run whose frames are done read no input, and wrote --json over an input's .scalars
# (point 4): its manifest now lists the files its frames were read from. A fresh run that refuses
# leaves no manifest in a directory it made; an older manifest (no list) renders anew.
cp good.cells good2.cells; cp good.scalars good2.scalars; cp good.rho.scalars good2.rho.scalars; cp good2.rho.scalars good2.orig
ok render good.cells good2.cells "${pic[@]}" -o fr/
expect1 "--json good2.rho.scalars is the input $dir/good2.rho.scalars (refused: it would be overwritten)" -- \
  render good.cells good2.cells "${pic[@]}" -o fr/ --json good2.rho.scalars
check1 cmp -s good2.rho.scalars good2.orig
expect1 "--json good2.rho.scalars is the input (read)" -- render good.cells good2.cells "${pic[@]}" -o fr2/ --json good2.rho.scalars
check1 test ! -e fr2
python3 -c "import json; m = json.load(open('fr/frame_manifest.json')); del m['inputsRead']; json.dump(m, open('fr/frame_manifest.json', 'w'))"
ok render good.cells good2.cells "${pic[@]}" -o fr/ --json fr.json
check1 grep -q "2 frames: 2 rendered" "$dir/ok.out"
check1 grep -q "does not list the files its frames were read from" "$dir/ok.err"
# A re-run after an input changed rendered nothing and kept the stale frames (point 9): the
# manifest stamps each file read (size, modification time), and a changed one renders anew.
ok render good.cells good2.cells "${pic[@]}" -o fr/
check1 grep -q "2 frames: 0 rendered" "$dir/ok.out"
python3 -c "import struct; open('good2.rho.scalars','r+b').write(struct.pack('<f', 7.5))"
ok render good.cells good2.cells "${pic[@]}" -o fr/
check1 grep -q "2 frames: 2 rendered" "$dir/ok.out"
check1 grep -q "good2.rho.scalars changed since the frames in fr/frame_manifest.json were rendered: rendering all 2 frames anew" "$dir/ok.err"
cp good2.orig good2.rho.scalars
# --series-range of one input into one picture wrote a_manifest.json beside it and then kept a
# stale picture (point 9): one input is one picture, with a note that the option changes nothing.
ok render good.cells "${pic[@]}" --series-range first -o sr.png
check1 test -s sr.png -a ! -e sr_manifest.json
check1 grep -q "^amrvk: --series-range: one input has one range" "$dir/ok.err"
# A medium so dense that its free paths are below float resolution ends each tracking call at
# once, also for rays that start at a collision (t = 0), where each burned the step cap: ms at
# --density-scale 1e30 took 42 s of GPU for 256 paths (point 6; ae was fixed in round 3).
check1 timeout 30 "$amrvk" render good.cells --size 16x16 --spp 1 --mode ms --grid 4 --density-scale 1e30 -o dense.png --json dense.json
check1 python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); assert j["trackingCapHits"] > 0 and j["majorantViolations"] == 0, j' dense.json
# A TF transparent over every value of the data says so in one line, not a silent black picture
# (point 7): a constant field under the fitted default TF.
python3 -c "import struct; open('const.cells','wb').write(b''.join(struct.pack('<4i', x, 0, 0, 0) for x in range(4))); open('const.scalars','wb').write(struct.pack('<4f', 2, 2, 2, 2))"
ok render const.cells "${pic[@]}" -o const.png
check1 grep -q "is transparent (alpha 0) over every value of the data \[2, 2\]: the picture shows only the background" "$dir/ok.err"
expect1 "--tfs ',,': names no TF" -- info good.cells --check-majorants --tfs ,,
# Two opposite clip planes keep nothing (point 7): said in one line, as a crop beside the data is.
ok render good.cells "${pic[@]}" --clip 1 1 1 1 0 0 --clip 3 1 1 -1 0 0 -o clip-none.png
check1 grep -q "the --clip planes keep nothing of the data (world bounds .*): the picture shows only the background" "$dir/ok.err"
ok render good.cells "${pic[@]}" --clip 3 1 1 1 0 0 --clip 1 1 1 -1 0 0 -o clip-some.png
check1 test ! -s "$dir/ok.err"
# The legend's own options without a legend drew nothing and said nothing (point 9).
expect1 "--legend-units applies only with --legend" -- render good.cells "${pic[@]}" --legend-units g/cm^3 -o lu.png
check1 test ! -e lu.png
expect1 "--legend-title: 300 bytes (at most 256)" -- render good.cells "${pic[@]}" --legend --legend-title "$(head -c 300 /dev/zero | tr '\0' t)" -o lt.png
check1 test ! -e lt.png
# --kd-leaves 16777215 on a small data set reserved a 1 GB tree and ended in "out of memory"
# (point 18): the leaves are bounded by the cells (about 60 bytes each on the host).
ok render good.cells "${pic[@]}" --traversal kdtree --kd-leaves 16777215 -o kbig.png --json kbig.json
check1 python3 -c 'import json,os,sys; j=json.load(open(sys.argv[1])); n=os.path.getsize("good.cells")//16; b=j["hostMemoryPerStructure"]["kdTree"]; assert 0 < b <= 64*n, (n, b)' kbig.json
# Misleading messages (point 16): a colour a rounding above 1 printed as 1; a NaN range called
# unordered; gen's limit unlike its --help; control characters of a name printed raw by gen and
# convert; an all-NaN field under --nan drop called "no cells".
echo '[{"Name":"x","ColorSpace":"RGB","RGBPoints":[0,1.0000001,0,0,1,1,1,1]}]' >over1.json
expect1 "RGBPoints node 0 colour r = 1.0000001 is outside [0, 1]" -- render good.cells "${pic[@]}" --tf over1.json -o o1.png
expect1 "--tf-range nan 1: LO and HI must be finite" -- info good.cells --check-majorants --tf-range nan 1
expect1 "--cells: 1099511627776 is outside [1, 1e+11]" -- gen cloud --cells 1099511627776 -o big
"$amrvk" gen cloud --cells 200 -o $'esc\x1bname' >gen.out 2>&1
check1 grep -qF 'esc\x1bname.cells' gen.out
check1 test -z "$(tr -d '\n' <gen.out | tr -d '[:print:]')"
"$amrvk" convert $'esc\x1bname.cells' -o $'conv\x1bname' >conv.out 2>&1
check1 grep -qF 'wrote conv\x1bname.cells' conv.out
check1 test -z "$(tr -d '\n' <conv.out | tr -d '[:print:]')"
python3 -c "import struct; open('allnan.cells','wb').write(b''.join(struct.pack('<4i', x, 0, 0, 0) for x in range(4))); open('allnan.scalars','wb').write(struct.pack('<4f', *[float('nan')] * 4))"
expect1 "allnan.cells: every one of its 4 cells has a non-finite value, and --nan drop dropped them all" -- \
  render allnan.cells --nan drop "${pic[@]}" -o allnan.png
check1 test ! -e allnan.png
# Older cases that no longer held (point 18): a valid 250-byte output name was refused because its
# temporary's name passed NAME_MAX; a symlink loop beside the data failed the read; saving a
# session back to the file it came from (the viewer's ordinary Save) was refused as an overwrite.
# An output that cannot be written (--json /dev/full) left the picture behind: one run's outputs
# are now all written or none.
expect1 "/dev/full: write failed (No space left on device)" -- render good.cells --size 8x8 --spp 2 --grid 4 --mode ae -o allor.png --variance allor.pfm --json /dev/full
check1 test ! -e allor.png -a ! -e allor.pfm
no_temporaries
long250=$(head -c 246 /dev/zero | tr '\0' n).png
ok render good.cells "${pic[@]}" -o "$long250"
check1 test -s "$long250"
no_temporaries
mkdir -p looped && cp good.cells good.scalars looped/ && ln -sfn loop1 looped/loop2 && ln -sfn loop2 looped/loop1
ok render looped/good.cells "${pic[@]}" -o looped.png
printf '0 quit\n' >quit.txt
ok view good.cells "${pic[@]}" --headless --script quit.txt --save-session back.json
cp back.json back.orig
ok view --session back.json --headless --script quit.txt --save-session back.json
check1 python3 -c 'import json,sys; assert json.load(open(sys.argv[1])) == json.load(open(sys.argv[2]))' back.json back.orig
expect1 "--stats back.json is the input --session back.json (refused: it would be overwritten)" -- \
  view --session back.json --headless --script quit.txt --save-session back.json --stats back.json

section ""
echo "hostile.sh: $cases cases"
test "$cases" -ge 150 || { echo "FAIL: only $cases cases"; fail=1; }
exit $fail
