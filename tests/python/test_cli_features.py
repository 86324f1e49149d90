"""What the command line has, from Python (issue 33, point 3): the colour legend on save, png
(_repr_png_) and render, drawn by the CLI's own code; matplotlib colormaps by name; camera orbit,
zoom and conversion from and to yt's camera; and the Jupyter widget that refines and orbits."""
import math
import os
import tempfile
import threading
import time

import numpy as np
import pytest

from conftest import DATA, ENZO, SAMPLE, need, run_cli

SMALL = dict(width=96, height=64, density_scale=3.0, tf_range=(0.3, 2.0), grid="16", quiet=True, seed=7)


def png_pixels(data):
    import io

    import matplotlib.image

    return matplotlib.image.imread(io.BytesIO(data), format="png")


def test_the_legend_is_the_command_lines(amrvk, tmp_path):
    r = amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), legend=True, **SMALL)
    image = r.render(spp=2)
    assert image.shape == (64, 96, 4), "an array is the picture alone unless legend=True"
    with_legend = r.image(legend=True)
    assert with_legend.shape[0] == 64 and with_legend.shape[1] > 96
    np.testing.assert_array_equal(with_legend[:, :96], image)  # side: every picture pixel kept
    assert r.render(spp=2, legend=True).shape == with_legend.shape
    # PNGs (save, png, _repr_png_) follow the renderer's legend setting.
    assert png_pixels(r._repr_png_()).shape[:2] == with_legend.shape[:2]
    assert png_pixels(r.png(legend=False)).shape[:2] == (64, 96)
    # The same picture as `amrvk render --legend` of the same session, byte for byte.
    r.save(str(tmp_path / "py.png"))
    r.save_session(str(tmp_path / "s.json"))
    run_cli("render", "--session", tmp_path / "s.json", "--spp", "2", "-o", tmp_path / "cli.png")
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    r.legend_place = "overlay"
    assert r.image(legend=True).shape == (64, 96, 4)
    r.legend_title, r.legend_units = "cloud", "g/cm^3"
    assert (r.legend, r.legend_place, r.legend_title, r.legend_units) == (True, "overlay", "cloud", "g/cm^3")
    r.legend = False
    assert png_pixels(r.png()).shape[:2] == (64, 96)
    with pytest.raises(ValueError, match="^legend: only PNG images get a legend"):
        r.save(str(tmp_path / "a.exr"), legend=True)
    with pytest.raises(ValueError, match="^legend_place 'left': expected side|overlay"):
        r.legend_place = "left"
    tiny = amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), **{**SMALL, "width": 8, "height": 8})
    tiny.render(spp=1)
    with pytest.raises(ValueError, match="^legend: the picture 8x8 is too small for a legend"):
        tiny.image(legend=True)


def test_colormaps_by_name(amrvk):
    matplotlib = pytest.importorskip("matplotlib", reason="Debian: python3-matplotlib")
    v = amrvk.Volume(str(SAMPLE), scale="linear")
    tf = amrvk.TransferFunction.preset("viridis", 0.5, 2.5)
    positions, colors = tf.nodes
    assert tf.name == "viridis" and tf.range == (0.5, 2.5) and len(positions) == 16
    # The map's colours as given; the ramp preset's opacity.
    expected = matplotlib.colormaps["viridis"](np.linspace(0, 1, 16))
    np.testing.assert_allclose(colors[:, :3], expected[:, :3], atol=1e-6)
    ramp = amrvk.TransferFunction.preset("ramp", 0.5, 2.5)
    np.testing.assert_allclose(colors[:, 3], ramp.evaluate(positions)[:, 3], atol=1e-6)
    fitted = amrvk.TransferFunction.from_colormap("magma", v)
    assert fitted.range == pytest.approx(v.value_range)
    # Built-in names stay the presets (matplotlib also has a 'grey').
    assert amrvk.TransferFunction.preset("grey", 0, 1).name == "grey"
    with pytest.raises(ValueError, match="^name: 'viridiss' is neither a built-in preset"):
        amrvk.TransferFunction.preset("viridiss", 0, 1)
    with pytest.raises(ValueError, match=r"^nodes: expected a whole number in \[2, 4096\], got 1"):
        amrvk.TransferFunction.from_colormap("viridis", 0, 1, nodes=1)


