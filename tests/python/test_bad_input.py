"""Bad input from Python (issue 33, point 4): every case raises ValueError or TypeError with one
line that names the keyword at fault (not pybind11's multi-line list of signatures, not a CLI
option such as --density-scale), and the limits are the command line's (src/scene/limits.h)."""
import re

import numpy as np
import pytest

from conftest import ENZO, SAMPLE, need

SMALL = dict(width=16, height=12, density_scale=3.0, tf_range=(0.3, 2.0), grid="16", quiet=True)


@pytest.fixture(scope="module")
def volume(amrvk):
    return amrvk.Volume(str(SAMPLE))


def one_line(kind, pattern, call):
    """call() raises `kind` whose message matches `pattern` and is one line."""
    with pytest.raises(kind, match=pattern) as e:
        call()
    message = str(e.value)
    assert "\n" not in message, message
    assert "incompatible function arguments" not in message, message
    return message


def test_renderer_arguments_name_the_keyword(amrvk, volume):
    one_line(TypeError, r"^volume: expected an amrvk.Volume, got None$", lambda: amrvk.Renderer(None))
    one_line(TypeError, r"^volume: expected an amrvk.Volume, got 'x.cells'$", lambda: amrvk.Renderer("x.cells"))
    one_line(TypeError, r"^tf: expected an amrvk.TransferFunction or None, got 'ramp'$",
             lambda: amrvk.Renderer(volume, "ramp"))
    one_line(TypeError, r"^camera: expected an amrvk.Camera or None, got 3$", lambda: amrvk.Renderer(volume, None, 3))
    cases = [
        (dict(spp=0), ValueError, re.escape("spp: 0 is outside [1, 16777216]")),
        (dict(spp=-1), ValueError, re.escape("spp: -1 is outside [1, 16777216]")),
        (dict(spp=2.5), TypeError, re.escape("spp: expected a whole number in [1, 16777216], got 2.5")),
        (dict(spp=10**9), ValueError, re.escape("spp: 1000000000 is outside [1, 16777216]")),
        (dict(width=0), ValueError, re.escape("width: 0 is outside [1, 16384]")),
        (dict(height=16385), ValueError, re.escape("height: 16385 is outside [1, 16384]")),
        (dict(width=12.5), TypeError, re.escape("width: expected a whole number in [1, 16384], got 12.5")),
        (dict(width="64"), TypeError, re.escape("width: expected a whole number in [1, 16384], got '64'")),
        (dict(seed=-1), ValueError, re.escape("seed: -1 is outside [0, 4294967295]")),
        (dict(density_scale="a"), TypeError, "^density_scale: expected a number, got 'a'$"),
        (dict(density_scale=-1), ValueError, r"^density_scale: -1 is outside \[0, inf\)$"),
        (dict(density_scale=True), TypeError, "^density_scale: expected a number, got True$"),
        (dict(g=float("nan")), ValueError, "^g: nan is not a finite number$"),
        (dict(mode="pt"), ValueError, r"^mode: 'pt' is not one of ae\|ss\|ms\|dvr$"),
        (dict(mode=3), TypeError, "^mode: expected one of 'ae', 'ss', 'ms', 'dvr', got 3$"),
        (dict(ambient=[1, 2]), ValueError, "^ambient: expected 3 numbers, got 2$"),
        (dict(ambient="red"), TypeError, "^ambient: expected 3 numbers, got 'red'$"),
        (dict(background=[0, -1, 0]), ValueError, "^background must be finite and >= 0$"),
        (dict(lights=[1, 2]), TypeError, r"^lights: expected a list of amrvk.Light, got \[1, 2\]$"),
        (dict(fov=180), ValueError, r"^fov: 180 is outside \(0, 180\)$"),
        (dict(dt=0), ValueError, r"^dt: 0 is outside \(0, 64\]$"),
        (dict(tf_range=(2, 1)), ValueError, "^tf_range 2 1: LO must be below HI$"),
        (dict(tf_range="lo"), TypeError, r"^tf_range: expected \(lo, hi\): two numbers, got 'lo'$"),
        (dict(crop=([5, 0, 0], [1, 1, 1])), ValueError, "^crop: lower corner 5 is not below upper corner 1 on axis x"),
        (dict(crop=5), TypeError, r"^crop: expected \(lo, hi\)"),
        (dict(clip=[([0, 0, 0], [1, 0, 0])] * 5), ValueError, "^clip: at most 4 planes"),
        (dict(sampler="dense", traversal="abr"), ValueError, "^sampler dense needs traversal grid-dda or grid-bvh"),
        (dict(traversal="nope"), ValueError, re.escape("traversal: 'nope' is not one of grid-dda|grid-bvh|abr|brick|domain|kdtree|auto")),
        (dict(kd_leaves=0), ValueError, re.escape("kd_leaves: 0 is outside [1, 16777215]")),
        (dict(dense_max_mib=-3), ValueError, re.escape("dense_max_mib: -3 is outside [1, 1048576]")),
        (dict(validation="yes"), TypeError, "^validation: expected True or False, got 'yes'$"),
        (dict(colour="red"), TypeError, "^Renderer\\(\\) got an unexpected keyword argument 'colour'$"),
    ]
    for kw, kind, pattern in cases:
        one_line(kind, pattern, lambda: amrvk.Renderer(volume, **{**SMALL, **kw}))


