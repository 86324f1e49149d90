"""Transfer functions from presets (range-fixed, and fitted to a volume's percentiles, which equal
numpy's), ParaView files and numpy nodes; evaluation against the nodes; ParaView JSON out and back;
bad nodes raise."""
import numpy as np
import pytest

from conftest import SAMPLE, SOURCE


def test_presets_nodes_and_files(amrvk, tmp_path):
    ramp = amrvk.TransferFunction.preset("ramp", 2.0, 6.0)
    assert ramp.range == (2.0, 6.0) and ramp.name == "ramp"
    positions, colors = ramp.nodes
    assert positions[0] == 2.0 and positions[-1] == 6.0 and colors.shape == (len(positions), 4)
    # Between two nodes the function is linear in every channel.
    mid = 0.5 * (positions[0] + positions[1])
    np.testing.assert_allclose(ramp.evaluate(np.array([mid]))[0], 0.5 * (colors[0] + colors[1]), rtol=1e-6)
    np.testing.assert_allclose(ramp.evaluate(np.array([-100.0, 100.0])), colors[[0, -1]], rtol=0)  # constant beyond

    tf = amrvk.TransferFunction.from_nodes(np.array([0.0, 1.0, 3.0]),
                                           np.array([[1, 0, 0, 0], [0, 1, 0, 2.5], [0, 0, 1, 0.5]]), name="mine")
    np.testing.assert_allclose(tf.evaluate(np.array([1.0, 2.0]))[:, 3], [2.5, 1.5], rtol=1e-6)
    tf.save(str(tmp_path / "mine.json"))
    back = amrvk.TransferFunction.from_file(str(tmp_path / "mine.json"))
    np.testing.assert_allclose(back.nodes[0], tf.nodes[0])
    np.testing.assert_allclose(back.nodes[1], tf.nodes[1], rtol=1e-6)
    np.testing.assert_allclose(tf.rescaled(10, 20).range, (10, 20))
    web = amrvk.TransferFunction.from_file(str(SOURCE / "assets" / "tf" / "cosmic-web.json"))
    assert len(web.nodes[0]) > 2


def test_bad_nodes(amrvk):
    with pytest.raises(ValueError, match="ascending|descending|non-descending"):
        amrvk.TransferFunction.from_nodes(np.array([1.0, 0.0]), np.array([[1, 1, 1, 1], [1, 1, 1, 1]], float))
    with pytest.raises(ValueError):
        amrvk.TransferFunction.from_nodes(np.array([0.0]), np.array([[2, 1, 1, 1]], float))  # rgb above 1
    with pytest.raises(ValueError):
        amrvk.TransferFunction.from_nodes(np.array([0.0]), np.array([[1, 1, 1, -1]], float))  # negative alpha
    with pytest.raises(ValueError, match="same length"):
        amrvk.TransferFunction.from_nodes(np.array([0.0, 1.0]), np.array([[1, 1, 1, 1]], float))
    with pytest.raises(ValueError, match=r"expected shape \(N, 4\)"):
        amrvk.TransferFunction.from_nodes(np.array([0.0]), np.array([[1, 1, 1]], float))
    with pytest.raises(ValueError, match="neither a built-in preset"):
        amrvk.TransferFunction.preset("rainbowz", 0, 1)  # 'rainbow' is a matplotlib colormap
    with pytest.raises(ValueError):
        amrvk.TransferFunction.from_nodes(np.array([np.nan]), np.array([[1, 1, 1, 1]], float))


def test_presets_fitted_to_a_volume(amrvk):
    v = amrvk.Volume(str(SAMPLE), scale="linear")
    values = np.fromfile(str(SAMPLE.with_suffix(".scalars")), dtype=np.float32)
    p = np.percentile(values, np.arange(101), method="lower").astype(np.float32)
    assert v.percentiles.dtype == np.float32 and v.percentiles.shape == (101,)
    np.testing.assert_array_equal(v.percentiles, p)
    assert v.value_range == (p[0], p[100])

    spiky = amrvk.TransferFunction.preset("spiky", v)
    positions, colors = spiky.nodes
    np.testing.assert_array_equal(positions, p[[0, 74, 75, 76, 89, 90, 91, 96, 97, 98, 100]])
    np.testing.assert_array_equal(colors[:, 3], [0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0])
    foggy = amrvk.TransferFunction.preset("foggy", v)
    positions, colors = foggy.nodes
    np.testing.assert_array_equal(positions, p[[0, 50, 60, 70, 80, 90, 95, 99, 100]])
    assert (foggy.evaluate(values[values <= p[50]])[:, 3] == 0).all()
    np.testing.assert_allclose(foggy.evaluate(p[[100]])[0, 3], 0.05, rtol=1e-6)
    # Over a range given by hand: the range-fixed shape, whatever the data.
    fixed = amrvk.TransferFunction.preset("spiky", float(p[0]), float(p[100]))
    assert len(fixed.nodes[0]) == 5 and fixed.evaluate(p[[75]])[0, 3] != 1.0
    # The others span the range either way.
    np.testing.assert_array_equal(amrvk.TransferFunction.preset("ramp", v).nodes[0],
                                  amrvk.TransferFunction.preset("ramp", float(p[0]), float(p[100])).nodes[0])
    with pytest.raises(ValueError, match="'rainbowz' is neither a built-in preset"):
        amrvk.TransferFunction.preset("rainbowz", v)
