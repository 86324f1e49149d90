#!/usr/bin/env bash
# amrvk set-up and entry points. Usage: tools/run.sh demo|test|build|deps|sanitize|fuzz [SECONDS]
#   demo  installs what is missing, builds the amrvk binary (Release, build/), renders the Enzo
#         cosmology data beside the checkout (or the bundled sample where it is absent) to out/demo.png
#   test  installs what is missing, builds, runs every test (ctest)
#   build installs what is missing and builds everything (tests and the Python module too)
#   deps  only installs what is missing (Debian 12; root or sudo)
#   sanitize  ASan + UBSan build (gcc) into build-asan/, runs the CPU tests (ctest -L cpu)
#   fuzz [SECONDS]  libFuzzer targets (clang) into build-fuzz/, runs each for SECONDS (default 60);
#         non-zero when any target finds a crash, leak or timeout (docs/fuzzing.md)
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
           libimgui-dev xvfb xauth xdotool libfreetype-dev fonts-dejavu-core
           python3-dev pybind11-dev python3-numpy python3-pytest python3-hypothesis python3-yt python3-tqdm
           python3-nbformat python3-nbconvert python3-ipykernel python3-ipywidgets  # docs/python.md as a notebook
           python3-build python3-pybind11 python3-venv  # the wheel (pyproject.toml) and its venv test
           openmpi-bin libopenmpi-dev
           ffmpeg)  # render -o movie.mp4 runs it; its tests skip without it
# What `demo` needs, a subset of the above: the compiler, CMake and the libraries the amrvk binary
# links (no tests, Python, MPI, ffmpeg or X tools): 251 packages (863 MB installed) in the
# dependency closure against 767 (2.1 GB) for the whole list (apt-cache depends --recurse,
# Debian 12), so a fresh machine fetches and unpacks about a third.
demo_pkgs=(cmake g++ make pkg-config libvulkan-dev glslc glslang-tools spirv-tools libglfw3-dev libglm-dev
           libhdf5-dev libpng-dev zlib1g-dev nlohmann-json3-dev libcli11-dev libtinyexr-dev libtbb-dev
           libshaderc-dev libimgui-dev libfreetype-dev fonts-dejavu-core)
# Only for `fuzz`: clang with libFuzzer and the sanitizer runtimes (libclang_rt.fuzzer-x86_64.a
# is in libclang-rt-14-dev).
fuzz_pkgs=(clang-14 libclang-rt-14-dev)
# Packages taken from bookworm-backports: lavapipe with VK_KHR_ray_query, and (not for `demo`)
# scikit-build-core, pyproject.toml's build back-end (bookworm has none).
backports_pkgs=(mesa-vulkan-drivers)
backports_test_pkgs=(python3-scikit-build-core)

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

# deps [demo]: installs what is missing of base_pkgs (or of demo_pkgs), and Mesa from backports.
deps() {
  if ! command -v dpkg-query >/dev/null; then
    say "not a Debian system: install the packages listed in tools/run.sh by hand"; return 0
  fi
  local need
  if [ "${1:-}" = demo ]; then
    mapfile -t need < <(missing_pkgs "${demo_pkgs[@]}")
  else
    mapfile -t need < <(missing_pkgs "${base_pkgs[@]}")
  fi
  if [ "${#need[@]}" -gt 0 ]; then
    say "installing ${need[*]}"
    apt_update
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}"
  fi
  local from_backports=()
  mesa_version_ok || from_backports+=("${backports_pkgs[@]}")
  [ "${1:-}" = demo ] || mapfile -t -O "${#from_backports[@]}" from_backports < <(missing_pkgs "${backports_test_pkgs[@]}")
  if [ "${#from_backports[@]}" -gt 0 ]; then
    add_backports
    apt_update
    say "installing ${from_backports[*]} from bookworm-backports"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
      -t bookworm-backports "${from_backports[@]}"
  fi
}

# build [TARGET...]: configures build/ and builds the targets named (default: everything, tests
# and the Python module included). Naming targets configures without the tests (the demo's
# packages have no GoogleTest); building everything configures with them again.
build() {
  local jobs; jobs=$(nproc 2>/dev/null || echo 2)
  local werror=OFF; [ "${CI:-}" = true ] && werror=ON
  local tests=ON; [ "$#" -gt 0 ] && tests=OFF
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DAMRVK_WERROR="$werror" -DAMRVK_BUILD_TESTS="$tests" >/dev/null
  local targets=(); [ "$#" -gt 0 ] && targets=(--target "$@")
  cmake --build build -j "$jobs" "${targets[@]}"
  install_python_path
}

