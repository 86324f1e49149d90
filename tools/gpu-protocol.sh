#!/usr/bin/env bash
# The GPU protocol in one command (issue 31, point 8; docs/benchmarks.md): `prepare DIR`, run on
# this Debian 12 machine, writes a folder that runs issue 31's measurements (points 1-7) on a lent
# GPU machine that cannot build amrvk (Ubuntu 24.04, no Vulkan loader; shared/design/gpu-machine.md):
# the Release amrvk (its own build in build-protocol/: without MPI, whose libraries would not fit),
# stripped; every library `ldd` lists but glibc's, Debian's Vulkan loader and libglvnd (the NVIDIA
# ICD needs libGLdispatch) in DIR/lib; libstdc++ and libgcc_s in DIR/lib/compat, used there only
# where the machine's lack a symbol version they need; DIR/run.sh (tools/gpu-protocol-run.sh) and a
# README. DIR stays under 40 MiB. Written into DIR.tmp-XXXXXX and renamed, so a failure leaves no
# half-written DIR; a non-empty DIR that this script did not make, or one holding anything it did
# not write (results put there since), is refused.
# Usage: tools/gpu-protocol.sh prepare DIR   then on the GPU machine: bash DIR/run.sh [OUT]
# Environment: AMRVK_PROTOCOL_BUILD, another build folder (default build-protocol/ in the checkout);
# AMRVK_PROTOCOL_BIN, an amrvk to carry instead of building one (the test's, with MPI);
# AMRVK_PROTOCOL_MAX_MIB, the size limit (default 40).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
die() { printf 'gpu-protocol.sh: %s\n' "$*" >&2; exit 1; }
if [ $# != 2 ] || [ "$1" != prepare ]; then die "usage: tools/gpu-protocol.sh prepare DIR"; fi
dir="$2"
marker=".amrvk-gpu-protocol"
maxMib="${AMRVK_PROTOCOL_MAX_MIB:-40}"
[[ "$maxMib" =~ ^[0-9]+$ ]] || die "AMRVK_PROTOCOL_MAX_MIB: '$maxMib' is not a whole number"

# DIR: new, empty, or made by this script and holding only what it wrote (results written into it
# since are never deleted); never a symlink, also when named with trailing slashes. Its parent must
# exist.
[ -n "$dir" ] || die "DIR: empty name"
[[ "$dir" == -* ]] && die "DIR '$dir': looks like an option (for a folder of that name: ./$dir)"
while [[ "$dir" == */ && "$dir" != / ]]; do dir="${dir%/}"; done
[ "$dir" = / ] && die "DIR /: the root folder, not a folder for the protocol"
[ -L "$dir" ] && die "$dir: is a symlink"
if [ -e "$dir" ]; then
  [ -d "$dir" ] || die "$dir: exists and is not a directory"
  [ -z "$(ls -A "$dir")" ] || [ -f "$dir/$marker" ] || die "$dir: not empty and not made by gpu-protocol.sh prepare"
  extra=()
  while IFS= read -r -d '' entry; do
    case "${entry##*/}" in amrvk | run.sh | README.md | BUILD | lib | "$marker") ;; *) extra+=("${entry##*/}") ;; esac
  done < <(find "$dir" -mindepth 1 -maxdepth 1 -print0)
  ((${#extra[@]} == 0)) || die "$dir: holds ${extra[*]:0:3}$( ((${#extra[@]} > 3)) && echo " ...") that prepare did not write: refused, it would be deleted (move it, or name another folder)"
fi
parent="$(dirname "$dir")"
[ -d "$parent" ] || die "$parent: no such directory"

# The binary: a Release build of the amrvk target only, without MPI; cmake rebuilds what is stale.
commit="$(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)"
[ -z "$(git -C "$here" status --porcelain --untracked-files=no 2>/dev/null)" ] || commit+=" with uncommitted changes"
if [ -n "${AMRVK_PROTOCOL_BIN:-}" ]; then
  bin="$AMRVK_PROTOCOL_BIN"
  if [ ! -f "$bin" ] || [ ! -x "$bin" ]; then die "AMRVK_PROTOCOL_BIN: $bin is not an executable file"; fi
  origin="$bin (AMRVK_PROTOCOL_BIN; checkout at commit $commit)"
else
  build="${AMRVK_PROTOCOL_BUILD:-$here/build-protocol}"
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  mkdir -p "$build"
  buildLog="$build/gpu-protocol-build.log"
  echo "gpu-protocol.sh: building amrvk in $build (log: $buildLog)" >&2
  { cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release -DAMRVK_MPI=OFF -DAMRVK_BUILD_TESTS=OFF \
      -DAMRVK_PYTHON=OFF "${launcher[@]}" &&
    cmake --build "$build" -j "$(nproc)" --target amrvk; } >"$buildLog" 2>&1 ||
    die "building amrvk failed: see $buildLog (missing packages: tools/run.sh deps)"
  bin="$build/bin/amrvk"
  [ -x "$bin" ] || die "$bin: not built"
  cxx="$(grep -m1 '^CMAKE_CXX_COMPILER:' "$build/CMakeCache.txt" | cut -d= -f2)"
  origin="commit $commit, Release, no MPI, $cxx $("$cxx" -dumpfullversion 2>/dev/null)"
fi

tmp="$(mktemp -d "$dir.tmp-XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
chmod 755 "$tmp"
mkdir "$tmp/lib" "$tmp/lib/compat"
strip -o "$tmp/amrvk" "$bin" || die "strip $bin failed"

# Libraries: ldd of the binary and of libglvnd, by soname; glibc's stay behind (the machine's 2.39
# runs Debian 12's 2.36 binaries).
glibc=" ld-linux-x86-64.so.2 libc.so.6 libm.so.6 libpthread.so.0 libdl.so.2 librt.so.1 libresolv.so.2 libutil.so.1 "
glibc+="libanl.so.1 libnsl.so.1 libmvec.so.1 libBrokenLocale.so.1 libthread_db.so.1 libc_malloc_debug.so.0 "
glvnd=(libGLdispatch.so.0 libGLX.so.0 libEGL.so.1 libOpenGL.so.0 libGL.so.1)
ldcache="$(/sbin/ldconfig -p)"
libPath() {  # the x86-64 file the dynamic linker finds for a soname
  local line
  line="$(grep -m1 -F "	$1 (libc6,x86-64" <<<"$ldcache")" || die "$1: not installed (Debian package: apt-get install $2)"
  echo "${line##* => }"
}
declare -A carried
for s in "${glvnd[@]}"; do carried[$s]="$(libPath "$s" "libglvnd0 libglx0 libegl1 libopengl0 libgl1")"; done
carried[libvulkan.so.1]="$(libPath libvulkan.so.1 libvulkan1)"
lddOut="$(env -i ldd "$bin" "${carried[@]}" 2>&1)"
grep -q 'not found' <<<"$lddOut" && die "ldd: $(grep -m1 'not found' <<<"$lddOut" | tr -s ' \t' ' ')"
while read -r name arrow path _; do
  if [ "$arrow" != "=>" ] || [[ "$glibc" == *" $name "* ]]; then continue; fi
  carried[$name]="$path"
done <<<"$lddOut"
for name in "${!carried[@]}"; do
  case "$name" in
    libstdc++.so.6|libgcc_s.so.1) to="$tmp/lib/compat/$name" ;;
    *) to="$tmp/lib/$name" ;;
  esac
  cp -L "${carried[$name]}" "$to" || die "cannot copy ${carried[$name]}"
done
# The libstdc++/libgcc_s symbol versions the carried files need: run.sh takes the machine's copies
# only where they have them all.
for f in "$tmp/amrvk" "$tmp"/lib/*.so*; do objdump -p "$f" || die "objdump -p $f failed"; done |
  grep -oE '\b(GLIBCXX|CXXABI|GCC)_[0-9][0-9.]*\b' | sort -uV >"$tmp/lib/compat/NEEDS"

# The carried binary must load with the carried libraries and the machine's glibc alone.
check="$(env -i LD_LIBRARY_PATH="$tmp/lib:$tmp/lib/compat" ldd "$tmp/amrvk")"
while read -r name arrow path _; do
  [ "$arrow" = "=>" ] || continue
  [[ "$glibc" == *" $name "* ]] || [[ "$path" == "$tmp/lib/"* ]] || die "$name: resolves to $path, not DIR/lib"
done <<<"$check"
env -i LD_LIBRARY_PATH="$tmp/lib:$tmp/lib/compat" "$tmp/amrvk" --help >/dev/null || die "the carried amrvk does not start"

cp "$here/tools/gpu-protocol-run.sh" "$tmp/run.sh" || die "cannot copy tools/gpu-protocol-run.sh"
chmod 755 "$tmp/run.sh" "$tmp/amrvk"
echo "$origin, prepared $(date -u '+%Y-%m-%d %H:%M UTC') on Debian $(cat /etc/debian_version 2>/dev/null || echo ?)" >"$tmp/BUILD"
# Which Debian package and version each library came from (two dpkg-query calls: they are slow).
declare -A pkgOf verOf
reals=()
for name in "${!carried[@]}"; do r="$(readlink -f "${carried[$name]}")"; reals+=("$r" "${r#/usr}"); done
while IFS=' ' read -r pkg path; do pkgOf[/usr${path#/usr}]="${pkg%%:*}"; done \
  < <(dpkg-query -S "${reals[@]}" 2>/dev/null || true)
while IFS=' ' read -r pkg ver; do verOf[$pkg]="$ver"; done \
  < <(dpkg-query -W -f '${Package} ${Version}\n' "${pkgOf[@]}" 2>/dev/null || true)
libList=""
for name in $(printf '%s\n' "${!carried[@]}" | sort); do
  pkg="${pkgOf[$(readlink -f "${carried[$name]}")]:-?}"
  where=lib; [ -f "$tmp/lib/compat/$name" ] && where=lib/compat
  libList+="- $where/$name: Debian $pkg ${verOf[$pkg]:-?}"$'\n'
done
echo "amrvk GPU protocol folder (tools/gpu-protocol.sh prepare)" >"$tmp/$marker"
mib() { awk -v b="$1" 'BEGIN { printf "%.1f MiB", b / 1048576 }'; }
sizeText="$(mib "$(( $(du -sb "$tmp" | cut -f1) + 4096 ))")"  # with the README
cat >"$tmp/README.md" <<EOF
# amrvk for a GPU machine that cannot build it

Made by \`tools/gpu-protocol.sh prepare\` ($(head -n 1 "$tmp/BUILD")); $sizeText.
It needs bash 5, coreutils and grep there, and a Vulkan ICD (default: the NVIDIA one at
/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json); nothing is installed.

\`\`\`sh
bash run.sh OUT      # issue 31's protocol in at most 8 minutes: OUT/results.md, OUT/raw/*.json
\`\`\`
run.sh measures, each step under \`timeout\` within one budget (later steps skipped with a note when
it is spent; OUT/results.md is rewritten after every step): a) devices, driver and machine, and
which Vulkan loader and ICD were loaded; b) 10^6- and 10^8-cell clouds (\`amrvk gen\`); c) the
exhaustive majorant check and every render's violation counter; d) speed of seven structure
combinations x the spiky and foggy TFs at 1024^2 (1 spp per frame) beside the paper's RTX 4090,
then grid-bvh querying after 8 and 128 culled macrocells instead of 32 (exported shaders);
e) \`--traversal auto\` against the best of d; f) the first sample against AMRVK_THREADS; g) 10^9
cells (host and device bytes per cell, first sample) when at least 150 s remain.
Environment: AMRVK_PROTOCOL_ICD (another ICD manifest), AMRVK_PROTOCOL_BUDGET (seconds, default
470), AMRVK_PROTOCOL_SCALE (full, small or tiny), AMRVK_PROTOCOL_STEPS (e.g. \`g\`: only the 10^9 step).
By hand: \`LD_LIBRARY_PATH=\$PWD/lib VK_DRIVER_FILES=ICD ./amrvk devices\`.

## Contents
- amrvk: the Release build, stripped (shaders embedded).
- run.sh: tools/gpu-protocol-run.sh of the same checkout.
- lib/: every library ldd lists but glibc's, Debian's Vulkan loader (libvulkan.so.1) and libglvnd
  (the NVIDIA ICD, libGLX_nvidia.so.0, needs libGLdispatch.so.0, which the machine lacks).
- lib/compat/: Debian's libstdc++ and libgcc_s, put on the library path only where the machine's
  lack one of the symbol versions in lib/compat/NEEDS (the lent machines' are newer).

$libList
EOF

size=$(du -sb "$tmp" | cut -f1)
(( size < maxMib << 20 )) || die "$dir would take $(mib "$size"), over the $maxMib MiB limit (AMRVK_PROTOCOL_MAX_MIB)"

# Into place: a DIR made earlier by this script is replaced only now.
if [ -e "$dir" ]; then
  old="$(mktemp -d "$dir.old-XXXXXX")"
  mv -T "$dir" "$old/dir"
  mv -T "$tmp" "$dir"
  rm -rf "$old"
else
  mv -T "$tmp" "$dir"
fi
trap - EXIT
echo "gpu-protocol.sh: wrote $dir ($sizeText): copy it to the GPU machine and run bash $dir/run.sh OUT"
