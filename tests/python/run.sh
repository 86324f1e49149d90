#!/bin/bash
# The Python module's tests (ctest python.pytest): run.sh PYTHON BUILD_DIR SOURCE_DIR [TESTS...]
# (TESTS: pytest paths relative to SOURCE_DIR; default all of tests/python).
# Skips (77) with the reason where the interpreter lacks pytest or numpy; everything else fails.
set -u
py=$1 build=$2 src=$3
shift 3
for m in pytest numpy; do
  if ! "$py" -c "import $m" 2>/dev/null; then
    echo "skip: $py cannot import $m (apt install python3-$m)"; exit 77
  fi
done
export PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}" AMRVK_BINARY_DIR="$build"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}"
cd "$src" && exec "$py" -m pytest -q -p no:cacheprovider "${@:-tests/python}"
