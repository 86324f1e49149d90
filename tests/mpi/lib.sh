# Shared by the MPI test scripts (sourced after they set $amrvk, $mpirun and $dir, and fail=0).
# Open MPI as root needs its run-as-root settings; more ranks than cores needs --oversubscribe;
# -q leaves amrvk's one error line alone on stderr (no launcher banners).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpi=("$mpirun" -q --oversubscribe)
check() { if ! "$@"; then echo "FAIL: $*"; fail=1; fi; }
# pfm_compare A B MAX_REL: the largest relative difference of two PFM images is at most MAX_REL
# (pixels below 1e-6 in both compare absolutely); prints it. pfm_differ A B MIN_REL: at least MIN_REL.
pfm_diff() {
  /usr/bin/python3 - "$1" "$2" "$(dirname "${BASH_SOURCE[0]}")" <<'PY'
import sys
import numpy as np
sys.path.insert(0, sys.argv[3])
from zcompare import pfm
a, b = pfm(sys.argv[1]), pfm(sys.argv[2])
assert a.shape == b.shape, (a.shape, b.shape)
print(float((np.abs(a - b) / np.maximum(np.maximum(np.abs(a), np.abs(b)), 1e-6)).max()))
PY
}
pfm_compare() {
  local d; d=$(pfm_diff "$1" "$2") || { echo "FAIL: cannot compare $1 $2"; fail=1; return; }
  if /usr/bin/python3 -c "import sys; sys.exit(0 if $d <= $3 else 1)"; then echo "ok: $2 vs $1: max rel $d <= $3"
  else echo "FAIL: $2 vs $1: max rel $d > $3"; fail=1; fi
}
pfm_differ() {
  local d; d=$(pfm_diff "$1" "$2") || { echo "FAIL: cannot compare $1 $2"; fail=1; return; }
  if /usr/bin/python3 -c "import sys; sys.exit(0 if $d >= $3 else 1)"; then echo "ok: $2 vs $1 differ: max rel $d >= $3"
  else echo "FAIL: $2 vs $1 should differ: max rel $d < $3"; fail=1; fi
}
