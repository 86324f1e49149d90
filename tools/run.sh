#!/usr/bin/env bash
# amrvk set-up and entry points. Usage: tools/run.sh demo|test|build|deps
#   demo  installs what is missing, builds Release into build/, renders the Enzo cosmology data
#         beside the checkout (or the bundled sample where it is absent) to out/demo.png
#   test  installs what is missing, builds, runs every test (ctest)
#   build installs what is missing and builds
#   deps  only installs what is missing (Debian 12; root or sudo)
# Everything comes from Debian's packages (bookworm, plus bookworm-backports for Mesa 25).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

say() { printf '[amrvk] %s\n' "$*" >&2; }

# Packages from bookworm itself.
base_pkgs=(cmake g++ make pkg-config libvulkan-dev vulkan-tools vulkan-validationlayers
           glslc glslang-tools spirv-tools libglfw3-dev libglm-dev libgtest-dev
           libhdf5-dev libpng-dev zlib1g-dev nlohmann-json3-dev python3 python3-matplotlib
           libcli11-dev libtinyexr-dev libtbb-dev libshaderc-dev
           libimgui-dev xvfb xauth xdotool)
# Packages taken from bookworm-backports (lavapipe with VK_KHR_ray_query).
backports_pkgs=(mesa-vulkan-drivers)

as_root() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }

missing_pkgs() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}

mesa_version_ok() {
  # lavapipe from Mesa >= 25 exposes VK_KHR_ray_query.
  local v
  v=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
  [ -n "$v" ] && dpkg --compare-versions "$v" ge 25
}

add_backports() {
  # Derive the backports entry from the machine's own Debian sources (deb822 or one-line style).
  if grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/ 2>/dev/null; then
    return 0
  fi
  local uri=""
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then
    uri=$(awk '/^URIs:/{print $2; exit}' /etc/apt/sources.list.d/debian.sources)
  fi
  if [ -z "$uri" ] && [ -f /etc/apt/sources.list ]; then
    uri=$(awk '$1=="deb" && $3 ~ /^bookworm$/ {print $2; exit}' /etc/apt/sources.list)
  fi
  [ -n "$uri" ] || uri="http://deb.debian.org/debian"
  say "adding bookworm-backports from $uri"
  printf 'Types: deb\nURIs: %s\nSuites: bookworm-backports\nComponents: main\nSigned-By: /usr/share/keyrings/debian-archive-keyring.gpg\n' \
    "$uri" | as_root tee /etc/apt/sources.list.d/amrvk-backports.sources >/dev/null
  apt_updated=0
}

apt_updated=0
apt_update() { if [ "$apt_updated" = 0 ]; then as_root apt-get update -qq; apt_updated=1; fi; }

deps() {
  if ! command -v dpkg-query >/dev/null; then
    say "not a Debian system: install the packages listed in tools/run.sh by hand"; return 0
  fi
  local need
  mapfile -t need < <(missing_pkgs "${base_pkgs[@]}")
  if [ "${#need[@]}" -gt 0 ]; then
    say "installing ${need[*]}"
    apt_update
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}"
  fi
  if ! mesa_version_ok; then
    add_backports
    apt_update
    say "installing Mesa lavapipe from bookworm-backports"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
      -t bookworm-backports "${backports_pkgs[@]}"
  fi
}

build() {
  local jobs; jobs=$(nproc 2>/dev/null || echo 2)
  local werror=OFF; [ "${CI:-}" = true ] && werror=ON
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DAMRVK_WERROR="$werror" >/dev/null
  cmake --build build -j "$jobs"
}

export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/amrvk-xdg-$(id -u)}"
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"

cmd="${1:-}"
case "$cmd" in
  deps)  deps ;;
  build) deps; build ;;
  demo)
    deps; build
    mkdir -p out
    # Lit from one side (a warm sun and a dim blue sky) on a black background, multiple scattering.
    look=(--mode ms --background 0.004 0.004 0.008 --ambient 0.1 0.1 0.14 --light-dir 1 -1 2 5 4.5 3.8)
    enzo="${AMRVK_DATA_DIR:-../shared/data/amr}/enzo_tiny_cosmology/DD0018/DD0018"
    if [ -f "$enzo" ]; then
      say "demo: Enzo cosmology at redshift 1.15 (137,502 leaf cells on 5 levels), gas density, the cosmic web"
      ./build/bin/amrvk info "$enzo" --field Density
      ./build/bin/amrvk render "$enzo" --field Density --tf assets/tf/cosmic-web.json --tf-range 0 4 \
        --density-scale 0.06 "${look[@]}" --size 384x384 --spp 32 -o out/demo.png --json out/demo.json
    else
      say "demo: $enzo is absent; the bundled sample instead (synthetic turbulent cloud, 32768 cells, 8 levels)"
      ./build/bin/amrvk info assets/samples/cloud.cells
      ./build/bin/amrvk render assets/samples/cloud.cells --tf ramp --tf-range 0.3 2 --density-scale 3 --grid 64 \
        "${look[@]}" --size 256x256 --spp 16 -o out/demo.png --json out/demo.json
    fi
    say "demo image: $here/out/demo.png (statistics: $here/out/demo.json)"
    ;;
  test)
    deps; build
    jobs=$(nproc 2>/dev/null || echo 2)
    # CPU tests first (no Vulkan), then the GPU tests on lavapipe or any Vulkan device.
    ctest --test-dir build --output-on-failure -j "$jobs" -L cpu
    ctest --test-dir build --output-on-failure -j "$jobs" -LE cpu
    ;;
  *) echo "usage: tools/run.sh demo|test|build|deps" >&2; exit 2 ;;
esac
