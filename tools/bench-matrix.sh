#!/usr/bin/env bash
# Benchmark (not a test): every traversal x sampler x back-end with `amrvk render --json` on one
# or more inputs, then a Markdown table (docs/benchmarks.md, "Structure matrix").
# Usage: [SIZE=256x256] [SPP=2] [MODE=ms] [BACKENDS="sw rq"] [TF="--tf spiky"] [EXTRA="..."] \
#          tools/bench-matrix.sh OUTDIR INPUT[:FIELD] ...   (EXTRA: more `amrvk render` options)
# Each combination renders twice; the second run is reported (the first warms driver caches).
# Columns: M paths/s (GPU time), real collisions / path, density lookups / path, traversal steps / path, null / real
# collisions, majorant violations, peak device MiB, host structure build s (incl. kd-tree).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
amrvk="$here/build/bin/amrvk"
[ -x "$amrvk" ] || { echo "build first: tools/run.sh build" >&2; exit 1; }
[ $# -ge 2 ] || { sed -n 2,8p "$0" >&2; exit 2; }
out="$1"; shift
mkdir -p "$out"
size="${SIZE:-256x256}"; spp="${SPP:-2}"; mode="${MODE:-ms}"; backends="${BACKENDS:-sw rq}"
for input in "$@"; do
  file="${input%%:*}"; field=""; [ "$file" != "$input" ] && field="${input#*:}"
  tag="$(basename "$file" | tr -c 'A-Za-z0-9_\n-' '_')"
  for t in grid-dda grid-bvh abr brick ext-brick kdtree; do
    for s in ext-brick abr; do
      for b in $backends; do
        j="$out/$tag.$t.$s.$b.json"
        args=("$file" --traversal "$t" --sampler "$s" --backend "$b" --mode "$mode" --size "$size" --spp "$spp"
              -o "$out/$tag.$t.$s.$b.png" --json "$j")
        [ -n "$field" ] && args+=(--field "$field")
        read -r -a more <<< "${TF:---tf spiky} ${EXTRA:-}"
        args+=("${more[@]}")
        echo "== $tag $t/$s/$b" >&2
        AMRVK_PROGRESS=0 "$amrvk" render "${args[@]}" >/dev/null
        AMRVK_PROGRESS=0 "$amrvk" render "${args[@]}" >/dev/null
      done
    done
  done
done
python3 - "$out" <<'PY'
import json, pathlib, sys
out = pathlib.Path(sys.argv[1])
rows = []
for f in sorted(out.glob("*.json")):
    j = json.loads(f.read_text())
    p = j["paths"]; real = max(j["realCollisions"], 1)
    rows.append((f.name.split(".")[0], j["traversal"], j["sampler"], j["backend"], j["pathsPerSecond"] / 1e6,
                 j["realCollisions"] / p, j["densityLookups"] / p, j["traversalSteps"] / p, j["nullCollisions"] / real,
                 j["majorantViolations"], j["deviceMemoryPeakBytes"] / 2**20,
                 j["structureBuildSeconds"] + j["structureBuildSecondsPer"]["kdTree"], j["device"]))
print("| data | traversal | sampler | back-end | M paths/s | real/path | lookups/path | steps/path | null/real | violations | peak MiB | build s |")
print("|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
for r in rows:
    print("| %s | %s | %s | %s | %.4f | %.3f | %.2f | %.2f | %.2f | %d | %.1f | %.2f |" % r[:12])
print("\ndevice: " + ", ".join(sorted({r[12] for r in rows})))
PY
