# Sourced by the tools/bench-*.sh scripts that run build/bin/amrvk on lavapipe or a GPU:
# here (the checkout), bin (AMRVK_BIN, default build/bin/amrvk), data (AMRVK_DATA_DIR, default
# ../shared/data/amr), enzo (the Enzo DD0018 parameter file), repeats (REPEATS, default 3), and a
# Vulkan runtime directory.
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${AMRVK_BIN:-$here/build/bin/amrvk}"
data="${AMRVK_DATA_DIR:-$here/../shared/data/amr}"
enzo="$data/enzo_tiny_cosmology/DD0018/DD0018"
repeats="${REPEATS:-3}"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/amrvk-xdg-$UID}"
mkdir -p "$XDG_RUNTIME_DIR"
