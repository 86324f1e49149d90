#!/usr/bin/env bash
# The paper's GPU protocol, ready to run unchanged on a machine with a Vulkan GPU (docs/benchmarks.md
# section 7): 1024^2, 1 spp per frame, 10 warm-up and 100 timed frames, ambient light only, ms, the
# spiky and foggy TFs, on a 10^8-cell synthetic cloud and on Enzo DD0018; every traversal x
# sampler x back-end (rq where the device offers ray queries), the dense sampler as the cost floor
# and the automatic choice; then samples per invocation and spirv-opt against none at 1024^2
# (tools/bench-invocation.sh). Reports (results.md/.json/.csv, plots) and /usr/bin/time logs go to OUT.
# Usage: tools/bench-gpu.sh [OUT]   (default out/bench-gpu; the 2 GB cloud is generated once there)
# It builds amrvk, which the lent H100/H200 machines cannot do: there, use tools/gpu-protocol.sh
# prepare DIR on Debian and run DIR/run.sh on the machine (issue 31's protocol within 8 minutes;
# docs/benchmarks.md, "The GPU protocol in one command").
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
out="${1:-out/bench-gpu}"
enzo="${AMRVK_DATA_DIR:-../shared/data/amr}/enzo_tiny_cosmology/DD0018/DD0018"
tools/run.sh build
amrvk=build/bin/amrvk
mkdir -p "$out/data"
"$amrvk" devices | tee "$out/devices.txt"
cloud="$out/data/cloud1e8"
[ -f "$cloud.cells" ] || "$amrvk" gen cloud --cells 100000000 --seed 1 -o "$cloud"
protocol=(--size 1024x1024 --frames 100 --warmup 10 --modes ms --tfs spiky,foggy --ambient 1 1 1
          --dvr-steps none --grid-sweep 64,128,256 --auto)
/usr/bin/time -v "$amrvk" bench "$cloud.cells" -o "$out/cloud" "${protocol[@]}" 2>"$out/cloud.time"
if [ -f "$enzo" ]; then
  /usr/bin/time -v "$amrvk" bench "$enzo" --field Density -o "$out/enzo" "${protocol[@]}" 2>"$out/enzo.time"
fi
# Work per dispatch on this device (section 10): 1-16 samples per invocation at 1024^2, and the
# same with spirv-opt's SPIR-V from a second build, to decide the GPU defaults from measurements.
cmake -S . -B build-spirv-opt -DAMRVK_SPIRV_OPT=ON -DAMRVK_BUILD_TESTS=OFF >/dev/null
cmake --build build-spirv-opt -j"$(nproc)" --target amrvk >/dev/null
SIZE=1024x1024 SPP=64 AMRVK_BIN_OPT=build-spirv-opt/bin/amrvk tools/bench-invocation.sh "$out/invocation" \
  | tee "$out/invocation.md"
echo "reports: $out/cloud/results.md $out/enzo/results.md $out/invocation.md (peak host memory: Maximum resident set size in *.time)"
