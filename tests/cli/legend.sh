#!/usr/bin/env bash
# Usage: legend.sh AMRVK SOURCE_DIR SCRATCH. Colour legends end to end (docs/cli.md "Colour legends"): render
# --legend beside and over the picture, the viewer's screenshot with the same legend, the legend
# kept in a session, and one-line errors (missing font, non-PNG output, a picture too small) that
# leave no output behind. The pixels themselves are checked by cpu/legend_image_test.
set -u
amrvk="$1"; src="$2"; dir="$3"
rm -rf "$dir"; mkdir -p "$dir"
sample="$src/assets/samples/cloud.cells"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
size() { python3 -c 'import struct,sys; d=open(sys.argv[1],"rb").read(24); assert d[:8]==b"\x89PNG\r\n\x1a\n"; print("%dx%d" % struct.unpack(">II", d[16:24]))' "$1"; }

common=(--size 64x96 --spp 1 --grid 16 --tf-range 0 1)
if ! "$amrvk" render "$sample" "${common[@]}" --legend -o "$dir/side.png" >/dev/null 2>"$dir/side.err"; then
  # A build without FreeType: --legend is one line saying why, and nothing is written.
  if grep -q "built without FreeType" "$dir/side.err" && [ "$(wc -l <"$dir/side.err")" = 1 ] && [ ! -e "$dir/side.png" ]; then
    echo "ok: built without FreeType: $(cat "$dir/side.err")"; exit 0
  fi
  echo "FAIL: render --legend: $(cat "$dir/side.err")"; exit 1
fi
# Beside the picture: as high, wider by the strip.
w=$(size "$dir/side.png"); check test "${w#*x}" = 96
check test "${w%x*}" -gt 64
# Over the picture: the size of the picture.
"$amrvk" render "$sample" --size 160x96 --spp 1 --grid 16 --legend --legend-place overlay --legend-units 'g/cm³' \
  -o "$dir/overlay.png" >/dev/null || fail=1
check test "$(size "$dir/overlay.png")" = 160x96

# The viewer's screenshot gets the same legend, and the session keeps it for render --session.
"$amrvk" view "$sample" "${common[@]}" --headless --frames 1 --legend --legend-title 'density of the cloud' \
  --screenshot "$dir/view.png" --save-session "$dir/s.json" 2>/dev/null || fail=1
check python3 -c 'import json,sys; l=json.load(open(sys.argv[1]))["legend"]; assert l["show"] and l["place"] == "side" and l["title"] == "density of the cloud", l' "$dir/s.json"
"$amrvk" render --session "$dir/s.json" -o "$dir/from-session.png" >/dev/null || fail=1
check test "$(size "$dir/view.png")" = "$(size "$dir/from-session.png")"
check test "${w%x*}" -lt "$(size "$dir/view.png" | cut -dx -f1)"  # a longer title, a wider strip
# The script action (and so the checkbox's state): on, a PNG screenshot with the legend; off, without.
printf '0 legend on\n1 screenshot %s\n1 legend off\n2 screenshot %s\n3 quit\n' "$dir/on.png" "$dir/off.png" >"$dir/legend.script"
"$amrvk" view "$sample" "${common[@]}" --headless --script "$dir/legend.script" 2>/dev/null || fail=1
check test "$(size "$dir/on.png")" = "$w"
check test "$(size "$dir/off.png")" = 64x96
# A session's legend is not drawn into linear images (a note), but --legend asks for a PNG.
"$amrvk" render --session "$dir/s.json" -o "$dir/from-session.pfm" >/dev/null 2>"$dir/pfm.err" || fail=1
check grep -q "legend is drawn into PNG images only" "$dir/pfm.err"

