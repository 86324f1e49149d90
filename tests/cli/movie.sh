#!/usr/bin/env bash
# Usage: movie.sh AMRVK SCRATCH. `amrvk render -o movie.mp4` (docs/movies.md): without ffmpeg on
# PATH one line that says so and how to write frames; with it (else the test is skipped, exit 77)
# a series and a turntable whose MP4s ffprobe counts frame by frame, at the frame rate asked, the
# temporary frames removed and --frames-dir's kept, and a re-run that renders nothing.
set -u
amrvk="$1"; dir="$2"
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$dir"; mkdir -p "$dir"; cd "$dir" || exit 1
fail=0
source "$here/lib.sh"
export AMRVK_PROGRESS=0
for pair in "1 0" "2 0.1" "3 0.2"; do
  set -- $pair
  "$amrvk" gen shells --cells 3000 --seed 5 --time "$2" -o "s_$1" >/dev/null || { echo "FAIL: gen"; fail=1; }
done
pic=(--size 32x32 --spp 4 --grid 8)

# Without ffmpeg: one line, exit 1, nothing written.
env PATH=/nonexistent "$amrvk" render 's_*.cells' "${pic[@]}" -o movie.mp4 >none.out 2>none.err; rc=$?
if [ "$rc" != 1 ] || [ "$(wc -l <none.err)" != 1 ] || ! grep -q "movie.mp4: ffmpeg was not found on PATH.*apt-get install ffmpeg.*-o frames/f_%04d.png" none.err; then
  echo "FAIL: without ffmpeg: rc=$rc: $(cat none.err)"; fail=1
else
  echo "ok: without ffmpeg: $(cat none.err)"
fi
check test ! -e movie.mp4
check test ! -e movie.mp4.frames

if ! command -v ffmpeg >/dev/null || ! command -v ffprobe >/dev/null; then
  echo "SKIP: ffmpeg/ffprobe not installed (apt-get install ffmpeg)"
  [ $fail = 0 ] && exit 77 || exit 1
fi
frames() { ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 "$1"; }
rate() { ffprobe -v error -select_streams v:0 -show_entries stream=r_frame_rate -of csv=p=0 "$1"; }

# A series: three frames, the temporary frames directory gone afterwards.
"$amrvk" render 's_*.cells' "${pic[@]}" -o movie.mp4 --json m.json >m.out 2>m.err || { echo "FAIL: movie: $(cat m.err)"; fail=1; }
check test "$(frames movie.mp4)" = 3
check test "$(rate movie.mp4)" = 24/1
check test ! -e movie.mp4.frames
check test -z "$(ls | grep -e '\.tmp-' || true)"
check /usr/bin/python3 -c 'import json; j = json.load(open("m.json")); assert j["movie"] == "movie.mp4" and j["framesPattern"] is None and j["rendered"] == 3 and all(f["file"] is None for f in j["frames"]), j'

# A turntable of one output with its frames kept; the re-run renders nothing and writes the movie again.
"$amrvk" render s_2.cells "${pic[@]}" --frames 6 --orbit 360 --fps 12 -o turn.mp4 --frames-dir kept >t.out 2>t.err \
  || { echo "FAIL: turntable movie: $(cat t.err)"; fail=1; }
check test "$(frames turn.mp4)" = 6
check test "$(rate turn.mp4)" = 12/1
check test "$(ls kept | tr '\n' ' ')" = "frame_0000.png frame_0001.png frame_0002.png frame_0003.png frame_0004.png frame_0005.png frame_manifest.json "
rm turn.mp4
"$amrvk" render s_2.cells "${pic[@]}" --frames 6 --orbit 360 --fps 12 -o turn.mp4 --frames-dir kept >t2.out 2>&1 || fail=1
check grep -q "wrote turn.mp4 (6 frames: 0 rendered, 6 already written by this command" t2.out
check test "$(frames turn.mp4)" = 6
expect "--fps: only with -o MOVIE.mp4" -- render s_1.cells s_2.cells "${pic[@]}" --fps 10 -o 'x_%d.png'
exit $fail
