#!/usr/bin/env bash
# Benchmark (not a test): time and peak memory of building bricks, ABRs and 128^3 macrocell value
# ranges for a synthetic cloud. Usage: [BLOCK=8] tools/bench-structures.sh [CELLS] [SEED]
# Prints the generator summary and one JSON object from `amrvk info --json`; see docs/benchmarks.md.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cells="${1:-1e7}"; seed="${2:-1}"
amrvk="$here/build/bin/amrvk"
[ -x "$amrvk" ] || { echo "build first: tools/run.sh build" >&2; exit 1; }
work="$(mktemp -d "${TMPDIR:-/tmp}/amrvk-bench.XXXXXX")"
trap 'rm -rf "$work"' EXIT
"$amrvk" gen cloud --cells "$cells" --seed "$seed" --block "${BLOCK:-8}" -o "$work/cloud"
"$amrvk" info "$work/cloud.cells" --grid 128 --json | python3 -c '
import json, sys
j = json.load(sys.stdin)
n = j["leafCells"]; b = j["buildSeconds"]; m = j["memoryBytes"]
print(json.dumps(j, indent=1))
print("cells %d  levels %d..%d  bricks %d  ABRs %d (%.2f bricks/ABR)" % (n, j["minLevel"], j["maxLevel"], j["bricks"], j["abrs"], j["averageBricksPerAbr"]))
print("seconds: read %.2f  bricks %.2f  abrs+ranges %.2f  macrocells %.2f  structures total %.2f" % (b["read"], b["bricks"], b["abrs"], b["macrocells"], b["bricks"] + b["abrs"] + b["macrocells"]))
print("peak resident %.1f MiB = %.1f bytes/cell; structures+model %.1f bytes/cell" % (j["peakResidentBytes"] / 2**20, j["peakResidentBytes"] / n, m["total"] / n))
'
