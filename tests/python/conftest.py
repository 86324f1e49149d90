"""Shared by the Python module's tests (ctest runs them: python.pytest). The module comes from the
build tree (PYTHONPATH=build/python, set by ctest), the real data from ../shared/data/amr or
AMRVK_DATA_DIR; tests that need yt or a data set skip with a message where it is absent."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE = pathlib.Path(__file__).resolve().parents[2]
DATA = pathlib.Path(os.environ.get("AMRVK_DATA_DIR", SOURCE.parent / "shared" / "data" / "amr"))
SAMPLE = SOURCE / "assets" / "samples" / "cloud.cells"
ENZO = DATA / "enzo_tiny_cosmology" / "DD0018" / "DD0018"

os.environ.setdefault("XDG_RUNTIME_DIR", "/tmp")


def amrvk_binary():
    build = pathlib.Path(os.environ.get("AMRVK_BINARY_DIR", SOURCE / "build"))
    return build / "bin" / "amrvk"


def need(path):
    if not pathlib.Path(path).exists():
        pytest.skip(f"{path} is absent (set AMRVK_DATA_DIR)")
    return pathlib.Path(path)


def run_cli(*args, check=True):
    """amrvk's command line; returns (exit status, stderr)."""
    binary = amrvk_binary()
    if not binary.exists():
        pytest.skip(f"{binary} is not built")
    p = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True)
    if check and p.returncode != 0:
        raise AssertionError(f"amrvk {' '.join(map(str, args))}: {p.stderr}")
    return p.returncode, p.stderr


def write_cells(base, cells, values):
    """An ExaBrick .cells/.scalars pair (cells: (x, y, z, level) rows)."""
    np.asarray(cells, dtype="<i4").tofile(f"{base}.cells")
    np.asarray(values, dtype="<f4").tofile(f"{base}.scalars")


def tile_z_test(a, var_a, b, var_b, tile=8, alpha=1e-4):
    """Tiles whose means differ by more than a Sidak-corrected z bound: the tile means' variances
    are the sums of their pixels' variances of the mean over the tile's pixel count squared."""
    from statistics import NormalDist

    h, w = a.shape[:2]
    tiles = [(y, x) for y in range(0, h, tile) for x in range(0, w, tile)]
    z = NormalDist().inv_cdf(1 - (1 - (1 - alpha) ** (1 / (3 * len(tiles)))) / 2)
    bad = 0
    for y, x in tiles:
        for c in range(3):
            sa, sb = a[y:y + tile, x:x + tile, c], b[y:y + tile, x:x + tile, c]
            n = sa.size
            va = var_a[y:y + tile, x:x + tile, c].sum() / n**2
            vb = var_b[y:y + tile, x:x + tile, c].sum() / n**2
            if abs(sa.mean() - sb.mean()) > z * np.sqrt(va + vb) + 1e-7:
                bad += 1
    return bad


def global_z(a, var_a, b, var_b):
    """Per channel, the difference of the two images' means over its standard error."""
    n = a[..., 0].size
    return [float((a[..., c].mean() - b[..., c].mean()) / np.sqrt((var_a[..., c].sum() + var_b[..., c].sum()) / n**2))
            for c in range(3)]


@pytest.fixture(scope="session")
def amrvk():
    import amrvk as module

    return module


@pytest.fixture(scope="session")
def yt():
    module = pytest.importorskip("yt", reason="yt is not installed (Debian: python3-yt)")
    module.set_log_level(40)
    return module