# `import amrvk` for Debian's python3: a .pth file naming build/python in its site directory
# (/usr/local/lib/python3.X/dist-packages, the place Debian keeps for local additions). Written only
# where the module was built; an amrvk.pth that names another checkout is replaced, with a note.
install_python_path() {
  [ -d build/python/amrvk ] && ls build/python/amrvk/_amrvk*.so >/dev/null 2>&1 || return 0
  local site; site=$(/usr/bin/python3 -c 'import sys; print(f"/usr/local/lib/python3.{sys.version_info[1]}/dist-packages")')
  local pth="$site/amrvk.pth" want="$here/build/python"
  if [ "$(cat "$pth" 2>/dev/null)" != "$want" ]; then
    [ -f "$pth" ] && say "python: $pth named $(cat "$pth"); now $want"
    as_root mkdir -p "$site" && printf '%s\n' "$want" | as_root tee "$pth" >/dev/null
    say "python: /usr/bin/python3 imports amrvk from $want ($pth)"
  fi
}

# seed_test_costs BUILD_DIR: a fresh build has no test times, so ctest starts the tests in the order
# they are declared and a long one started last runs alone at the end; seeded with the times of a
# full run on the 2-core machine (tests/ctest_costs.txt), it starts the longest first. A build that
# has run its tests keeps its own times.
seed_test_costs() {
  local costs="$1/Testing/Temporary/CTestCostData.txt"
  [ -f "$costs" ] || { mkdir -p "$(dirname "$costs")" && cp tests/ctest_costs.txt "$costs"; }
}

# ASan + UBSan build of everything the CPU tests run (amrvk_tests_cpu and the amrvk binary the CLI
# tests call); GPU tests stay on the normal build. Leak checking stays on: the CPU tests create no
# Vulkan instance, and tools/lsan.supp names what the system libraries keep (none so far).
sanitize() {
  local jobs; jobs=$(nproc 2>/dev/null || echo 2)
  local flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
  local t0=$SECONDS
  # -g1 (line tables only): the reports' file:line frames as with -g, for about 15% less compile
  # time (session.cpp: 26.6 s against 31.5 s) and half the object size.
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
  cmake --build build-asan -j "$jobs" --target amrvk_tests_cpu amrvk
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  export LSAN_OPTIONS="suppressions=$here/tools/lsan.supp:print_suppressions=0"
  # Tests that fail under the sanitizers because of known bugs in src/, each listed in
  # tests/fuzz/findings.md; remove an entry when its bug is fixed.
  local skip=()
  local exclude=(); [ "${#skip[@]}" -gt 0 ] && exclude=(-E "$(IFS='|'; echo "${skip[*]}")")
  # cli.check_majorants checks the bundled sample and Enzo only here (its memory safety; Release
  # checks every data set). Longest first, as in `test` (seed_test_costs): unseeded, it started
  # last and ran alone for over two minutes of the 311 s.
  seed_test_costs build-asan
  AMRVK_SANITIZER_RUN=1 ctest --test-dir build-asan --output-on-failure -j "$jobs" -L cpu "${exclude[@]}"
  sanitize_python
  say "sanitize: build and tests took $((SECONDS - t0)) s"
}

