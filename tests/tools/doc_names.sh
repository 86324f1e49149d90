#!/usr/bin/env bash
# Usage: doc_names.sh SOURCE_DIR SCRATCH. Every code name docs/architecture.md cites exists
# (issue 54; tools/doc_names.py), and the check's power: a document citing a made-up qualified
# name, file pair and source file fails, naming each, while real ones pass.
set -u
src="$1"; dir="$2"
git -C "$src" rev-parse --git-dir >/dev/null 2>&1 || { echo "SKIP: $src is not a git checkout (the check lists tracked files)"; exit 77; }
rm -rf "$dir"; mkdir -p "$dir"
fail=0
/usr/bin/python3 "$src/tools/doc_names.py" "$src" "$src/docs/architecture.md" || fail=1
cat >"$dir/doc.md" <<'MD'
Real: `scene::Volume`, `render::Renderer::accumulateStaged`, `auto_select.*`, `tools/run.sh`.
Made up: `scene::Volume::warpDrive`, `teleporter.*`, `src/render/teleporter.cpp`; not checked: `--spp`.
MD
out=$(/usr/bin/python3 "$src/tools/doc_names.py" "$src" "$dir/doc.md"); rc=$?
echo "$out"
[ "$rc" = 1 ] || { echo "FAIL: made-up names passed"; fail=1; }
for name in 'scene::Volume::warpDrive' 'teleporter.\*' 'src/render/teleporter.cpp'; do
  echo "$out" | grep -q "doc.md:2: \`$name\` names nothing" || { echo "FAIL: $name not reported"; fail=1; }
done
echo "$out" | grep -q "7 names checked, 3 missing" || { echo "FAIL: the count"; fail=1; }
exit $fail