# The window (tests/with_xvfb.sh): the overlay darkens the picture's lower right corner under its
# backdrop while the legend is on, and the corner is the white background again when it is off.
if command -v Xvfb >/dev/null; then
  printf '4 capture-window %s\n5 legend off\n8 capture-window %s\n9 quit\n' "$dir/win-on.png" "$dir/win-off.png" >"$dir/win.script"
  bash "$src/tests/with_xvfb.sh" 800x600x24 "$amrvk" view "$sample" --size 200x150 --window 800x600 --spp 1 --grid 16 \
    --background 1 1 1 --legend --script "$dir/win.script" --stats "$dir/win.json" --validation 2>"$dir/win.err" || { echo "FAIL: window: $(tail -1 "$dir/win.err")"; fail=1; }
  check python3 - "$dir/win-on.png" "$dir/win-off.png" "$dir/win.json" <<'PY'
import sys, zlib, struct
def grey(path):  # 8-bit RGB(A) PNG without interlace, as amrvk writes it: the mean of each pixel's channels
    d = open(path, "rb").read(); pos, idat, w, h = 8, b"", 0, 0
    while pos < len(d):
        n, kind = struct.unpack(">I4s", d[pos:pos + 8]); body = d[pos + 8:pos + 8 + n]; pos += 12 + n
        if kind == b"IHDR": w, h, depth, ctype = struct.unpack(">IIBB", body[:10]); assert depth == 8 and ctype in (2, 6)
        if kind == b"IDAT": idat += body
    raw, bpp = zlib.decompress(idat), 4 if ctype == 6 else 3
    rows, prev = [], bytearray(w * bpp)
    for y in range(h):
        f, line = raw[y * (w * bpp + 1)], bytearray(raw[y * (w * bpp + 1) + 1:(y + 1) * (w * bpp + 1)])
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0; b = prev[i]; c = prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line); prev = line
    return lambda x, y: sum(rows[y][x * bpp:x * bpp + 3]) / 3
on, off = grey(sys.argv[1]), grey(sys.argv[2])
import json
p = json.load(open(sys.argv[3]))["layout"]["picture"]  # the picture's rectangle beside the panel
right, bottom = p["x"] + p["width"], p["y"] + p["height"]
corner = [(x, y) for x in range(right - 40, right - 10) for y in range(bottom - 40, bottom - 10)]
dark_on = sum(on(x, y) < 200 for x, y in corner); bright_off = sum(off(x, y) > 240 for x, y in corner)
assert dark_on > 0.6 * len(corner) and bright_off > 0.9 * len(corner), (dark_on, bright_off, len(corner))
PY
else
  echo "skip: no Xvfb for the window check"
fi

expect "--legend: /nonexistent/font.ttf: no such file" -- render "$sample" "${common[@]}" --legend \
  --legend-font /nonexistent/font.ttf -o "$dir/x.png"
echo "not a font" >"$dir/bad.ttf"
expect "not a font FreeType can read" -- render "$sample" "${common[@]}" --legend --legend-font "$dir/bad.ttf" -o "$dir/x.png"
expect "--legend: only PNG images get a legend" -- render "$sample" "${common[@]}" --legend -o "$dir/x.exr"
expect "is too small for a legend" -- render "$sample" --size 16x12 --spp 1 --legend -o "$dir/x.png"
expect "--legend-place: 'corner' is not one of side|overlay" -- render "$sample" "${common[@]}" --legend --legend-place corner -o "$dir/x.png"
cp "$dir/bad.ttf" "$dir/font.png"  # a font that is not to be overwritten by the output it names
expect "is the input --legend-font $dir/font.png" -- render "$sample" "${common[@]}" --legend --legend-font "$dir/font.png" -o "$dir/font.png"
expect "--legend: /nonexistent/font.ttf: no such file" -- view "$sample" "${common[@]}" --headless --frames 1 --legend \
  --legend-font /nonexistent/font.ttf --screenshot "$dir/x.png"
check test ! -e "$dir/x.png"
check test ! -e "$dir/x.exr"
check cmp -s "$dir/bad.ttf" "$dir/font.png"
exit $fail