def test_camera_orbit_and_zoom(amrvk):
    c = amrvk.Camera([10, 0, 3], [0, 0, 3], [0, 0, 1], 30)
    quarter = c.orbit(90)
    np.testing.assert_allclose(quarter.eye, [0, 10, 3], atol=1e-12)
    assert quarter.target == c.target and quarter.up == c.up and quarter.fov == 30
    np.testing.assert_allclose(c.orbit(360).eye, c.eye, atol=1e-12)
    np.testing.assert_allclose(c.orbit(90, axis=[0, 0, -1]).eye, [0, -10, 3], atol=1e-12)
    np.testing.assert_allclose(c.zoom(2).eye, [5, 0, 3])
    np.testing.assert_allclose(c.zoom(0.5).eye, [20, 0, 3])
    with pytest.raises(ValueError, match="^factor: 0 must be > 0$"):
        c.zoom(0)
    with pytest.raises(TypeError, match="^degrees: expected a finite number, got 'a'$"):
        c.orbit("a")
    with pytest.raises(ValueError, match="^axis: expected 3 finite numbers"):
        c.orbit(10, axis=[0, 0, 0])
    r = amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), **SMALL)
    first = r.camera
    r.render(spp=1)
    r.orbit(45).zoom(1.5)
    assert r.spp == 0, "a camera edit restarts the estimate"
    np.testing.assert_allclose(r.camera.eye, first.orbit(45).zoom(1.5).eye, rtol=1e-12)


def test_cameras_to_and_from_yt(amrvk, yt):
    ds = yt.load(str(need(ENZO)))
    sc = yt.create_scene(ds, ("gas", "density"))
    cam = amrvk.Camera.from_yt(sc.camera)
    position = sc.camera.position.to("code_length").d
    focus = sc.camera.focus.to("code_length").d
    np.testing.assert_allclose(cam.eye, position)
    np.testing.assert_allclose(cam.target, focus)
    height = float(sc.camera.width[1].to("code_length").d)
    assert math.tan(math.radians(cam.fov) / 2) * np.linalg.norm(position - focus) == pytest.approx(height / 2)
    # And back: an amrvk camera set on yt's, read back as the same camera.
    turned = cam.orbit(30).zoom(1.2)
    again = amrvk.Camera.from_yt(turned.to_yt(sc.camera))
    np.testing.assert_allclose(again.eye, turned.eye, rtol=1e-9)
    np.testing.assert_allclose(again.target, turned.target, rtol=1e-9)
    np.testing.assert_allclose(again.up, turned.up, atol=1e-9)
    assert again.fov == pytest.approx(turned.fov)
    with pytest.raises(TypeError, match="^yt_camera: expected a yt Camera"):
        amrvk.Camera.from_yt(ds)


