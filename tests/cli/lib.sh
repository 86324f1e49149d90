# Shared by the CLI test scripts (sourced after they set $amrvk and $dir and fail=0).
# check CMD...: CMD must succeed. expect FRAGMENT -- ARGS...: `amrvk ARGS` must exit with 1 and
# print exactly one line on stderr containing FRAGMENT.
check() { if ! "$@"; then echo "FAIL: $*"; fail=1; fi; }
expect() {
  local frag="$1"; shift 2
  "$amrvk" "$@" >"$dir/expect.out" 2>"$dir/expect.err"; local rc=$?
  local lines; lines=$(wc -l <"$dir/expect.err")
  if [ "$rc" != 1 ] || [ "$lines" != 1 ] || ! grep -qF -- "$frag" "$dir/expect.err"; then
    echo "FAIL: amrvk $* -> rc=$rc, stderr($lines lines): $(cat "$dir/expect.err")"; fail=1
  else
    echo "ok: amrvk $* -> $(cat "$dir/expect.err")"
  fi
}
# Counted cases (the hostile campaigns report how many they ran): expect1, check1, and ok ARGS...
# (`amrvk ARGS` must exit 0), each one case.
cases=0
expect1() { cases=$((cases + 1)); expect "$@"; }
check1() { cases=$((cases + 1)); check "$@"; }
ok() {
  cases=$((cases + 1))
  if "$amrvk" "$@" >"$dir/ok.out" 2>"$dir/ok.err"; then echo "ok: amrvk $*"; else
    echo "FAIL: amrvk $* -> rc=$?: $(tail -2 "$dir/ok.err")"; fail=1; fi
}
