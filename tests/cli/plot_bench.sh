#!/usr/bin/env bash
# Usage: plot_bench.sh PLOT_SCRIPT SCRATCH. tools/plot_bench.py on a fixture results.json shaped like
# `amrvk bench` output (14 combinations, dense and --auto runs, dvr over three steps, a grid sweep
# of two traversals, failed runs, null and zero values, a data set whose runs all failed): it
# writes exactly the expected PNG and PDF files, names them on stdout, leaves no temporary file,
# and rejects a missing results.json with one line and exit status 1. Exits 77 (skipped) when no
# Python with matplotlib is found (python3 on PATH, then /usr/bin/python3, as amrvk bench does).
set -u
script="$1"; dir="$2"
rm -rf "$dir"; mkdir -p "$dir/out"
fail=0
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
python=""
for p in python3 /usr/bin/python3; do
  if "$p" -c "import matplotlib" >/dev/null 2>&1; then python="$p"; break; fi
done
if [ -z "$python" ]; then
  echo "SKIP: no Python with matplotlib (tried python3 on PATH and /usr/bin/python3)"; exit 77
fi

"$python" - "$dir/out/results.json" <<'PY'
import json, sys
def run(kind, traversal, sampler, dataset="cloud.cells", mode="ms", scale=1.0, **extra):
    r = {"dataset": dataset, "tf": "spiky", "mode": mode, "kind": kind,
         "label": "{}/{}/sw".format(traversal, sampler), "traversal": traversal, "sampler": sampler,
         "backend": "sw", "grid": "auto", "width": 64, "height": 64, "frames": 16,
         "fps": 100.0 / scale, "deviceBytesAfterBuild": int(2e6 * scale), "deviceBytesPeak": int(3e6 * scale),
         "error": [{"spp": n, "seconds": 0.01 * n * scale, "rmse": 0.2 / n ** 0.5, "relMse": 0.1 / n}
                   for n in (1, 2, 4, 8, 16)]}
    r.update(extra)
    return r
runs = [run("matrix", t, s, scale=1 + i) for i, (t, s) in enumerate(
    (t, s) for t in ("grid-dda", "grid-bvh", "abr", "brick", "ext-brick", "kdtree") for s in ("ext-brick", "abr"))]
runs[3]["error"][2]["rmse"] = None        # a non-finite value, written as null
runs[4]["error"][0]["seconds"] = 0.0      # not positive on a log axis
runs.append(run("matrix", "kdtree", "abr", error="out of device memory"))
runs.append(run("dense", "grid-dda", "dense", scale=200.0))
runs.append(run("auto", "grid-bvh", "abr", label="grid-bvh/abr/sw grid 64"))
runs.append(run("pt-ae", "grid-dda", "ext-brick", mode="ae", label="ae tracking (grid-dda/ext-brick/sw)"))
for dt in (2, 0.5, 0.125):
    runs.append(run("dvr", "grid-dda", "ext-brick", mode="dvr", dt=dt, label="dvr dt {:g}".format(dt)))
for t in ("grid-dda", "grid-bvh"):
    for g in ("16", "32", "64"):
        runs.append(run("grid-sweep", t, "ext-brick", grid=g, label="{}/ext-brick/sw grid {}".format(t, g)))
runs.append(run("grid-sweep", "grid-bvh", "ext-brick", grid="128", error="failed"))
runs.append(run("matrix", "grid-dda", "ext-brick", dataset="DD0018:Density", error="no such field"))
json.dump({"device": "fixture device", "width": 64, "height": 64, "frames": 16, "runs": runs},
          open(sys.argv[1], "w"), indent=1)
PY

"$python" "$script" "$dir/out" >"$dir/stdout.txt" || { echo "FAIL: plot_bench.py exited with $?"; fail=1; }
expected=""
for stem in error_cloud_cells_spiky_ms error_cloud_cells_spiky_dvr grid_sweep_cloud_cells_spiky memory_cloud_cells; do
  expected="$expected$stem.png\n$stem.pdf\n"
  check test "$(head -c 4 "$dir/out/$stem.png" | od -An -tx1 | tr -d ' \n')" = 89504e47
  check test "$(head -c 4 "$dir/out/$stem.pdf")" = "%PDF"
done
check test "$(sort "$dir/stdout.txt")" = "$(printf "$expected" | sort)"
check test "$(ls "$dir/out" | grep -cv -e '\.png$' -e '\.pdf$')" = 1   # results.json only: no temporaries
echo "plots: $(tr '\n' ' ' <"$dir/stdout.txt")"

# A directory without results.json: one line on stderr, exit status 1.
"$python" "$script" "$dir/missing" >/dev/null 2>"$dir/missing.err"; rc=$?
check test "$rc" = 1
check test "$(wc -l <"$dir/missing.err")" = 1
check grep -q "results.json" "$dir/missing.err"
# A plot that cannot be written (a full disk; here its name is a directory) is named, not
# results.json, and no temporary stays.
mkdir -p "$dir/blocked"; cp "$dir/out/results.json" "$dir/blocked/"; mkdir "$dir/blocked/memory_cloud_cells.png"
"$python" "$script" "$dir/blocked" >/dev/null 2>"$dir/blocked.err"; rc=$?
check test "$rc" = 1
check test "$(wc -l <"$dir/blocked.err")" = 1
check grep -q "^plot_bench.py: error: cannot write $dir/blocked/memory_cloud_cells.png: Is a directory$" "$dir/blocked.err"
check test -z "$(ls "$dir/blocked" | grep tmp-)"
exit $fail
