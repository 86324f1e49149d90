#!/usr/bin/env bash
# The GPU protocol of issue 31 (points 1-7) in one command: `tools/gpu-protocol.sh prepare DIR` copies
# this script to DIR/run.sh beside the carried amrvk and its libraries, for a lent GPU machine that
# cannot build amrvk (docs/benchmarks.md, "The GPU protocol in one command"). Every step runs under
# `timeout` within one shared time budget: a step may use a share of it (a 1/16, b 1/8 + 1/4, c 1/4,
# d 1/2, e 1/5, f 1/4), never more than is left, and g starts only with enough left; a step or
# render that no longer fits is skipped with a note. OUT/results.md is rewritten after every step,
# so a stopped run leaves what it measured; the JSON it read is kept under OUT/raw/, the pictures
# under OUT/images/, and the generated data is deleted at the end.
# Needs bash 5, coreutils and grep (nothing else installed); awk or python3 for the derived figures
# (without either they read n/a; the raw figures are still there).
# Usage: run.sh [OUT]        (default ./amrvk-protocol; OUT must not exist or be empty)
# Environment:
#   AMRVK_PROTOCOL_ICD     Vulkan ICD manifest (default: the NVIDIA one of the lent machines)
#   AMRVK_PROTOCOL_BUDGET  seconds for all steps (default 470: with `timeout`'s 5 s grace for a
#                          step that ignores SIGTERM, the run ends within 8 minutes)
#   AMRVK_PROTOCOL_SCALE   full (default: 10^8 cells at 1024^2) | small (10^6 at 128^2, for lavapipe)
#                          | tiny (the test's: 2x10^4 at 32^2)
#   AMRVK_PROTOCOL_STEPS   the steps to run, e.g. g (default abcdefg; a always runs, and d, e and f
#                          bring b along)
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
amrvk="$here/amrvk"
say() { printf 'run.sh: %s\n' "$*" >&2; }
die() { say "$*"; exit 1; }
[ -x "$amrvk" ] || die "$amrvk is missing: run tools/gpu-protocol.sh prepare DIR on the build machine"
(( BASH_VERSINFO[0] >= 5 )) || die "bash $BASH_VERSION is too old (needs 5: EPOCHREALTIME)"
[ $# -le 1 ] || die "usage: run.sh [OUT]"

icd="${AMRVK_PROTOCOL_ICD:-/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json}"
budget="${AMRVK_PROTOCOL_BUDGET:-470}"
scale="${AMRVK_PROTOCOL_SCALE:-full}"
steps="${AMRVK_PROTOCOL_STEPS:-abcdefg}"
if ! [[ "$budget" =~ ^[0-9]+$ ]] || (( budget == 0 )); then
  die "AMRVK_PROTOCOL_BUDGET: '$budget' is not a positive whole number of seconds"
fi
[[ "$steps" =~ ^[a-g]+$ ]] || die "AMRVK_PROTOCOL_STEPS: '$steps' is not a set of the letters a-g"
[[ "$steps" == *a* ]] || steps="a$steps"
[[ "$steps" == *[def]* && "$steps" != *b* ]] && steps+=b  # their data
# Per scale: the speed data set, the exactness check's, picture and spp, the 10^9 step's data set
# and the least budget it starts with, and the first-sample picture.
case "$scale" in
  full)  big=1e8 check=1e6 size=1024x1024 spp=24 huge=1e9 hugeMin=150 fsSize=64x64 checkOpts=() ;;
  small) big=1e6 check=1e5 size=128x128 spp=24 huge=1e7 hugeMin=30 fsSize=64x64 checkOpts=() ;;
  tiny)  big=2e4 check=2e4 size=32x32 spp=2 huge=1e5 hugeMin=5 fsSize=16x16 checkOpts=(--grid 16) ;;
  *) die "AMRVK_PROTOCOL_SCALE: '$scale' is not full, small or tiny" ;;
