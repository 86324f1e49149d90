"""amrvk's native RAMSES reader against yt 4.1 (an independent reader) on the 3-D galaxy output
(8 domain files): the same leaf cells (position and size, every one), the same density in every
cell, and the same leaves per level, minimum, maximum and sum in `amrvk info --json`. yt 4.1
cannot read the 2-D RAMSES outputs; their oracle numbers are in tests/cpu/ramses_reader_test.cpp.
Only the amrvk binary is used (`amrvk convert` writes the cells and values, `amrvk info --json`
reports the summary), so this runs without a Vulkan device."""
import json
import subprocess

import numpy as np
import pytest

from conftest import DATA, amrvk_binary, need, run_cli

GALAXY = DATA / "ramses_galaxy_3d" / "output_00010"


@pytest.fixture(scope="module")
def yt_leaves():
    """yt's leaves: integer lower corners in finest-cell units, widths, density (code units)."""
    yt = pytest.importorskip("yt")
    need(GALAXY)
    ds = yt.load(str(GALAXY / "info_00010.txt"))
    ad = ds.all_data()
    pos = np.stack([ad["index", a].to("code_length").d for a in "xyz"], axis=1)
    dx = ad["index", "dx"].to("code_length").d
    finest = dx.min()
    lower = np.rint((pos - dx[:, None] / 2) / finest).astype(np.int64)
    width = np.rint(dx / finest).astype(np.int64)
    return lower, width, ad["ramses", "Density"].d, float(ds.parameters["boxlen"]), finest


def amrvk_leaves(tmp_path):
    base = tmp_path / "galaxy"
    run_cli("convert", GALAXY, "--field", "density", "-o", base)
    cells = np.fromfile(f"{base}.cells", dtype="<i4").reshape(-1, 4)
    values = np.fromfile(f"{base}.density.scalars", dtype="<f4")
    return cells[:, :3].astype(np.int64), np.left_shift(1, cells[:, 3]).astype(np.int64), values


def order(lower, width):
    return np.lexsort((lower[:, 0], lower[:, 1], lower[:, 2], width))


def test_every_leaf_and_its_density_agree_with_yt(tmp_path, yt_leaves):
    y_lower, y_width, y_density, _, _ = yt_leaves
    a_lower, a_width, a_density = amrvk_leaves(tmp_path)
    assert len(a_density) == len(y_density) == 262144
    ya, aa = order(y_lower, y_width), order(a_lower, a_width)
    np.testing.assert_array_equal(a_lower[aa], y_lower[ya])
    np.testing.assert_array_equal(a_width[aa], y_width[ya])
    # amrvk stores float32: within float32 rounding of yt's float64 values.
    np.testing.assert_allclose(a_density[aa], y_density[ya], rtol=1e-7, atol=0)
    # A few single cells by position (corner, width): the densest and the thinnest.
    for i in (int(np.argmax(y_density)), int(np.argmin(y_density))):
        hit = np.flatnonzero((a_lower == y_lower[i]).all(axis=1) & (a_width == y_width[i]))
        assert len(hit) == 1
        assert a_density[hit[0]] == pytest.approx(y_density[i], rel=1e-7)


def test_info_json_summary_agrees_with_yt(yt_leaves):
    _, y_width, y_density, boxlen, finest = yt_leaves
    binary = amrvk_binary()
    if not binary.exists():
        pytest.skip(f"{binary} is not built")
    p = subprocess.run([str(binary), "info", str(GALAXY), "--field", "density", "--scale", "linear", "--json"],
                       capture_output=True, text=True, check=True)
    info = json.loads(p.stdout)
    assert info["format"] == "ramses"
    assert info["leafCells"] == len(y_density)
    widths, counts = np.unique(y_width, return_counts=True)
    per_level = [0] * len(info["cellsPerLevel"])
    for w, c in zip(widths, counts):
        per_level[int(w).bit_length() - 1] += int(c)
    assert info["cellsPerLevel"] == per_level
    lo, hi = info["valueRange"]
    assert lo == pytest.approx(y_density.min(), rel=1e-7)
    assert hi == pytest.approx(y_density.max(), rel=1e-7)
    # Every leaf of this output has the same volume: the volume-weighted mean times the count is the sum.
    assert info["volumeWeightedMean"] * info["leafCells"] == pytest.approx(y_density.sum(), rel=1e-6)
    assert y_density.sum() == pytest.approx(484588.48476868507, rel=1e-12)  # FORMATS.md section 6
    # World bounds: code units, [0, boxlen] (yt's code_length spans the unit box).
    assert info["worldBounds"]["lower"] == [0.0, 0.0, 0.0]
    assert info["worldBounds"]["upper"] == pytest.approx([boxlen] * 3)