# The Python module under ASan + UBSan: the sanitizer runtimes preloaded into Debian's python3
# (which is not built with them), leak checking off (the interpreter keeps its objects at exit),
# the pytest tests of the module (bad arrays, closed renderers, threads, yt input and renders
# through lavapipe, hypothesis). Not the notebook (docs/python.md run through a kernel: the calls
# the other tests make, minutes under ASan) nor the yt comparisons of units and RAMSES, which run
# the amrvk binary only and are among the CPU tests above already, nor the setting table's three
# front ends (about 25 runs of the amrvk binary; its C++ is in the CPU tests' SettingTable.*).
sanitize_python() {
  local targets; targets=$(cmake --build build-asan --target help)
  [[ $targets == *" _amrvk"* ]] || { say "sanitize: no Python module to test"; return 0; }
  cmake --build build-asan -j "$(nproc 2>/dev/null || echo 2)" --target _amrvk
  local rt; rt="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libubsan.so)"
  ASAN_OPTIONS="detect_leaks=0:abort_on_error=0:strict_string_checks=1:check_initialization_order=1" \
    LD_PRELOAD="$rt" timeout 1800 bash tests/python/run.sh /usr/bin/python3 "$here/build-asan" "$here" tests/python \
    --ignore=tests/python/test_notebook.py --ignore=tests/python/test_units_yt.py --ignore=tests/python/test_ramses_yt.py \
    --ignore=tests/python/test_setting_table.py
}

fuzz_deps() {
  command -v dpkg-query >/dev/null || return 0
  local need
  mapfile -t need < <(missing_pkgs "${fuzz_pkgs[@]}")
  if [ "${#need[@]}" -gt 0 ]; then
    say "installing ${need[*]}"
    apt_update
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}"
  fi
}

# Largest input per target (bytes): the AMReX seed holds the real level-0 FAB data (156 KB), the
# Chombo seed the real 403 KB file; the others stay small so mutations stay fast.
fuzz_max_len() {
  case "$1" in
    chombo) echo 524288 ;;
    amrex) echo 262144 ;;
    enzo) echo 131072 ;;
    raw) echo 65536 ;;
    *) echo 16384 ;;
  esac
}

# One line for a replayed finding's report: the error and the first frame in amrvk's sources.
fuzz_signature() {
  local err frame
  err=$(grep -Eo -m1 '(SUMMARY: [A-Za-z]+: [a-z-]+|runtime error: [a-z ]*[a-z]|==amrvk-fuzz== .*: uncaught .*)' "$1" \
        | sed -E 's/^SUMMARY: //' || true)
  frame=$(grep -Eo -m1 ' in [^ ]+.* (/[^ ]*)?/(src/[a-z]+|tests/fuzz)/[a-z0-9_]+\.(cpp|h):[0-9]+' "$1" \
          | grep -Eo '(src/[a-z]+|tests/fuzz)/[a-z0-9_]+\.(cpp|h):[0-9]+' || true)
  [ -n "$err" ] || err="no report on replay (flaky or needs the fork's state)"
  echo "${err} at ${frame:-?}"
}

# fuzz_scratch_left DIR WHO: fails, saying how many, when DIR holds scratch directories of the
# fuzz targets (amrvk-fuzz-*, tests/fuzz/fuzz_common.h), which each input must remove itself.
fuzz_scratch_left() {
  local n; n=$(find "$1" -mindepth 1 -maxdepth 1 -name 'amrvk-fuzz-*' | wc -l)
  [ "$n" = 0 ] && return 0
  say "fuzz: $2 left $n scratch directories behind in $1 (tests/fuzz/fuzz_common.h removes each input's)"
  return 1
}

