"""Volumes from files and from numpy arrays: arrays are validated as the readers validate (the
same one-line messages as the command line), every bad array raises a Python exception, and a
volume made from arrays is the volume the same cells make when read from a file."""
import numpy as np
import pytest

from conftest import SAMPLE, run_cli, write_cells

FIVE = [(0, 0, 0, 1), (2, 0, 0, 0), (3, 0, 0, 0), (2, 1, 0, 0), (3, 1, 0, 0)]


def arrays(cells=FIVE, values=(1, 2, 3, 4, 5)):
    c = np.asarray(cells, dtype=np.int64)
    return c[:, :3].copy(), c[:, 3].copy(), np.asarray(values, dtype=np.float32)


def test_a_file_and_its_summary(amrvk):
    v = amrvk.Volume(str(SAMPLE), scale="linear")
    s = v.summary()
    assert v.cells == 32768 and s["cells"] == 32768
    assert sum(s["cells_per_level"]) == 32768
    assert v.field == "scalars"
    lo, hi = v.value_range
    assert lo < hi
    assert s["bricks"] > 0 and s["host_bytes"] > 32768 * (8 + 4)  # 8-byte cells, 4-byte values, structures


def test_a_log_scaled_file_has_the_logs_of_its_values(amrvk, tmp_path):
    write_cells(tmp_path / "five", FIVE, [1e-2, 1, 10, 0, 1000])
    v = amrvk.Volume(str(tmp_path / "five.cells"), scale="log")
    lo, hi = v.value_range
    assert lo == pytest.approx(-2, abs=1e-6) and hi == pytest.approx(3, abs=1e-6)  # 0 floored at 1e-2
    floored = amrvk.Volume(str(tmp_path / "five.cells"), scale="log", log_floor=0.5)
    assert floored.value_range[0] == pytest.approx(np.log10(0.5), abs=1e-6)
    with pytest.raises(ValueError, match="^scale: 'ln' is not auto, linear or log"):
        amrvk.Volume(str(tmp_path / "five.cells"), scale="ln")


def test_arrays_make_the_volume_the_same_cells_make_from_a_file(amrvk, tmp_path):
    write_cells(tmp_path / "five", FIVE, [1, 2, 3, 4, 5])
    from_file = amrvk.Volume(str(tmp_path / "five.cells"), scale="linear").summary()
    from_arrays = amrvk.Volume.from_arrays(*arrays(), field="scalars").summary()
    for key in ("cells", "cells_per_level", "value_range", "volume_weighted_mean", "bricks"):
        assert from_arrays[key] == from_file[key], key


def test_non_contiguous_and_read_only_arrays_are_read_as_they_are(amrvk):
    lower, level, values = arrays()
    wide = np.zeros((5, 6), dtype=np.int32)
    wide[:, ::2] = lower  # every other column: strided
    strided = wide[:, ::2]
    assert not strided.flags["C_CONTIGUOUS"]
    values.setflags(write=False)
    a = amrvk.Volume.from_arrays(strided, level.astype(np.uint8), values).summary()
    b = amrvk.Volume.from_arrays(*arrays()).summary()
    assert a["cells_per_level"] == b["cells_per_level"] and a["volume_weighted_mean"] == b["volume_weighted_mean"]
    assert not values.flags["WRITEABLE"], "the caller's array is not touched"


