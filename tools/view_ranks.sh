#!/usr/bin/env bash
# Usage: tools/view_ranks.sh AMRVK DATA [RANKS...] -- the MPI viewer's numbers (docs/benchmarks.md):
# for each rank count, `mpirun -n N amrvk view DATA --headless --frames 80 --size 256x256` with
# --stats, then one line per run: ranks, time to the first picture, median idle frame, spp reached,
# and spp per second after the first picture (the run's wall time less the time to it).
set -u
amrvk="$1"; data="$2"; shift 2
ranks=("$@"); [ ${#ranks[@]} -gt 0 ] || ranks=(1 2 4)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 AMRVK_PROGRESS=0
out=$(mktemp -d)
for n in "${ranks[@]}"; do
  start=$(date +%s.%N)
  mpirun -q --oversubscribe -n "$n" "$amrvk" view "$data" --headless --frames 80 \
    --size 256x256 --stats "$out/stats.$n.json" >/dev/null 2>"$out/err.$n" || { echo "ranks $n: failed: $(tail -1 "$out/err.$n")"; continue; }
  end=$(date +%s.%N)
  /usr/bin/python3 - "$out/stats.$n.json" "$n" "$start" "$end" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); n = int(sys.argv[2]); wall = float(sys.argv[4]) - float(sys.argv[3])
print(f"ranks {n}: first picture {j['timeToFirstPicture']:.2f} s, idle frame median {j['idleFrames']['medianSeconds']*1e3:.0f} ms, "
      f"{j['spp']} spp in {wall:.1f} s, {j['spp']/(wall - j['timeToFirstPicture']):.1f} spp/s after the first picture, "
      f"device {j['device']}")
PY
done
rm -rf "$out"
