#!/usr/bin/env bash
# Usage: function_lengths.sh SOURCE_DIR SCRATCH. No function of the product (src/, shaders/) is over
# 100 lines (issue 54; tools/function_lengths.py), and the check's power: it finds a 101-line
# function, a 101-line member defined in a class and a GLSL main of 101 lines, and passes 100.
set -u
src="$1"; dir="$2"
rm -rf "$dir"; mkdir -p "$dir"
fail=0
/usr/bin/python3 "$src/tools/function_lengths.py" "$src/src" "$src/shaders" || fail=1
body() { for i in $(seq "$1"); do echo "    x += $i;  // \"{\" in a string and a comment { do not count"; done; }
{ echo "int f(int x) {"; body 99; echo "}"; } >"$dir/ok.cpp"  # 101 lines from { to }: over
{ echo "struct S {"; echo "    int g(int x) const {"; body 99; echo "    }"; echo "};"; } >"$dir/member.h"
{ echo "void main() {"; body 99; echo "}"; } >"$dir/main.comp"
{ echo "int h(int x) {"; body 98; echo "}"; } >"$dir/fits.cpp"  # 100 lines: not over
out=$(/usr/bin/python3 "$src/tools/function_lengths.py" "$dir"); rc=$?
echo "$out"
[ "$rc" = 1 ] || { echo "FAIL: the check passed functions over 100 lines"; fail=1; }
echo "$out" | grep -q "ok.cpp:1: f is 101 lines" || { echo "FAIL: f not found"; fail=1; }
echo "$out" | grep -q "main.comp:1: main is 101 lines" || { echo "FAIL: main not found"; fail=1; }
echo "$out" | grep -q "member.h:2: g is 101 lines" || { echo "FAIL: the member g not found"; fail=1; }
echo "$out" | grep -q "fits.cpp" && { echo "FAIL: a 100-line function reported"; fail=1; }
echo "$out" | grep -q "4 functions, 3 over 100 lines" || { echo "FAIL: the count"; fail=1; }
exit $fail
