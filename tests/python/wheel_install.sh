#!/bin/bash
# Usage: wheel_install.sh PYTHON AMRVK SOURCE_DIR WORK_DIR (ctest python.wheel; issue 54, point 5).
# Python installed the way Python users install it: `PYTHON -m build --wheel --no-isolation` builds
# the module through pyproject.toml (scikit-build-core, the project's own CMake, in WORK_DIR/build,
# kept between runs), the wheel goes into a fresh venv (with the system's site packages for numpy),
# and that venv's python, outside the checkout and with no PYTHONPATH, imports amrvk from the venv
# and renders the bundled cloud: the same image as `AMRVK render` of the same description.
# Skips (77) naming the package where the interpreter lacks build, scikit-build-core, pybind11,
# venv or numpy; everything else fails.
set -euo pipefail
py=$1 amrvk=$2 src=$3 work=$4
for m in build:python3-build scikit_build_core:python3-scikit-build-core pybind11:python3-pybind11 \
         ensurepip:python3-venv numpy:python3-numpy; do
  if ! "$py" -c "import ${m%%:*}" 2>/dev/null; then
    echo "skip: $py cannot import ${m%%:*} (apt install ${m##*:})"; exit 77
  fi
done
mkdir -p "$work"
rm -rf "$work/dist" "$work/venv" "$work/out"
env -u PYTHONPATH "$py" -m build --wheel --no-isolation -C build-dir="$work/build" -o "$work/dist" "$src" >"$work/build.log" 2>&1 ||
  { tail -30 "$work/build.log"; echo "FAIL: the wheel did not build (log: $work/build.log)"; exit 1; }
wheels=("$work"/dist/amrvk-*.whl)
[ "${#wheels[@]}" = 1 ] && [ -f "${wheels[0]}" ] || { echo "FAIL: expected one wheel in $work/dist: ${wheels[*]}"; exit 1; }
# The wheel holds the package's Python files and the compiled module, nothing from the build tree.
"$py" - "${wheels[0]}" <<'PYEOF'
import sys, zipfile
names = set(zipfile.ZipFile(sys.argv[1]).namelist())
need = {"amrvk/__init__.py", "amrvk/widget.py", "amrvk/yt_bridge.py"}
assert need <= names, f"missing from the wheel: {sorted(need - names)}"
assert any(n.startswith("amrvk/_amrvk.") and n.endswith(".so") for n in names), "no compiled module in the wheel"
stray = [n for n in names if not (n.startswith("amrvk/") or ".dist-info/" in n)]
assert not stray, f"the wheel holds files outside the package: {stray}"
PYEOF
"$py" -m venv --system-site-packages "$work/venv"
"$work/venv/bin/python" -m pip install -q --no-index --no-deps --no-cache-dir "${wheels[0]}"
mkdir -p "$work/out"
"$amrvk" render "$src/assets/samples/cloud.cells" --scale linear --tf ramp --tf-range 0.3 2 --background 1 1 1 \
  --size 32x24 --density-scale 3 --grid 16 --mode ss --seed 3 --light-dir 1 -1 2 3 3 3 --spp 8 \
  -o "$work/out/cli.pfm" 2>"$work/out/cli.log" || { cat "$work/out/cli.log"; exit 1; }
cd "$work/out"
env -u PYTHONPATH XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}" "$work/venv/bin/python" - "$work/venv" "$src" <<'PYEOF'
import pathlib, sys
import numpy as np
import amrvk
venv, src = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2])
for m in (amrvk, amrvk._amrvk):
    assert venv in pathlib.Path(m.__file__).resolve().parents, f"{m.__name__} came from {m.__file__}, not the venv"
import re
from importlib.metadata import version
declared = re.search(r"project\(amrvk VERSION ([0-9.]+)", (src / "CMakeLists.txt").read_text()).group(1)
assert version("amrvk") == declared, f"installed as {version('amrvk')}, CMakeLists.txt says {declared}"
r = amrvk.Renderer(amrvk.Volume(str(src / "assets/samples/cloud.cells"), scale="linear"),
                   tf=amrvk.TransferFunction.preset("ramp", 0.3, 2.0), width=32, height=24, density_scale=3.0,
                   grid="16", background=(1, 1, 1), mode="ss", seed=3, quiet=True,
                   lights=[amrvk.Light.directional([1, -1, 2], [3, 3, 3])])
image = r.render(spp=8)
with open("cli.pfm", "rb") as f:
    assert f.readline().strip() == b"PF"
    w, h = map(int, f.readline().split())
    scale = float(f.readline())
    cli = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4").reshape(h, w, 3)[::-1]
assert image.shape == (24, 32, 4) and (w, h) == (32, 24)
err = np.max(np.abs(cli - image[..., :3]) / np.maximum(np.abs(cli), 1e-3))
assert err < 1e-5, f"the wheel's image differs from amrvk render's by {err} (relative)"
assert float(image[..., :3].std()) > 1e-3, "a flat image"
r.save("wheel.png")
assert pathlib.Path("wheel.png").stat().st_size > 100
print(f"wheel {amrvk.__file__}: renders what amrvk render renders (max relative difference {err:.1e})")
PYEOF
