"""TF colours are display (sRGB) colours (issue 35): a TF made with from_nodes renders, on an opaque
slab in ae mode on black, the colour itself in 8 bits, as `amrvk render` and the viewer do
(tests/gpu/tf_colors_gpu_test.cpp); tf_colors="linear" keeps the old meaning, as a keyword and as
a property; a bad value is a one-line ValueError naming the keyword."""
import numpy as np
import pytest


def encode8(linear):
    """IEC 61966-2-1 encoding of linear values to 8-bit codes, written out here."""
    c = np.clip(linear, 0.0, 1.0)
    s = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.rint(s * 255).astype(int)


def slab(amrvk, **kw):
    """The slab [0, 64)^2 x [0, 4) of value 1, optical depth 400, seen from above."""
    x, y, z = np.meshgrid(np.arange(64), np.arange(64), np.arange(4), indexing="ij")
    lower = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1).astype(np.int32)
    volume = amrvk.Volume.from_arrays(lower, np.zeros(len(lower), np.int32), np.ones(len(lower), np.float32))
    tf = amrvk.TransferFunction.from_nodes(np.array([0.0]), np.array([[0.2, 0.4, 0.6, 1.0]]))
    camera = amrvk.Camera([32, 32, 100], [32, 32, 0], [0, 1, 0], 20)
    return amrvk.Renderer(volume, tf, camera, mode="ae", background=[0, 0, 0], density_scale=100.0, width=24,
                          height=24, grid="16", quiet=True, **kw)


def test_an_opaque_slab_shows_the_tf_colour_itself(amrvk):
    r = slab(amrvk)
    assert r.tf_colors == "srgb"
    codes = encode8(r.render(spp=2)[..., :3])
    assert np.all(np.abs(codes - [51, 102, 153]) <= 1), codes.reshape(-1, 3)[:3]
    # The TF keeps its colours as given; only the picture decodes them.
    assert np.allclose(r.tf.evaluate(np.array([1.0]))[0, :3], [0.2, 0.4, 0.6])
    r.tf_colors = "linear"
    codes = encode8(r.render(spp=2)[..., :3])
    assert np.all(np.abs(codes - [124, 170, 203]) <= 1), codes.reshape(-1, 3)[:3]
    old = encode8(slab(amrvk, tf_colors="linear").render(spp=2)[..., :3])
    assert np.all(np.abs(old - [124, 170, 203]) <= 1)


def test_a_bad_tf_colors_value_names_the_keyword(amrvk):
    with pytest.raises(ValueError, match="tf_colors 'gamma': expected linear|srgb"):
        slab(amrvk, tf_colors="gamma")
    r = slab(amrvk)
    with pytest.raises(ValueError, match="tf_colors 'display'"):
        r.tf_colors = "display"
    assert r.tf_colors == "srgb"