def test_calls_and_edits_name_the_keyword(amrvk, volume):
    r = amrvk.Renderer(volume, **SMALL)
    one_line(ValueError, re.escape("spp: 0 is outside [1, 16777216]"), lambda: r.render(spp=0))
    one_line(ValueError, re.escape("spp: 1000000000 is outside [1, 16777216]"), lambda: r.render(spp=10**9))
    one_line(ValueError, re.escape("spp: -1 is outside"), lambda: r.render(spp=-1))
    one_line(TypeError, re.escape("spp: expected a whole number in [1, 16777216], got 2.5"), lambda: r.render(spp=2.5))
    one_line(ValueError, re.escape("n: -5 is outside [1, 16777216]"), lambda: r.accumulate(-5))
    assert r.spp == 0, "a refused call renders nothing"

    def edit(name, value):
        return lambda: setattr(r, name, value)

    one_line(ValueError, r"^density_scale: -1 is outside \[0, inf\)$", edit("density_scale", -1))
    one_line(TypeError, "^density_scale: expected a number, got 'x'$", edit("density_scale", "x"))
    one_line(ValueError, re.escape("size: width: 0 is outside [1, 16384]"), edit("size", (0, 8)))
    one_line(ValueError, re.escape("size: height: 16385 is outside [1, 16384]"), edit("size", (8, 16385)))
    one_line(TypeError, re.escape("size: expected (width, height), got 8"), edit("size", 8))
    one_line(TypeError, "^seed: expected a whole number", edit("seed", 1.5))
    one_line(ValueError, r"^mode: 'pt' is not one of ae\|ss\|ms\|dvr$", edit("mode", "pt"))
    one_line(TypeError, "^mode: expected one of", edit("mode", None))
    one_line(TypeError, "^camera: expected an amrvk.Camera, got 'front'$", edit("camera", "front"))
    one_line(TypeError, "^tf: expected an amrvk.TransferFunction, got None$", edit("tf", None))
    one_line(TypeError, "^lights: expected a list of amrvk.Light", edit("lights", "sun"))
    one_line(TypeError, "^ambient: expected 3 numbers", edit("ambient", 1))
    one_line(ValueError, "^background must be finite and >= 0$", edit("background", [0, -1, 0]))
    one_line(TypeError, "^g: expected a number", edit("g", [0.5]))
    assert r.size == (16, 12) and r.density_scale == 3.0 and r.mode == "ms", "a refused edit changes nothing"


def test_volumes_and_images_name_the_keyword(amrvk, tmp_path):
    values = np.array([np.nan, 1.0], np.float32)
    lower = np.array([[0, 0, 0], [1, 0, 0]], np.int32)
    level = np.zeros(2, np.int32)
    message = one_line(ValueError, "non-finite value", lambda: amrvk.Volume.from_arrays(lower, level, values))
    assert "nan='drop'" in message and "--nan" not in message, message
    one_line(ValueError, "^nan: unknown NaN policy 'keep'", lambda: amrvk.Volume.from_arrays(lower, level, values, nan="keep"))
    one_line(ValueError, "^nan: unknown NaN policy 'keep'", lambda: amrvk.Volume(str(SAMPLE), nan="keep"))
    one_line(ValueError, "^scale: 'ln' is not auto, linear or log$", lambda: amrvk.Volume(str(SAMPLE), scale="ln"))
    # show() checks its array when called, not when Jupyter displays it.
    one_line(ValueError, re.escape("image: expected shape (height, width, 3) or (height, width, 4), got (5, 5)"),
             lambda: amrvk.show(np.zeros((5, 5))))
    one_line(ValueError, re.escape("got (5, 5, 2)"), lambda: amrvk.show(np.zeros((5, 5, 2))))
    one_line(TypeError, "^image: expected numbers, got dtype <U1$", lambda: amrvk.show(np.array([[["a"] * 3]])))
    assert amrvk.show(np.zeros((5, 5, 3)))._repr_png_()[:4] == b"\x89PNG"
    # A session needs a file: the refusal says where the volume came from.
    arrays = amrvk.Renderer(amrvk.Volume.from_arrays(lower[1:], level[1:], values[1:]), width=8, height=8, quiet=True)
    one_line(ValueError, "^save_session: this volume was made from arrays", lambda: arrays.save_session(str(tmp_path / "s.json")))