def test_the_widget_refines_and_orbits(amrvk):
    pytest.importorskip("ipywidgets", reason="Debian: python3-ipywidgets")
    r = amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), **SMALL)
    first = r.camera
    dvr = amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), **SMALL).png()  # its first frame
    w = amrvk.Widget(r, spp=8, batch=2)
    try:
        # At once, before any path-traced sample: the renderer's dvr first frame (the thread
        # replaces it from its first batch on). Its step is refined while its GPU budget allows,
        # so under load it may stop a refinement earlier than the other renderer's: the same
        # picture up to the step's aliasing, not byte for byte.
        assert w.first_frame is not None and w.status.value.startswith("first frame (dvr")
        shown, alone = png_pixels(w.first_frame), png_pixels(dvr)
        assert shown.shape == alone.shape and np.abs(shown - alone).mean() < 0.005, np.abs(shown - alone).mean()
        assert w.wait(120), "the widget reaches its sample count"
        assert w.image.value != dvr
        assert r.spp == 8 and w.image.value == r.png() and w.status.value.startswith("8/8 spp, mean standard error")
        w.azimuth.value = 90
        w.zoom.value = 2
        assert w.wait(120)
        assert r.spp == 8
        np.testing.assert_allclose(r.camera.eye, first.orbit(90).zoom(2).eye, rtol=1e-12)
        assert w.image.value == r.png()
        w.elevation.value = 20
        assert w.wait(120)
        view = np.subtract(r.camera.eye, r.camera.target)
        before = np.subtract(first.orbit(90).eye, first.target)
        angle = math.degrees(math.acos(np.dot(view, before) / np.linalg.norm(view) / np.linalg.norm(before)))
        assert angle == pytest.approx(20, abs=1e-6)
        assert repr(w) == "Widget(8/8 spp, azimuth 90, elevation 20, zoom 2)"
        # Sliders moved while the thread refines (each restarts the estimate between its calls).
        for step in range(40):
            w.azimuth.value = 90 + step
            time.sleep(0.005)
        assert w.wait(120) and r.spp == 8 and w.image.value == r.png()
    finally:
        w.close()
    assert not r.closed
    # A widget on a renderer that already has its samples shows them at once (it stayed blank), at
    # the image's own size with the whole status line.
    again = amrvk.Widget(r, spp=8)
    try:
        assert again.image.value == r.png() and again.status.value.startswith("8/8 spp, mean standard error")
        assert again.image.layout.width == f"{r.size[0]}px" and again.status.layout.width == "auto"
    finally:
        again.close()
    with pytest.raises(TypeError, match="^renderer: expected an amrvk.Renderer, got NoneType$"):
        amrvk.Widget(None)
    with pytest.raises(ValueError, match=r"^spp: 0 is outside \[1, 16777216\]$"):
        amrvk.Widget(r, spp=0)


def test_the_first_frame_stays_until_the_estimate_is_as_clean(amrvk):
    # Issue 53, point 7: the widget replaced the clean first frame with the grainy estimate after its
    # first batch. Now the first frame stays until the estimate's noise is as low as the first
    # frame's (or 0.05), or the widget's spp is reached; a scattering haze is far grainier at 4 spp.
    pytest.importorskip("ipywidgets", reason="Debian: python3-ipywidgets")
    r = amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), mode="ms", **SMALL)
    first = r.png()
    first_noise = r.first_frame["noise"]
    at_once = r._shown(64)
    assert at_once["shown"] == "first frame" and at_once["png"] == first and at_once["spp"] == 0
    r.accumulate(4)
    held = r._shown(64)
    assert held["shown"] == "first frame" and held["png"] == first and held["spp"] == 4
    assert held["first_frame_noise"] == first_noise and held["noise"] > max(first_noise, 0.05)
    # The rule's other ends: the spp asked for, and no hold, show the estimate.
    assert r._shown(4)["shown"] == "estimate" and r._shown(4)["png"] == r.png() != first
    assert r._shown(64, hold=False)["shown"] == "estimate"
    # As the estimate converges it takes over exactly when its noise reaches the threshold.
    while r.spp < 4096:
        s = r._shown(1 << 20)
        assert (s["shown"] == "estimate") == (s["noise"] <= max(first_noise, 0.05)), s
        if s["shown"] == "estimate":
            break
        r.accumulate(r.spp)
    assert s["shown"] == "estimate", f"the estimate never got as clean as the first frame ({s['noise']} at {r.spp})"
    # The widget: at its spp it shows the estimate, and says so.
    w = amrvk.Widget(amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), mode="ms", **SMALL), spp=8, batch=4)
    try:
        assert w.shown == "first frame"
        assert w.wait(120) and w.shown == "estimate" and w.status.value.startswith("8/8 spp")
    finally:
        w.close()