esac
width=${size%x*} height=${size#*x}

out="${1:-$PWD/amrvk-protocol}"
if [ -e "$out" ] || [ -L "$out" ]; then
  if [ -L "$out" ] || [ ! -d "$out" ]; then die "$out: exists and is not a directory"; fi
  [ -z "$(ls -A "$out")" ] || die "$out: not empty (give a new folder)"
fi
mkdir -p "$out/raw" "$out/data" "$out/images" || die "$out: cannot create it"
out="$(cd "$out" && pwd)"
cells() { local n=${1%e*} e=${1#*e}; while (( e-- > 0 )); do n=$((n * 10)); done; echo "$n"; }

# The carried libraries first; the machine's libstdc++/libgcc_s where they have every symbol version
# the carried files need (the lent machines' are newer than Debian 12's), else the copies in lib/compat.
compat=""
if [ -d "$here/lib/compat" ]; then
  compat="$here/lib/compat"
  for d in /usr/lib/x86_64-linux-gnu /lib/x86_64-linux-gnu /usr/lib64 /lib64; do
    if [ ! -f "$d/libstdc++.so.6" ] || [ ! -f "$d/libgcc_s.so.1" ]; then continue; fi
    newEnough=1
    while read -r v; do
      lib="$d/libstdc++.so.6"; [[ "$v" == GCC_* ]] && lib="$d/libgcc_s.so.1"
      grep -qaF -e "$v" "$lib" 2>/dev/null || { newEnough=0; break; }
    done <"$here/lib/compat/NEEDS"
    (( newEnough )) && compat="" && break
  done
fi
export LD_LIBRARY_PATH="$here/lib${compat:+:$compat}${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
for d in /usr/local/nvidia/lib64 /usr/local/nvidia/lib; do  # where the NVIDIA ICD's libraries live
  [ -d "$d" ] && [[ ":$LD_LIBRARY_PATH:" != *":$d:"* ]] && LD_LIBRARY_PATH+=":$d"
done
export VK_DRIVER_FILES="$icd"

# ---- figures: JSON (nlohmann's indented dump) into J[TAG:a.b.0.c]; awk or python3 for arithmetic
declare -A J
jsonLoad() {  # jsonLoad TAG FILE
  local tag=$1 line key val i p n path=() kind=() idx=()
  [ -s "$2" ] || return 1
  while IFS= read -r line || [ -n "$line" ]; do
    line=${line#"${line%%[![:space:]]*}"}; line=${line%,}
    [ -z "$line" ] && continue
    n=${#path[@]}
    if [ "$line" = "}" ] || [ "$line" = "]" ]; then
      (( n > 0 )) && unset "path[n-1]" "kind[n-1]" "idx[n-1]"
      continue
    fi
    if (( n == 0 )); then key="" val=$line
    elif [ "${kind[n-1]}" = a ]; then key=${idx[n-1]} val=$line; idx[n-1]=$((key + 1))
    else key=${line%%\": *} val=${line#*\": }; key=${key#\"}
    fi
    p=""; for ((i = 1; i < n; i++)); do p+="${path[i]}."; done
    case "$val" in
      "{") path+=("$key"); kind+=(o); idx+=(0); continue ;;
      "[") path+=("$key"); kind+=(a); idx+=(0); continue ;;
    esac
    if [[ "$val" == \"*\" ]]; then val=${val:1:-1}; val=${val//\\\"/\"}; val=${val//\\\\/\\}; fi
    J["$tag:$p$key"]=$val
  done <"$2"
}
get() { printf '%s' "${J[$1]-}"; }
isNum() { [[ "$1" =~ ^-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?$ ]]; }
awkBin=$(command -v awk || true)
pyBin=$(command -v python3 || true)
# calc FORMAT EXPR [X [Y]]: printf FORMAT of EXPR (awk syntax) with X and Y replaced by the values;
# n/a when a value is not a number or neither awk nor python3 is there.
calc() {
  local f=$1 e=$2
  if [ $# -ge 3 ]; then isNum "$3" || { printf 'n/a'; return; }; e=${e//X/($3)}; fi
  if [ $# -ge 4 ]; then isNum "$4" || { printf 'n/a'; return; }; e=${e//Y/($4)}; fi
  # In parentheses: a bare `X > Y` in awk's printf would write to a file named Y.
  if [ -n "$awkBin" ]; then "$awkBin" "BEGIN { printf \"$f\", ($e) }" 2>/dev/null || printf 'n/a'
  elif [ -n "$pyBin" ]; then "$pyBin" -c "print('$f' % ($e), end='')" 2>/dev/null || printf 'n/a'
  else printf 'n/a'; fi
}
div() { calc "$1" 'X / Y' "$2" "$3"; }  # div FORMAT A B
jf() { calc "$1" X "$(get "$2")"; }     # jf FORMAT KEY: one JSON figure
gb() { div '%.2f GB' "$1" 1e9; }
mega() { div '%.2f' "$1" 1e6; }
perPath() { div '%.2f' "$(get "$1:$2")" "$(get "$1:paths")"; }  # perPath TAG COUNTER

# ---- time: one budget shared by the steps
nowUs() { echo "${EPOCHREALTIME/./}"; }
t0=$(nowUs)
elapsed() { echo $(( ($(nowUs) - t0) / 1000000 )); }
left() { echo $(( budget - ($(nowUs) - t0) / 1000000 )); }
min() { echo $(( $1 < $2 ? $1 : $2 )); }
share() { min $(( budget * $1 / $2 )) "$(left)"; }  # share P Q: at most P/Q of the budget, and what is left
upTo() { local l; l=$(min $(( $1 - $(elapsed) )) "$(left)"); echo $(( l > 0 ? l : 0 )); }  # upTo END: seconds to END, and no more than is left

# ---- results: a title and a body per step, and the step log; rewritten whole after each step
declare -A T=([a]="a. Device and machine" [b]="b. Data" [c]="c. Exactness (point 1)"
  [d]="d. Speed on the $big-cell cloud (points 2 and 5)" [e]="e. \`--traversal auto\` against the best measured (point 4)"
  [f]="f. First sample at $big cells against host threads (point 6)" [g]="g. $huge cells (point 7)") S
for s in a b c d e f g; do
  if [[ "$steps" == *$s* ]]; then S[$s]="_Not reached: the run stopped before this step._"
  else S[$s]="_Not selected (AMRVK_PROTOCOL_STEPS=$steps)._"; fi
done
log=()      # step log rows
renders=()  # tags of every render's JSON (for the violation total)
state="running"
started=$(date -u '+%Y-%m-%d %H:%M UTC')
show() {  # a command as typed, with OUT for the output folder
  local s="" a
  for a in "$@"; do
    a=${a//"$out"/OUT}; [ "$a" = "$amrvk" ] && a=amrvk
    [[ "$a" =~ [[:space:]] ]] && a="'$a'"
    s+="${s:+ }$a"
  done
  printf '%s' "$s"
}
writeResults() {
  local f="$out/results.md" v=0 n=0 t r
  for t in "${renders[@]}"; do
    r=$(get "$t:majorantViolations"); isNum "$r" && v=$((v + r)) && n=$((n + 1))
  done
  {
    echo "# amrvk GPU protocol (issue 31, points 1-7)"
    echo
    echo "- State: $state; $(elapsed) s of the $budget s budget used (started $started); scale $scale ($big cells at $size, $spp spp)."
    echo "- Device: $(get dev:0.name), driver $(get dev:0.driver), Vulkan $(get dev:0.apiVersion) (\`amrvk devices --json\`)."
    echo "- amrvk: $(head -n 1 "$here/BUILD" 2>/dev/null); run from $here; ICD $icd."
    echo "- Majorant violations summed over the $n renders below: **$v** (step c has the exhaustive check)."
    echo "- Raw figures: raw/ (the JSON of every command, its stdout and stderr); pictures: images/."
    for s in a b c d e f g; do printf '\n## %s\n\n%s\n' "${T[$s]}" "${S[$s]}"; done
    echo
    echo "## Step log"
    echo
    echo "| step | command | status | seconds |"
    echo "|---|---|---|---|"
    for r in "${log[@]}"; do echo "$r"; done
  } >"$f.tmp" && mv -f "$f.tmp" "$f"
}

# run LIMIT NAME CMD...: CMD under `timeout LIMIT`, stdout and stderr to raw/NAME.out and .err; sets
# rc, us (microseconds) and status, and logs a row for step $step.
child=""
run() {
  local limit=$1 name=$2 t; shift 2
  (( limit >= 1 )) || limit=1  # timeout 0 would mean none
  t=$(nowUs)
  timeout -k 5 "$limit" "$@" >"$out/raw/$name.out" 2>"$out/raw/$name.err" &
  child=$!
  wait "$child"; rc=$?
  child=""
  us=$(( $(nowUs) - t ))
  case $rc in
    0) status="ok" ;;
    124|137) status="stopped at its limit of $limit s" ;;
    *) status="exit $rc: $(tail -n 1 "$out/raw/$name.err" | tr '|' '/')" ;;
  esac
  log+=("| $step | \`$(show "$@")\` | $status | $(div '%.1f' "$us" 1e6) |")
}
skip() { log+=("| $step | $1 | skipped: $2 | |"); }
stopped() {
  state="interrupted by a signal after $(elapsed) s"
  [ -n "$child" ] && kill -TERM "$child" 2>/dev/null && wait "$child"
  rm -rf "$out/data"
  S[b]+=$'\n'"- The generated data was deleted when the run was interrupted."
  writeResults; say "interrupted; partial results in $out/results.md"; exit 130
}
trap stopped INT TERM HUP

# ---- a. device, driver, machine
gpu=1
stepA() {
  step=a
  local lim i dev="" loader lib="" icdLib="" nv="" mem avail cpu os glibc disk
  lim=$(share 1 16); (( lim >= 1 )) || lim=1  # timeout 0 would mean none
  run "$lim" devices "$amrvk" devices --json
  mv -f "$out/raw/devices.out" "$out/raw/devices.json"
  if ! jsonLoad dev "$out/raw/devices.json" || [ "$(get dev:0.usable)" != true ]; then gpu=0; fi
  # The libraries the process really loads: the carried libvulkan.so.1 and the ICD's.
  LD_DEBUG=libs timeout "$lim" "$amrvk" devices >/dev/null 2>"$out/raw/ld-debug.txt"
  grep -F 'calling init:' "$out/raw/ld-debug.txt" | while read -r _ _ _ f; do echo "$f"; done \
    >"$out/raw/loaded-libraries.txt"
  rm -f "$out/raw/ld-debug.txt"
  loader=$(grep -m1 -F '/libvulkan.so.1' "$out/raw/loaded-libraries.txt")
  if [ -f "$icd" ]; then
    icdLib=$(grep -m1 -F '"library_path"' "$icd"); icdLib=${icdLib#*: }; icdLib=${icdLib%,}; icdLib=${icdLib//\"/}
    lib=$(grep -m1 -F "/${icdLib##*/}" "$out/raw/loaded-libraries.txt")
  fi
  if command -v nvidia-smi >/dev/null; then
    nv=$(timeout 20 nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader 2>&1 | head -n 2)
  fi
  mem=$(grep -m1 '^MemTotal' /proc/meminfo); mem=${mem//[!0-9]/}
  avail=$(grep -m1 '^MemAvailable' /proc/meminfo); avail=${avail//[!0-9]/}
  cpu=$(grep -m1 '^model name' /proc/cpuinfo); cpu=${cpu#*: }
  os=$(grep -m1 '^PRETTY_NAME=' /etc/os-release 2>/dev/null); os=${os#*=}; os=${os//\"/}
  glibc=$(getconf GNU_LIBC_VERSION 2>/dev/null)
  disk=$(df -Pk "$out" | { read -r _; read -r _ _ _ a _; echo "$a"; })
  for ((i = 0; i < 8; i++)); do
    [ -n "$(get "dev:$i.name")" ] || break
    dev+="| $i | $(get "dev:$i.name") | $(get "dev:$i.type") | $(get "dev:$i.driver") | $(get "dev:$i.apiVersion")"
    dev+=" | $(gb "$(get "dev:$i.deviceLocalBytes")") | $(get "dev:$i.rayQuery") | $(get "dev:$i.usable") $(get "dev:$i.rejectReason") |"$'\n'
  done
  S[a]="| index | device | type | driver | Vulkan | device-local | ray query | usable |
|---|---|---|---|---|---|---|---|
${dev:-| | no device listed (raw/devices.err) | | | | | | |
}
- Machine: $(nproc) cores (${cpu:-?}), $(div '%.1f' "$mem" 1048576) GiB memory ($(div '%.1f' "$avail" 1048576) GiB available), $(div '%.1f' "$disk" 1048576) GiB free where OUT is; ${os:-unknown OS}, ${glibc:-glibc ?}, kernel $(uname -r).
- nvidia-smi: ${nv:-not available}
- Vulkan loader loaded: ${loader:-not seen (raw/loaded-libraries.txt)}$([[ "$loader" == "$here/lib/"* ]] && echo " (the carried one)")
- ICD: $icd$([ -f "$icd" ] || echo ' (MISSING: set AMRVK_PROTOCOL_ICD)'); its library ${icdLib:-?} loaded from ${lib:-nowhere}
- libstdc++ and libgcc_s: $([ -n "$compat" ] && echo "the carried copies (lib/compat: the machine's are missing or too old)" || echo "the machine's")"
  (( gpu )) || S[a]+=$'\n'"- **No usable Vulkan device**: the rendering steps (d-g) are skipped."
}

# ---- b. data
bigData="$out/data/cloud$big" checkData="$out/data/cloud$check"
genData() {  # genData COUNT BASE LIMIT: one cloud, if the disk has room; sets genLine
  local need free name="gen-${2##*/}"
  need=$(( $(cells "$1") * 21 / 1024 + 1048576 ))  # 20 B/cell, and 1 GiB to spare (KiB)
  free=$(df -Pk "$out/data" | { read -r _; read -r _ _ _ a _; echo "$a"; })
  if (( free < need )); then
    skip "\`amrvk gen cloud --cells $1\`" "needs $((need / 1048576)) GiB of disk, $((free / 1048576)) GiB free"
    genLine="not generated: too little disk"; return 1
  fi
  run "$3" "$name" "$amrvk" gen cloud --cells "$1" --seed 1 -o "$2"
  genLine=$(tail -n 1 "$out/raw/$name.out"); genLine=${genLine//"$out"/OUT}
  [ "$rc" = 0 ] || { genLine="$status (last progress: $(tail -n 1 "$out/raw/$name.err"))"; return 1; }
}
stepB() {
  step=b
  genData "$check" "$checkData" "$(share 1 8)"
  S[b]="- \`amrvk gen cloud --cells $check --seed 1\`: $genLine"
  if [ "$big" != "$check" ]; then
    genData "$big" "$bigData" "$(share 1 4)"
    S[b]+=$'\n'"- \`amrvk gen cloud --cells $big --seed 1\`: $genLine"
  fi
}

# ---- c. exactness: the exhaustive majorant check (the renders' counters are summed at the top)
stepC() {
  step=c
  local lim i rows="" k
  lim=$(share 1 4)
  k="$lim s left for step c"; [ -f "$checkData.cells" ] || k="no cloud$check data (step b)"
  if (( lim < 5 )) || [ ! -f "$checkData.cells" ]; then
    skip "\`amrvk info cloud$check.cells --check-majorants --json\`" "$k"
    S[c]="_Skipped: $k._"; return
  fi
  run "$lim" check-majorants "$amrvk" info "$checkData.cells" --check-majorants --json "${checkOpts[@]}"
  mv -f "$out/raw/check-majorants.out" "$out/raw/check-majorants.json"
  jsonLoad chk "$out/raw/check-majorants.json"
  for ((i = 0; i < 32; i++)); do
    k="chk:majorantCheck.$i"
    [ -n "$(get "$k.boxes")" ] || break
    rows+="| $(get "$k.boxes")$([ -n "$(get "$k.builtForTf")" ] && echo " ($(get "$k.builtForTf"))") | $(get "$k.traversals") | $(get "$k.count") | $(get "$k.rangeFailures")"
    rows+=" | $(get "$k.worst") | $(jf '%.1f' "$k.seconds") | $(get "$k.ok") |"$'\n'
  done
  case $rc in
    0) k="every traversal's majorants hold" ;;
    1) k="**a majorant does not hold** (raw/check-majorants.err)" ;;
    *) k="no verdict: $status" ;;
  esac
  S[c]="\`$(show "$amrvk" info "$checkData.cells" --check-majorants --json "${checkOpts[@]}")\`$([ -n "$(get chk:leafCells)" ] && echo " ($(get chk:leafCells) cells)"): exit status $rc, $k. The majorant violation counters of every render are summed at the top.

| boxes | traversals | count | range failures | worst | s | ok |
|---|---|---|---|---|---|---|
$rows"
}

# ---- d. speed on the big cloud (points 2 and 5)
declare -A best bestLabel
# traversal/sampler[@grid][!off][%regen][~K]: grid-dda crosses empty blocks of macrocells in one
# step, so a finer grid's tighter majorants can pay for its steps (benchmarks section 23); !off:
# without sub-majorants (the default builds them where the TF makes macrocells loose: the paper's
# macrocell majorants beside them, section 27); %regen: --path-regeneration, which raised the
# lanes' use but not the paths/s on lavapipe (section 27); +sun: a directional light as well
# (--light-dir 1 0.5 2 2 2 2), so paths cast shadow rays; ^ubrm: those by unbiased ray marching
# (--transmittance ubrm), lower error at equal samples and 1.5-3.5x the time on lavapipe (section
# 28); :min: --control-extinction minorant (decomposition tracking, and residual ratio tracking for
# the shadow rays: fewer lookups where a macrocell is dense throughout, section 29); ~K: grid-bvh querying after K culled macrocells in a row instead of 32, the device's best K
# being unknown (section 26). Last, so they are the first skipped for time.
combos=(grid-dda/grid grid-dda/grid!off grid-dda/grid%regen grid-dda/ext-brick!off grid-dda/grid@256
  grid-bvh/grid abr/abr brick/grid kdtree/grid abr/ext-brick grid-dda/grid+sun grid-dda/grid+sun^ubrm
  grid-dda/grid:min grid-dda/grid+sun:min grid-bvh/grid~8 grid-bvh/grid~128)
common=(--size "$size" --spp "$spp" --samples-per-invocation 1 --mode ms --ambient 1 1 1 --backend sw)
renderRows() {  # renderRows TAG TF LABEL: sets speedRow and distRow from one render's JSON
  local t=$1 p k q
  p=$(get "$t:pathsPerSecond")
  speedRow="| $2 | $3 | $(mega "$p") | $(div '%.2f' "$p" "$((width * height))") | $(perPath "$t" densityLookups)"
  speedRow+=" | $(perPath "$t" nullCollisions) | $(perPath "$t" traversalSteps) | $(jf '%.3f' "$t:lookupLaneUtilization")"
  speedRow+=" | $(jf '%.2f' "$t:gpuNanosecondsPerLookup") | $(get "$t:majorantViolations") | $(jf '%.2f' "$t:firstSampleSeconds")"
  speedRow+=" | $(jf '%.2f' "$t:readSeconds") | $(jf '%.2f' "$t:structureBuildSeconds") | $(gb "$(get "$t:peakHostBytes")")"
  speedRow+=" | $(gb "$(get "$t:deviceMemoryPeakBytes")") |"
  distRow="| $2 | $3"
  for k in lookups nullCollisions; do
    for q in mean p50 p90 p99 p999 max; do distRow+=" | $(jf '%.4g' "$t:perPath.$k.$q")"; done
  done
  distRow+=" |"
}
# kShaders K: makes OUT/shaders-kK, amrvk's shaders with grid-bvh's K (culled macrocells stepped
# before a box query) a constant, for --shader-dir; fails (leaving nothing) when it cannot.
kShaders() {
  local d="$out/shaders-k$1" f
  f="$d/lib/traversal.glsl"
  if [ ! -d "$d" ]; then
    if ! "$amrvk" shaders --export "$d" >/dev/null 2>&1 || [ "$(grep -c 'culled < P\.scene\.gridBvhQueryAfter)' "$f")" != 1 ] ||
      ! sed -i "s/culled < P\.scene\.gridBvhQueryAfter)/culled < ${1}u)/" "$f"; then
      rm -rf "$d"
      return 1
    fi
  fi
}
stepD() {
  step=d
  local end lim c base k tf trav samp grid tag p last=0 speed="" dist="" note="" skipped="" why="" paper target
  end=$(( $(elapsed) + $(share 1 2) ))
  for c in "${combos[@]}"; do
    base=${c%~*} k=(); [[ $c == *~* ]] && k=(--shader-dir "$out/shaders-k${c#*~}")
    local extra=() suffix=""
    if [[ $base == *%regen ]]; then base=${base%\%regen} extra+=(--path-regeneration) suffix+="-regen"; fi
    if [[ $base == *!off ]]; then base=${base%!off} extra+=(--sub-majorants off) suffix+="-nosub"; fi
    if [[ $base == *:min ]]; then base=${base%:min} extra+=(--control-extinction minorant) suffix+="-min"; fi
    if [[ $base == *^ubrm ]]; then base=${base%^ubrm} extra+=(--transmittance ubrm) suffix+="-ubrm"; fi
    if [[ $base == *+sun ]]; then base=${base%+sun} extra+=(--light-dir 1 0.5 2 2 2 2) suffix="-sun$suffix"; fi
    if (( ${#k[@]} )) && ! kShaders "${c#*~}"; then
      note+="- $c: \`amrvk shaders --export\` or its edit failed."$'\n'; continue
    fi
    for tf in spiky foggy; do
      grid=(); [[ $base == *@* ]] && grid=(--grid "${base#*@}")
      trav=${base%%/*} samp=${base#*/} samp=${samp%@*} tag="d-$tf-${base/\//-}" tag=${tag/@/-grid}
      tag+="$suffix"
      (( ${#k[@]} )) && tag+="-k${c#*~}"
      lim=$(upTo "$end")
      if (( lim < 3 || lim < last )); then
        why="$lim s left for step d$( (( last > 0 )) && echo ", the last render took $last s")"
        skip "\`amrvk render cloud$big.cells --tf $tf --traversal $trav --sampler $samp ${grid[*]} ${extra[*]} ${k[*]//"$out"/OUT} ...\`" "$why"
        skipped+="${skipped:+, }$c $tf"
        continue
      fi
      run "$lim" "$tag" "$amrvk" render "$bigData.cells" "${common[@]}" --tf "$tf" --traversal "$trav" \
        --sampler "$samp" "${grid[@]}" "${extra[@]}" "${k[@]}" --json "$out/raw/$tag.json" -o "$out/images/$tag.png"
      last=$(( us / 1000000 + 1 ))
      if [ "$rc" != 0 ] || ! jsonLoad "$tag" "$out/raw/$tag.json"; then
        note+="- $c $tf: $status."$'\n'; continue
      fi
      renders+=("$tag")
      renderRows "$tag" "$tf" "$c"; speed+="$speedRow"$'\n'; dist+="$distRow"$'\n'
      p=$(get "$tag:pathsPerSecond")
      (( ${#k[@]} )) && continue  # a shader experiment: not a configuration amrvk ships
      [ -n "$suffix" ] && continue  # an A/B row: the configuration amrvk renders by default is the other
      if isNum "$p" && { [ -z "${best[$tf]-}" ] || [ "$(calc '%d' 'X > Y' "$p" "${best[$tf]}")" = 1 ]; }; then
        best[$tf]=$p bestLabel[$tf]=$c
      fi
    done
  done
  S[d]="\`$(show "$amrvk" render "$bigData.cells" "${common[@]}" --tf TF --traversal T --sampler S --json ...)\`; fps = paths/s / ($width x $height) at 1 spp per frame$([ "$scale" = full ] || echo " (**at this scale not comparable with the paper**)").
The paper's RTX 4090 on its 102M-cell cloud at 1024^2, 1 spp per frame: spiky 14-22 fps, foggy 37-62 fps, 2.2-2.5 GB on the device. Targets: spiky >= 22 fps, foggy >= 62 fps.

| TF | traversal/sampler | M paths/s | fps | lookups / path | null / path | steps / path | lookup lane use | GPU ns / lookup | violations | first sample s | read s | build s | host peak | device peak |
|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|
${speed}
grid-bvh/grid~K: grid-bvh querying its BVH after K culled macrocells in a row instead of 32 (\`--shader-dir OUT/shaders-kK\`, amrvk's shaders with K a constant; docs/benchmarks.md section 26).

Per path (lookups, then null collisions): mean, p50, p90, p99, p99.9 (quantiles from amrvk's histogram: exact below 8, 4 bins per octave above), max.

| TF | traversal/sampler | mean | p50 | p90 | p99 | p999 | max | null: mean | p50 | p90 | p99 | p999 | max |
|---|---|---|---|---|---|---|---|---|---|---|---|---|---|
${dist}
${note}${skipped:+- Skipped for time: $skipped ($why).
}"
  for tf in spiky foggy; do
    [ -n "${best[$tf]-}" ] || continue
    paper="14-22" target=22; [ "$tf" = foggy ] && paper="37-62" target=62
    S[d]+="- Fastest $tf: ${bestLabel[$tf]}, **$(div '%.1f' "${best[$tf]}" "$((width * height))") fps** (paper: $paper; target >= $target)."$'\n'
  done
}

# ---- e. --traversal auto against the best measured (point 4)
stepE() {
  step=e
  local end lim tf tag rows="" pick p ratio
  end=$(( $(elapsed) + $(share 1 5) ))
  for tf in spiky foggy; do
    tag="e-$tf-auto"
    lim=$(upTo "$end")
    if (( lim < 5 )); then
      skip "\`amrvk render cloud$big.cells --tf $tf --traversal auto ...\`" "$lim s left for step e"
      rows+="| $tf | skipped: $lim s left for step e | | | | | |"$'\n'; continue
    fi
    run "$lim" "$tag" "$amrvk" render "$bigData.cells" "${common[@]}" --tf "$tf" --traversal auto \
      --json "$out/raw/$tag.json" -o "$out/images/$tag.png"
    if [ "$rc" != 0 ] || ! jsonLoad "$tag" "$out/raw/$tag.json"; then
      rows+="| $tf | $status | | | | | |"$'\n'; continue
    fi
    renders+=("$tag")
    pick=$(grep -m1 -F -e '--traversal auto picked' "$out/raw/$tag.err"); pick=${pick#*picked }
    p=$(get "$tag:pathsPerSecond")
    ratio=$(div '%.2f' "$p" "${best[$tf]:-none}")
    rows+="| $tf | ${pick:-?} | $(mega "$p") | ${bestLabel[$tf]:-none measured} | $(mega "${best[$tf]:-none}") | **$ratio**"
    rows+=" | $(jf '%.2f' "$tag:firstSampleSeconds") |"$'\n'
  done
  S[e]="\`$(show "$amrvk" render "$bigData.cells" "${common[@]}" --tf TF --traversal auto --json ...)\`. Every combination estimates the same image with the same per-path variance, so the efficiency ratio is the ratio of paths/s: the pick's over the fastest of step d. Target >= 0.8.

| TF | pick (amrvk's note) | pick M paths/s | best measured (d) | best M paths/s | efficiency ratio | first sample s (probes included) |
|---|---|---|---|---|---|---|
$rows"
}

# ---- f. first sample against host threads (point 6)
stepF() {
  step=f
  local end lim n ns=() tag rows="" lastN=0 lastS=0 need
  end=$(( $(elapsed) + $(share 1 4) ))
  for ((n = $(nproc); n > 1; n /= 2)); do ns+=("$n"); done
  ns+=(1)
  for n in "${ns[@]}"; do
    tag="f-threads-$n"
    lim=$(upTo "$end")
    need=$(( lastN > 0 ? lastS * lastN / n : 3 ))  # as if the time grew with 1/threads
    if (( lim < need )); then
      skip "\`AMRVK_THREADS=$n amrvk render cloud$big.cells --size $fsSize --spp 1 ...\`" \
        "$lim s left for step f, about $need s needed"
      rows+="| $n | skipped: $lim s left for step f, about $need s needed | | | | | |"$'\n'; continue
    fi
    run "$lim" "$tag" env AMRVK_THREADS="$n" "$amrvk" render "$bigData.cells" --size "$fsSize" --spp 1 \
      --json "$out/raw/$tag.json" -o "$out/images/$tag.png"
    lastN=$n lastS=$(( us / 1000000 + 1 ))
    if [ "$rc" != 0 ] || ! jsonLoad "$tag" "$out/raw/$tag.json"; then
      rows+="| $n | $status | | | | | |"$'\n'; continue
    fi
    renders+=("$tag")
    rows+="| $n | $(get "$tag:threads") | **$(jf '%.2f' "$tag:firstSampleSeconds")** | $(jf '%.2f' "$tag:readSeconds")"
    rows+=" | $(jf '%.2f' "$tag:structureBuildSeconds") | $(jf '%.2f' "$tag:structureBuildSecondsPer.bricks")"
    rows+=" | $(jf '%.2f' "$tag:structureBuildSecondsPer.macrocells") |"$'\n'
  done
  S[f]="\`AMRVK_THREADS=N $(show "$amrvk" render "$bigData.cells" --size "$fsSize" --spp 1 --json ...)\` (the default structures); target <= 4 s on 16 cores.

| AMRVK_THREADS | threads (JSON) | first sample s | read s | build s | bricks s | macrocells s |
|---|---|---|---|---|---|---|
$rows"
}

# ---- g. 10^9 cells (point 7)
stepG() {
  step=g
  local l n availKb need genLim c tag="g-render" hugeData="$out/data/cloud$huge"
  rm -f "$bigData.cells" "$bigData.scalars"  # d-f are done with it
  l=$(left)
  if (( l < hugeMin )); then
    skip "\`amrvk gen cloud --cells $huge\`, render" "$l s left, it needs $hugeMin"
    S[g]="_Skipped: $l s of the budget left, the step needs at least $hugeMin s (run it alone: AMRVK_PROTOCOL_STEPS=g)._"
    return
  fi
  n=$(cells "$huge")
  availKb=$(grep -m1 '^MemAvailable' /proc/meminfo); availKb=${availKb//[!0-9]/}
  need=$(( n * 30 / 1024 ))  # the render's host peak was about 26 B/cell at 10^8
  if (( availKb < need )); then
    skip "\`amrvk gen cloud --cells $huge\`" "needs about $((need / 1048576)) GiB of memory, $((availKb / 1048576)) GiB available"
    S[g]="_Skipped: too little memory._"; return
  fi
  genLim=$(( l * 2 / 3 ))  # the rest for the render
  if ! genData "$huge" "$hugeData" "$genLim"; then
    S[g]="- \`amrvk gen cloud --cells $huge --seed 1\` within $genLim s: $genLine."
    rm -f "$hugeData".*; return
  fi
  S[g]="- \`amrvk gen cloud --cells $huge --seed 1\`: $genLine"$'\n'
  run "$(left)" "$tag" "$amrvk" render "$hugeData.cells" --size "$fsSize" --spp 1 --json "$out/raw/$tag.json" \
    -o "$out/images/$tag.png"
  if [ "$rc" = 0 ] && jsonLoad "$tag" "$out/raw/$tag.json"; then
    renders+=("$tag")
    c=${genLine#*: }; c=${c%% cells*}  # "amrvk gen cloud: N cells, ..."
    S[g]+="- \`$(show "$amrvk" render "$hugeData.cells" --size "$fsSize" --spp 1 --json ...)\`: $c cells; host peak $(gb "$(get "$tag:peakHostBytes")") = **$(div '%.1f' "$(get "$tag:peakHostBytes")" "$c") B/cell** (target <= 20), device peak $(gb "$(get "$tag:deviceMemoryPeakBytes")") = **$(div '%.2f' "$(get "$tag:deviceMemoryPeakBytes")" "$c") B/cell** (target <= 5), first sample **$(jf '%.1f' "$tag:firstSampleSeconds") s** (target <= 60; read $(jf '%.1f' "$tag:readSeconds") s, build $(jf '%.1f' "$tag:structureBuildSeconds") s)."
  else
    S[g]+="- render: $status"
  fi
  rm -f "$hugeData".*
}

say "budget $budget s, scale $scale, steps $steps; results in $out/results.md"
writeResults
for s in a b c d e f g; do
  [[ "$steps" == *$s* ]] || continue
  step=$s
  if [[ "$s" == [defg] ]] && (( ! gpu )); then
    skip "step $s" "no usable Vulkan device (step a)"
    S[$s]="_Skipped: no usable Vulkan device (step a)._"
  elif [ "$s" != a ] && (( $(left) <= 0 )); then
    skip "step $s" "the budget is spent"
    S[$s]="_Skipped: the $budget s budget was spent._"
  elif [[ "$s" == [def] ]] && [ ! -f "$bigData.cells" ]; then
    skip "step $s" "no cloud$big data (step b)"
    S[$s]="_Skipped: the cloud$big data is missing (step b)._"
  else
    "step${s^^}"
  fi
  writeResults
done
rm -f "$bigData".* "$checkData".*
rmdir "$out/data" 2>/dev/null
[[ "$steps" == *b* ]] && S[b]+=$'\n'"- The generated data was deleted at the end of the run."
state="finished"
[[ "${log[*]}" == *"| skipped: "* || "${log[*]}" == *"stopped at its limit"* ]] &&
  state="finished; some steps were stopped or skipped (the step log says why)"
writeResults
say "done in $(elapsed) s: $out/results.md"