# Builds the libFuzzer targets (clang, ASan + UBSan) into build-fuzz/, writes the seed corpora
# (generated + cut from the data beside the checkout) into build-fuzz/corpus/<target>/, which
# grows from run to run, and runs every target (or those in AMRVK_FUZZ_TARGETS) for $1 seconds.
# Findings (crash-*, leak-*, timeout-*, oom-*) go to build-fuzz/artifacts/<target>/; the logs to
# build-fuzz/logs/<target>.log. Non-zero exit when any target found something.
fuzz() {
  local seconds="$1"
  local jobs; jobs=$(nproc 2>/dev/null || echo 2)
  local bd=build-fuzz data="${AMRVK_DATA_DIR:-$here/../shared/data/amr}"
  cmake -S . -B "$bd" -DAMRVK_FUZZ=ON -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 >/dev/null
  cmake --build "$bd" -j "$jobs"
  export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  export LSAN_OPTIONS="suppressions=$here/tools/lsan.supp:print_suppressions=0"
  local targets; read -r -a targets <<<"${AMRVK_FUZZ_TARGETS:-$(tr '\n' ' ' <"$bd/fuzz_targets.txt")}"
  local t failed=() summary=()
  # Every process below makes its scratch directories (tests/fuzz/fuzz_common.h) under a folder of
  # this run's, in $TMPDIR (e.g. /dev/shm) or /tmp, removed at the end: an input that kills its
  # process (a finding) leaves its directory there, not in /tmp.
  local scratch; scratch=$(mktemp -d "${TMPDIR:-/tmp}/amrvk-fuzz-run-XXXXXX")
  trap "rm -rf '$scratch'" EXIT  # expanded now: \$scratch is local
  for t in "${targets[@]}"; do mkdir -p "$bd/corpus/$t"; done
  TMPDIR="$scratch" "$bd/bin/amrvk_fuzz_seeds" "$bd/corpus" "$data" "$here" >/dev/null
  fuzz_scratch_left "$scratch" "the seed generator" || failed+=(seeds)
  mkdir -p "$bd/logs"
  for t in "${targets[@]}"; do
    local art="$bd/artifacts/$t" log="$bd/logs/$t.log" dict=()
    mkdir -p "$art"
    local TMPDIR="$scratch/$t"
    mkdir -p "$TMPDIR"
    export TMPDIR
    [ -f "tests/fuzz/dict/$t.dict" ] && dict=(-dict="tests/fuzz/dict/$t.dict")
    : >"$log.start"
    # The committed inputs of earlier findings (tests/fuzz/findings.md) first: each must now give
    # success or an amrvk::Error.
    local r regressed=0
    for r in tests/fuzz/regressions/"$t"/*; do
      [ -f "$r" ] || continue
      if ! "$bd/bin/fuzz_$t" -timeout=10 -rss_limit_mb=2048 "$r" >"$bd/logs/replay.txt" 2>&1; then
        regressed=$((regressed + 1))
        echo "    regression $r: $(fuzz_signature "$bd/logs/replay.txt")" >&2
      fi
    done
    # A replay that found nothing leaves no scratch directory.
    [ "$regressed" -gt 0 ] || fuzz_scratch_left "$TMPDIR" "$t's replay" || regressed=$((regressed + 1))
    if [ "$seconds" -le 0 ]; then  # fuzz 0: build, seeds and the replay only
      summary+=("$(printf '%-12s replay only, %s regressions' "$t" "$regressed")")
      [ "$regressed" -gt 0 ] && failed+=("$t")
      continue
    fi
    say "fuzz $t: ${seconds} s"
    # -fork=1 with -ignore_*: a finding does not end the run, so one run lists every distinct
    # crash; each input that crashed, leaked, hung (> 10 s) or exceeded 2 GB stays in $art.
    # chombo_bytes runs in one process (stops at its first finding): in a 220 s fork-mode run its
    # 403 KB seed was not taken up (465 edges; docs/fuzzing.md).
    local mode=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
    [ "$t" = chombo_bytes ] && mode=()
    "$bd/bin/fuzz_$t" "$bd/corpus/$t" "${dict[@]}" -max_len="$(fuzz_max_len "$t")" \
      -timeout=10 -rss_limit_mb=2048 -max_total_time="$seconds" "${mode[@]}" \
      -artifact_prefix="$art/" -print_final_stats=1 >"$log" 2>&1 || true
    local execs found
    # Fork mode's status lines "#N: cov: ..." count the executions of all jobs.
    local last secs
    last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
    if [ "${#mode[@]}" = 0 ]; then  # one process: its final stats
      last="#$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -Eo '[0-9]+$' || echo 0) time: $seconds"
    fi
    execs=$(echo "$last" | grep -Eo '^#[0-9]+' | tr -d '#' || true)
    secs=$(echo "$last" | grep -Eo ' time: [0-9]+' | grep -Eo '[0-9]+' | head -1 || true)
    [ -n "$secs" ] && [ "$secs" -gt 0 ] || secs=$seconds
    # Findings: new crash-, leak-, timeout- and oom- inputs. slow-unit- files (an input over 10 s
    # that still finished) are listed but do not fail; an empty oom-da39a3ee... is fork mode's
    # placeholder when a child ran out of memory between inputs (replays clean), likewise.
    found=$(find "$art" -type f -newer "$log.start" -size +0 \( -name 'crash-*' -o -name 'leak-*' \
      -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
    local slow; slow=$(find "$art" -type f -newer "$log.start" -name 'slow-unit-*' ! -name '*.txt' | wc -l)
    # Without a finding, no process of the run may have left a scratch directory; with one, the
    # inputs that killed their process left theirs (removed with $scratch).
    local leaked=0
    [ "$found" -gt 0 ] || fuzz_scratch_left "$TMPDIR" "$t" || leaked=1
    summary+=("$(printf '%-12s %10s execs %6s exec/s  %s new findings, %s slow inputs, %s regressions%s' \
      "$t" "${execs:-0}" "$(( ${execs:-0} / secs ))" "$found" "$slow" "$regressed" \
      "$([ "$leaked" = 0 ] || echo ', scratch directories left')")")
    [ "$found" -gt 0 ] || [ "$regressed" -gt 0 ] || [ "$leaked" -gt 0 ] && failed+=("$t")
    if [ "$found" -gt 0 ] || [ "$slow" -gt 0 ]; then
      # Fork mode keeps the children's reports to itself: replay each new artifact once, keep its
      # report beside it (<artifact>.txt) and print each distinct (error, first amrvk frame).
      local a
      for a in $(find "$art" -type f ! -name '*.txt' -size +0 -newer "$log.start"); do
        "$bd/bin/fuzz_$t" -timeout=10 -rss_limit_mb=2048 "$a" >"$a.txt" 2>&1 || true
        fuzz_signature "$a.txt"
      done | sort | uniq -c | sed 's/^/    /' >&2
    fi
  done
  say "fuzz summary (${seconds} s per target; findings in $bd/artifacts/<target>/, logs in $bd/logs/):"
  printf '  %s\n' "${summary[@]}" >&2
  if [ "${#failed[@]}" -gt 0 ]; then
    say "fuzz: findings in ${failed[*]} (reproduce: $bd/bin/fuzz_TARGET FILE; tests/fuzz/findings.md)"
    return 1
  fi
}

export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp/amrvk-xdg-$(id -u)}"
mkdir -p "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"

cmd="${1:-}"
case "$cmd" in
  deps)  deps ;;
  build) deps; build ;;
  demo)
    # Only what the binary it runs needs (the tests and the Python module: `build` and `test`).
    deps demo; build amrvk
    mkdir -p out
    # Lit from one side (a warm sun and a dim blue sky) on a black background, multiple scattering.
    look=(--mode ms --background 0.004 0.004 0.008 --ambient 0.1 0.1 0.14 --light-dir 1 -1 2 5 4.5 3.8)
    enzo="${AMRVK_DATA_DIR:-../shared/data/amr}/enzo_tiny_cosmology/DD0018/DD0018"
    if [ -f "$enzo" ]; then
      say "demo: Enzo cosmology at redshift 1.15 (137,502 leaf cells on 5 levels), gas density, the cosmic web"
      ./build/bin/amrvk info "$enzo" --field Density
      ./build/bin/amrvk render "$enzo" --field Density --scale linear --tf assets/tf/cosmic-web.json --tf-range 0 4 \
        --density-scale 0.06 "${look[@]}" --size 384x384 --spp 32 -o out/demo.png --json out/demo.json
    else
      say "demo: $enzo is absent; the bundled sample instead (synthetic turbulent cloud, 32768 cells, 8 levels)"
      ./build/bin/amrvk info assets/samples/cloud.cells
      ./build/bin/amrvk render assets/samples/cloud.cells --scale linear --tf ramp --tf-range 0.3 2 --density-scale 3 --grid 64 \
        "${look[@]}" --size 256x256 --spp 16 -o out/demo.png --json out/demo.json
    fi
    say "demo image: $here/out/demo.png (statistics: $here/out/demo.json)"
    ;;
  test)
    deps; build
    jobs=$(nproc 2>/dev/null || echo 2)
    seed_test_costs build
    # CPU tests first (no Vulkan), then the GPU tests on lavapipe or any Vulkan device.
    ctest --test-dir build --output-on-failure -j "$jobs" -L cpu
    ctest --test-dir build --output-on-failure -j "$jobs" -LE cpu
    ;;
  sanitize) deps; sanitize ;;
  fuzz) deps; fuzz_deps; fuzz "${2:-60}" ;;
  *) echo "usage: tools/run.sh demo|test|build|deps|sanitize|fuzz [SECONDS]" >&2; exit 2 ;;
esac
