#!/usr/bin/env bash
# Usage: widget_notebook.sh BUILD_DIR SOURCE_DIR SCRATCH. The Jupyter widget in a real browser
# (issue 52, points 11-15): Debian's Notebook 6.4 with its ipywidgets, opened in headless Chromium
# driven by puppeteer-core (widget_notebook.js). Exits 77 (skipped) where chromium, node or
# puppeteer-core is missing: puppeteer-core comes from npm, not Debian, so CI skips this and a
# developer runs it (docs/python.md section 9 says how). PUPPETEER_DIR names the folder whose
# node_modules holds puppeteer-core (default: npm's global root).
set -u
build=$(cd "$1" && pwd); src=$(cd "$2" && pwd); dir=$3
command -v chromium >/dev/null || { echo "SKIP: no chromium (apt install chromium)"; exit 77; }
command -v node >/dev/null || { echo "SKIP: no node"; exit 77; }
modules="${PUPPETEER_DIR:-$(npm root -g 2>/dev/null)/..}/node_modules"
[ -d "$modules/puppeteer-core" ] || { echo "SKIP: no puppeteer-core in $modules (npm install puppeteer-core; PUPPETEER_DIR=...)"; exit 77; }
/usr/bin/python3 -c "import notebook, ipywidgets" 2>/dev/null || { echo "SKIP: no python3-notebook or python3-ipywidgets"; exit 77; }
rm -rf "$dir"; mkdir -p "$dir/home"
token=$(head -c 12 /dev/urandom | od -An -tx1 | tr -d ' \n')
port=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
# The notebook the page runs: a widget on the bundled sample, and a cell that reports the state.
/usr/bin/python3 - "$dir/widget.ipynb" "$src" <<'PY'
import nbformat, sys
src = sys.argv[2]
nb = nbformat.v4.new_notebook()
nb.cells = [nbformat.v4.new_code_cell(
    "import amrvk, json\n"
    f"r = amrvk.Renderer(amrvk.Volume({src + '/assets/samples/cloud.cells'!r}, scale='linear'), width=96, height=64,\n"
    "                   density_scale=3.0, tf_range=(0.3, 2.0), grid='16', quiet=True, seed=7)\n"
    "first = r.camera\n"
    "w = amrvk.Widget(r, spp=16, batch=4)\n"
    "w"),
    nbformat.v4.new_code_cell(
    "w.wait(120)\n"
    "print('STATE ' + json.dumps({'mode': r.mode, 'spp': r.spp, 'azimuth': w.azimuth.value,\n"
    "      'eye': list(r.camera.eye), 'expected_eye': list(first.orbit(w.azimuth.value).eye),\n"
    "      'status': w.status.value}))")]
nbformat.write(nb, sys.argv[1])
PY
export PYTHONPATH="$build/python" XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-/tmp}" HOME="$dir/home" JUPYTER_RUNTIME_DIR="$dir/home/runtime"
/usr/bin/python3 -m notebook --no-browser --ip=127.0.0.1 --port="$port" --NotebookApp.token="$token" \
  --notebook-dir="$dir" --allow-root >"$dir/server.log" 2>&1 & server=$!
trap 'kill $server 2>/dev/null; wait $server 2>/dev/null' EXIT
for _ in $(seq 300); do grep -q "is running at" "$dir/server.log" && break; sleep 0.1; done
NODE_PATH="$modules" node "$src/tests/browser/widget_notebook.js" "http://127.0.0.1:$port/notebooks/widget.ipynb?token=$token" "$dir"