def test_bad_arrays_raise_python_exceptions(amrvk):
    lower, level, values = arrays()
    with pytest.raises(TypeError, match="lower: dtype float64 is not an integer type"):
        amrvk.Volume.from_arrays(lower.astype(np.float64), level, values)
    with pytest.raises(TypeError, match="values: dtype complex128"):
        amrvk.Volume.from_arrays(lower, level, values.astype(np.complex128))
    with pytest.raises(TypeError, match="values: dtype bool"):
        amrvk.Volume.from_arrays(lower, level, values > 2)
    with pytest.raises(TypeError, match="expected a numpy array, got list"):
        amrvk.Volume.from_arrays(lower.tolist(), level, values)
    with pytest.raises(ValueError, match=r"lower: expected shape \(N, 3\), got \(5, 2\)"):
        amrvk.Volume.from_arrays(lower[:, :2], level, values)
    with pytest.raises(ValueError, match=r"level: expected shape \(N,\)"):
        amrvk.Volume.from_arrays(lower, level[:, None], values)
    with pytest.raises(ValueError, match="same length"):
        amrvk.Volume.from_arrays(lower, level, values[:4])
    with pytest.raises(ValueError, match=r"level\[1\]: -1 is outside \[0, 30\]"):
        amrvk.Volume.from_arrays(lower, np.array([1, -1, 0, 0, 0]), values)
    with pytest.raises(ValueError, match=r"lower\[0\]: 4294967296 does not fit in 32 bits"):
        amrvk.Volume.from_arrays(lower + np.array([1 << 32, 0, 0]), level, values)
    # uint64 beyond int64 is shown as given, never wrapped to a negative number (issue 34, 9)
    with pytest.raises(ValueError, match=r"level\[0\]: 9223372036854775808 is outside \[0, 30\]"):
        amrvk.Volume.from_arrays(lower, np.array([1 << 63, 0, 0, 0, 0], dtype=np.uint64), values)
    big = lower.astype(np.uint64)
    big[0, 0] = np.uint64((1 << 64) - 1)
    with pytest.raises(ValueError, match=r"lower\[0\]: 18446744073709551615 does not fit in 32 bits"):
        amrvk.Volume.from_arrays(big, level, values)
    with pytest.raises(ValueError, match="the model has no cells|no cells"):
        amrvk.Volume.from_arrays(lower[:0], level[:0], values[:0])
    with pytest.raises(ValueError, match="spacing: every component must be > 0"):
        amrvk.Volume.from_arrays(lower, level, values, spacing=[1, 0, 1])
    with pytest.raises(ValueError, match="origin: nan is not finite"):
        amrvk.Volume.from_arrays(lower, level, values, origin=[float("nan"), 0, 0])
    with pytest.raises(ValueError, match="field: 'a/b' is not a field name"):
        amrvk.Volume.from_arrays(lower, level, values, field="a/b")


def test_the_readers_checks_and_messages(amrvk, tmp_path):
    # Each bad model gives the message the command line gives for the same cells in a file.
    cases = {
        "misaligned": ([(1, 0, 0, 1)], [1.0]),
        "overlap": ([(0, 0, 0, 1), (1, 1, 1, 0)], [1.0, 2.0]),
        "nan": ([(0, 0, 0, 0), (1, 0, 0, 0)], [1.0, float("nan")]),
    }
    for name, (cells, values) in cases.items():
        write_cells(tmp_path / name, cells, values)
        status, stderr = run_cli("info", tmp_path / f"{name}.cells", check=False)
        assert status == 1
        cli = stderr.strip().split("error: ", 1)[1]
        c = np.asarray(cells, dtype=np.int64)
        with pytest.raises(ValueError) as e:
            amrvk.Volume.from_arrays(c[:, :3], c[:, 3], np.asarray(values, np.float32), field="scalars",
                                     source=str(tmp_path / f"{name}.cells"))
        # The same text once the file's own wording (its path) is taken out, with the keyword where
        # the command line names its option (issue 33, point 4).
        python = str(e.value).split(": ", 1)[1]
        assert python == cli.split(": ", 1)[1].replace("--nan drop", "nan='drop'"), (name, str(e.value), cli)
    c = np.asarray(cases["nan"][0], dtype=np.int64)
    dropped = amrvk.Volume.from_arrays(c[:, :3], c[:, 3], np.array([1.0, np.nan], np.float32), nan="drop")
    assert dropped.cells == 1


def test_refinement_must_be_by_powers_of_two(amrvk):
    # A cell 3 finest cells wide cannot exist: levels are powers of two by construction, and a
    # corner not on its width's lattice is refused as the readers refuse it.
    with pytest.raises(ValueError, match="aligned"):
        amrvk.Volume.from_arrays(np.array([[3, 0, 0]]), np.array([1]), np.array([1.0], np.float32))


def test_a_file_that_is_not_a_data_set(amrvk, tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        amrvk.Volume(str(tmp_path / "missing.cells"), scale="linear")
    with pytest.raises(ValueError, match="unknown field 'rho'"):
        amrvk.Volume(str(SAMPLE), field="rho", scale="linear")
    with pytest.raises(ValueError, match="unknown NaN policy"):
        amrvk.Volume(str(SAMPLE), nan="maybe", scale="linear")