def test_yt_input_names_the_keyword(amrvk, yt, tmp_path):
    ds = yt.load(str(need(ENZO)))
    one_line(ValueError, r"^field: \('all', 'particle_mass'\) is a particle field; amrvk renders fields with a value "
             r"per cell", lambda: amrvk.Volume.from_yt(ds, ("all", "particle_mass")))
    one_line(ValueError, r"^field: \('gas', 'nope'\) is not a field of DD0018",
             lambda: amrvk.Volume.from_yt(ds, ("gas", "nope")))
    one_line(TypeError, r"^field: expected a yt field name", lambda: amrvk.Volume.from_yt(ds, 3))
    one_line(TypeError, r"^log: expected True, False or None, got 'yes'$",
             lambda: amrvk.Volume.from_yt(ds, ("gas", "density"), log="yes"))
    region = ds.region([0.5] * 3, [0.45] * 3, [0.55] * 3)
    r = amrvk.Renderer(amrvk.Volume.from_yt(region, ("gas", "density"), log=True), width=8, height=8, quiet=True)
    message = one_line(ValueError, r"^save_session: this volume came from yt \(DD0018\), not from a file amrvk reads",
                       lambda: r.save_session(str(tmp_path / "s.json")))
    assert "arrays" not in message


def test_cameras_lights_tfs_and_structures_name_the_keyword(amrvk, volume):
    one_line(TypeError, r"^eye: expected 3 numbers, got 'a'$", lambda: amrvk.Camera("a", [0, 0, 0]))
    one_line(ValueError, r"^target: expected 3 numbers, got 2$", lambda: amrvk.Camera([1, 0, 0], [0, 0]))
    one_line(TypeError, r"^fov: expected a number, got None$", lambda: amrvk.Camera([1, 0, 0], [0, 0, 0], fov=None))
    one_line(ValueError, r"^fov: 200 is outside \(0, 180\)$", lambda: amrvk.Camera([1, 0, 0], [0, 0, 0], fov=200))
    one_line(TypeError, r"^volume: expected an amrvk.Volume, got 'x'$", lambda: amrvk.Camera.frame("x"))
    one_line(ValueError, r"^fov: 0 is outside \(0, 180\)$", lambda: amrvk.Camera.frame(volume, fov=0))
    one_line(TypeError, r"^direction: expected 3 numbers, got None$", lambda: amrvk.Light.directional(None))
    one_line(ValueError, r"^intensity: expected 3 numbers, got 1$", lambda: amrvk.Light.point([0, 0, 0], [1]))
    one_line(TypeError, r"^lo: expected a number, got 'a'$", lambda: amrvk.TransferFunction.preset("ramp", "a", 1))
    one_line(TypeError, r"^volume: expected an amrvk.Volume \(or lo, hi\), got None$",
             lambda: amrvk.TransferFunction.preset("ramp", None))
    one_line(TypeError, r"^hi: expected a number, got \[1\]$",
             lambda: amrvk.TransferFunction.preset("ramp", 0, 1).rescaled(0, [1]))
    r = amrvk.Renderer(volume, **SMALL)
    one_line(ValueError, re.escape("kd_leaves: 0 is outside [1, 16777215]"), lambda: r.set_structure(kd_leaves=0))
    one_line(TypeError, r"^traversal: expected one of 'grid-dda', .*, 'auto', got 3$", lambda: r.set_structure(traversal=3))