def test_the_widget_steps_a_series(amrvk):
    # Issue 53, point 5: a step slider over a time series (Chombo's two mushy-layer outputs); each
    # step is that data set with the camera and TF kept, and its picture is the one a renderer made
    # for that data set with the same session gives (the same samples: equal to float rounding).
    pytest.importorskip("ipywidgets", reason="Debian: python3-ipywidgets")
    chombo = need(DATA / "chombo_mushy_layer_2d")
    steps = sorted(str(p) for p in chombo.glob("plt*.2d.hdf5"))
    r = amrvk.Renderer(amrvk.Volume(steps[0]), width=32, height=32, quiet=True, seed=3)
    camera, tf = r.camera, r.tf
    w = amrvk.Widget(r, spp=4, batch=2, series=str(chombo / "plt*.2d.hdf5"))
    try:
        assert w.series == steps and w.step.value == 0 and w.wait(120)
        first = r.image()
        w.step.value = 1
        assert r.input == steps[1] and w.step_label.value == "plt025000.2d.hdf5"
        assert w.wait(120) and r.spp == 4
        np.testing.assert_allclose(r.camera.eye, camera.eye, rtol=1e-12)
        assert repr(r.tf.nodes) == repr(tf.nodes), "one TF over the series"
        second = r.image()
        assert np.abs(second - first).max() > 0.01, "step 1 is another picture"
        with tempfile.TemporaryDirectory() as d:
            r.save_session(os.path.join(d, "s.json"))
            alone = amrvk.Renderer.from_session(os.path.join(d, "s.json"), quiet=True)
            np.testing.assert_allclose(alone.render(spp=4), second, rtol=1e-4, atol=1e-6)
    finally:
        w.close()
    with pytest.raises(TypeError, match="^series: expected a glob or a list of paths, got int$"):
        amrvk.Widget(r, series=3)


def test_a_long_call_yields_to_the_widget_and_the_count_is_the_images(amrvk):
    # Issue 52, point 15: r.render(spp=4096) held the renderer for the whole call (the widget and
    # its sliders froze), and the status counted samples in one call and showed another's image.
    # Now the long call yields between its quarter-second chunks in turn (a fair lock): a slider
    # moved while it runs is served while it still runs, and restarts its count, so it returns the
    # samples it was asked for, of the new view.
    pytest.importorskip("ipywidgets", reason="Debian: python3-ipywidgets")
    r = amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), **SMALL)
    first = r.camera
    w = amrvk.Widget(r, spp=4, batch=2)
    try:
        assert w.wait(120)
        long_spp, images = 256, []
        t = threading.Thread(target=lambda: images.append(r.render(spp=long_spp)))
        t.start()
        deadline = time.monotonic() + 120
        while r.spp < 8 and t.is_alive() and time.monotonic() < deadline:  # under way, past the widget's 4
            time.sleep(0.01)
        w.azimuth.value = 45  # sets r.camera from this thread: waits its turn, one chunk at most
        moved_while_running = t.is_alive()
        t.join(300)
        assert not t.is_alive() and moved_while_running, "the slider waited for the whole call"
        assert r.spp == long_spp, r.spp
        np.testing.assert_allclose(r.camera.eye, first.orbit(45).eye, rtol=1e-12)
        assert images[0].shape[:2] == (64, 96)
        spp, png, error = r._snapshot()
        assert spp == long_spp and png == r.png() and error is not None
        assert w.wait(120)
        assert w.image.value == png and w.status.value == f"{long_spp}/4 spp, mean standard error {error:.4g}", \
            w.status.value
    finally:
        w.close()
    assert r._snapshot()[0] == long_spp
    r.reset()
    assert r._snapshot() == (0, None, None)