def test_no_call_answers_with_pybind11s_list_of_signatures(amrvk, volume, tmp_path):
    """Every other call of the compiled module: a wrong type is one line naming the argument
    (python/amrvk/one_line_errors.py), not pybind11's multi-line 'incompatible function arguments'."""
    r = amrvk.Renderer(volume, **SMALL)
    cases = [
        (lambda: amrvk.Volume(3), "^path: expected a path \\(str or os.PathLike\\), got 3$"),
        (lambda: amrvk.Volume(str(SAMPLE), field=3), "^field: expected a string, got 3$"),
        (lambda: amrvk.Volume(str(SAMPLE), dims=5), "^dims: expected a list of whole numbers or None, got 5$"),
        (lambda: amrvk.Volume.from_arrays(np.zeros((1, 3), np.int32), np.zeros(1, np.int32), np.ones(1), origin="a"),
         "^origin: expected a list of numbers, got 'a'$"),
        (lambda: amrvk.TransferFunction.from_file(None), "^path: expected a path"),
        (lambda: amrvk.TransferFunction.from_nodes(np.zeros(2), np.zeros((2, 4)), name=5), "^name: expected a string"),
        (lambda: amrvk.Renderer.from_session(3), "^path: expected a path"),
        (lambda: r.save(3), "^path: expected a path \\(str or os.PathLike\\), got 3$"),
        (lambda: r.save_session(None), "^path: expected a path"),
        (lambda: r.variance(3), "^Renderer.variance: takes 0 argument\\(s\\) \\(\\), got 1$"),
    ]
    for call, pattern in cases:
        one_line(TypeError, pattern, call)
    # The wrapped calls work as before.
    assert r.render(spp=1).shape == (12, 16, 4)
    r.save(str(tmp_path / "a.png"))
    assert "render(self" in amrvk.Renderer.render.__doc__


def test_an_object_never_initialised_is_refused_not_a_crash(amrvk):
    # T.__new__(T) without __init__: pybind11 would call the C++ method on a null object and crash
    # the interpreter (round 3's one open case); every method, dunder and property asks first.
    for cls, calls in ((amrvk.Volume, (repr, lambda v: v.field, lambda v: v.summary())),
                       (amrvk.Camera, (repr, lambda c: c.eye, lambda c: c.zoom(2.0))),
                       (amrvk.Light, (repr, lambda l: l.is_point)),
                       (amrvk.TransferFunction, (repr, lambda t: t.range, lambda t: t.rescaled(0, 1))),
                       (amrvk.Renderer, (repr, lambda r: r.spp, lambda r: r.render(spp=1)))):
        empty = cls.__new__(cls)
        for call in calls:
            one_line(TypeError, "never initialised", lambda: call(empty))


def test_round_4_messages_name_the_argument(amrvk, volume):
    """Issue 52, point 17: each of these named the wrong thing, spanned lines, or was taken and
    failed later; now one line naming the argument, at the call."""
    r = amrvk.Renderer(volume, **SMALL)
    one_line(TypeError, r"^tf_colors: expected 'srgb' or 'linear', got 5$", lambda: setattr(r, "tf_colors", 5))
    one_line(ValueError, r"^legend_title: 10000 bytes \(at most 256\)$", lambda: setattr(r, "legend_title", "x" * 10000))
    one_line(ValueError, r"^legend_units: 300 bytes \(at most 256\)$",
             lambda: amrvk.Renderer(volume, legend_units="u" * 300, **SMALL))
    assert r.legend_title == ""
    one_line(TypeError, r"^degrees: expected a finite number, got inf$", lambda: r.camera.orbit(float("inf")))
    one_line(ValueError, r"^hi: expected a finite number, got nan$",
             lambda: amrvk.TransferFunction.from_colormap("viridis", 0, float("nan")))
    one_line(ValueError, r"^axis: expected 3 finite numbers, not all 0, got 'z'$", lambda: r.camera.orbit(10, axis="z"))
    one_line(TypeError, r"^path: contains a NUL character \(at 1\)", lambda: amrvk.Volume("a\0b"))

    class Length:  # yt's unyt quantities, as from_yt reads them
        def __init__(self, v):
            self.d = v

        def to(self, unit):
            return self

    class YtCamera:
        position, focus, north_vector = Length([0.0, 0.0, 2.0]), Length([0.0, 0.0, 0.0]), [0.0, 1.0, 0.0]
        width = [Length(1.0), Length(0.0), Length(1.0)]

    one_line(ValueError, r"^yt_camera: its width's height 0 must be finite and > 0$",
             lambda: amrvk.Camera.from_yt(YtCamera()))
    pytest.importorskip("ipywidgets", reason="Debian: python3-ipywidgets")
    w = amrvk.Widget(r, spp=1)
    try:
        one_line(TypeError, r"^timeout: expected a number of seconds or None, got str$", lambda: w.wait("x"))
    finally:
        w.close()
