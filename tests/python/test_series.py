"""Series and movies from Python (issue 33, point 3): a glob, a list or a yt DatasetSeries in, frames
(arrays, numbered files or an MP4) out, one TF range for all, the command line's order and checks."""
import json
import shutil

import numpy as np
import pytest

from conftest import ENZO, need, write_cells

SMALL = dict(width=24, height=16, density_scale=3.0, grid="16", seed=5)


def cube(base, value):
    """A 4^3 block of level-0 cells whose values rise along x from `value`."""
    cells = [(x, y, z, 0) for x in range(4) for y in range(4) for z in range(4)]
    write_cells(base, cells, [value + 0.25 * c[0] for c in cells])


@pytest.fixture()
def series(tmp_path):
    for name, value in (("s_10", 3.0), ("s_2", 2.0), ("s_1", 1.0)):
        cube(tmp_path / name, value)
    return tmp_path


def test_a_glob_in_natural_order_with_one_tf_range(amrvk, series):
    frames = amrvk.render_series(str(series / "s_*.cells"), tf_range="union", tf="ramp", spp=2, **SMALL)
    assert len(frames) == 3
    # Frame k is the picture of the k-th file in natural order (s_1, s_2, s_10) under the TF over
    # the union of the three ranges, with the first file's camera.
    tf = amrvk.TransferFunction.preset("ramp", 1.0, 3.75)
    first = amrvk.Volume(str(series / "s_1.cells"), scale="linear")
    camera = amrvk.Camera.frame(first)
    for frame, name in zip(frames, ("s_1", "s_2", "s_10")):
        with amrvk.Renderer(amrvk.Volume(str(series / f"{name}.cells"), scale="linear"), tf, camera, quiet=True, **SMALL) as r:
            np.testing.assert_allclose(frame, r.render(spp=2), atol=1e-5, err_msg=name)
    # tf_range="first": the first file's range, so the later (denser) files are shown differently.
    firsts = amrvk.render_series([str(series / n) for n in ("s_10.cells", "s_1.cells")], tf="ramp", spp=2, **SMALL)
    with amrvk.Renderer(first, amrvk.TransferFunction.preset("ramp", 1.0, 1.75), camera, quiet=True, **SMALL) as r:
        np.testing.assert_allclose(firsts[0], r.render(spp=2), atol=1e-5)


def test_frames_movies_and_turntables(amrvk, series, tmp_path):
    files = amrvk.render_series(str(series / "s_*.cells"), str(tmp_path / "out" / "f_%02d.png"), tf="ramp", spp=1,
                                legend=False, **SMALL)
    assert [f.rsplit("/", 1)[1] for f in files] == ["f_00.png", "f_01.png", "f_02.png"]
    assert all((tmp_path / "out" / f"f_{k:02d}.png").stat().st_size > 0 for k in range(3))
    # A turntable: one input, 4 frames over 360 degrees; frame k turned by 90 k.
    one = str(series / "s_2.cells")
    turns = amrvk.render_series(one, frames=4, orbit=360, tf="ramp", spp=2, **SMALL)
    camera = amrvk.Camera.frame(amrvk.Volume(one, scale="linear")).orbit(90)
    with amrvk.Renderer(amrvk.Volume(one, scale="linear"), amrvk.TransferFunction.preset("ramp", 2.0, 2.75), camera, quiet=True,
                        **SMALL) as r:
        np.testing.assert_allclose(turns[1], r.render(spp=2), atol=1e-5)
    if shutil.which("ffmpeg") is None:
        pytest.skip("ffmpeg is absent (Debian: ffmpeg)")
    movie = tmp_path / "m.mp4"
    assert amrvk.render_series(str(series / "s_*.cells"), str(movie), tf="ramp", spp=1, fps=2, **SMALL) == [str(movie)]
    assert movie.read_bytes()[4:8] == b"ftyp"


def test_spiky_follows_the_series_percentiles(amrvk, tmp_path):
    """spiky over several data sets: fitted to their cells' pooled percentiles ("union") or to the
    first's ("first"), as `amrvk render` fits it; over a turntable, to its data set like one picture."""
    rng = np.random.default_rng(3)
    values = {}
    for name, scale in (("a", 1.0), ("b", 4.0)):
        cells = [(x, y, z, 0) for x in range(6) for y in range(6) for z in range(6)]
        values[name] = (scale * rng.exponential(size=len(cells))).astype(np.float32)
        write_cells(tmp_path / name, cells, values[name].tolist())
    paths = [str(tmp_path / f"{n}.cells") for n in ("a", "b")]
    vols = [amrvk.Volume(p, scale="linear") for p in paths]
    camera = amrvk.Camera.frame(vols[0])
    options = dict(width=24, height=16, density_scale=0.3, grid="8", seed=5)
    union = amrvk.render_series(paths, tf="spiky", tf_range="union", spp=2, **options)
    first = amrvk.render_series(paths, tf="spiky", spp=2, **options)
    # The union TF's alpha-1 apexes, against numpy's percentiles of every cell of both: each within
    # one percentile by rank (the pooling's bound, plus one value per data set).
    tf = amrvk._amrvk._series_preset("spiky", [amrvk._amrvk._distribution(v) for v in vols])
    positions, colors = tf.nodes
    apexes = positions[colors[:, 3] == 1.0]
    every = np.sort(np.concatenate(list(values.values())))
    for apex, k in zip(apexes, (75, 90, 97)):
        below, at = np.searchsorted(every, apex, "left") / every.size, np.searchsorted(every, apex, "right") / every.size
        assert below - 0.01 - 2 / every.size <= k / 100 <= at + 0.01 + 2 / every.size, (k, apex, below, at)
    # Frame 0 is the first data set under that TF; "first" is the first data set's own fitted spiky.
    with amrvk.Renderer(vols[0], tf, camera, quiet=True, **options) as r:
        np.testing.assert_allclose(union[0], r.render(spp=2), atol=1e-5)
    fitted = amrvk.TransferFunction.preset("spiky", vols[0])
    with amrvk.Renderer(vols[0], fitted, camera, quiet=True, **options) as r:
        own = r.render(spp=2)
    np.testing.assert_allclose(first[0], own, atol=1e-5)
    assert np.abs(union[0] - own).mean() > 1e-4, "the pooled and the first data set's spiky render alike"
    # The default (layers) over "first": the first data set's own picture, its histogram's layers.
    layers = amrvk.render_series(paths, spp=2, **options)
    with amrvk.Renderer(vols[0], amrvk.TransferFunction.preset("layers", vols[0]), camera, quiet=True, **options) as r:
        np.testing.assert_allclose(layers[0], r.render(spp=2), atol=1e-5)
    # A turntable: fitted to its data set (not the range-fixed shape over its range).
    turn = amrvk.render_series(paths[1], frames=2, orbit=90, tf="spiky", spp=2, **options)
    with amrvk.Renderer(vols[1], amrvk.TransferFunction.preset("spiky", vols[1]), amrvk.Camera.frame(vols[1]), quiet=True,
                        **options) as r:
        np.testing.assert_allclose(turn[0], r.render(spp=2), atol=1e-5)


def test_bad_series_input_is_one_line_naming_the_keyword(amrvk, series):
    cases = [
        (dict(inputs=str(series / "none_*.cells")), ValueError, "no file or directory matches the pattern"),
        (dict(inputs=str(series / "s_*.cells"), frames=3), ValueError, "^frames 3: renders one input 3 times"),
        (dict(inputs=str(series / "s_1.cells"), frames=3), ValueError, "^frames 3 without orbit"),
        (dict(inputs=str(series / "s_*.cells"), tf_range="all"), ValueError, "^tf_range: 'all' is not"),
        (dict(inputs=str(series / "s_*.cells"), tf_range=(2, 1)), ValueError, "^tf_range: 2 is not below 1$"),
        (dict(inputs=str(series / "s_*.cells"), tf=3), TypeError, "^tf: expected None, a preset"),
        (dict(inputs=3), TypeError, "^inputs: expected a path or glob"),
        (dict(inputs=str(series / "s_*.cells"), out=str(series / "one.png")), ValueError, "^out .*one.png: 3 frames"),
        (dict(inputs=str(series / "s_1.cells"), orbit="x"), TypeError, "^orbit: expected degrees"),
    ]
    for kw, kind, pattern in cases:
        with pytest.raises(kind, match=pattern) as e:
            amrvk.render_series(**{**SMALL, "spp": 1, **kw})
        assert "\n" not in str(e.value)


def test_a_failed_series_leaves_nothing_behind(amrvk, series, tmp_path):
    """Issue 52, points 9 and 17: the folders it made and the frames it wrote go when it fails; a
    bad fps is refused before any frame is rendered."""
    (series / "s_2.cells").write_bytes(b"not cells")  # the second frame's input fails to read
    out = tmp_path / "a" / "b" / "c"
    with pytest.raises(ValueError, match="s_2.cells"):
        amrvk.render_series(str(series / "s_*.cells"), out=str(out / "f_%04d.png"), tf="ramp", spp=1, **SMALL)
    assert not (tmp_path / "a").exists(), list((tmp_path / "a").rglob("*"))
    keep = tmp_path / "mine"
    keep.mkdir()  # a folder the user made stays, and is left as it was
    with pytest.raises(ValueError, match="s_2.cells"):
        amrvk.render_series(str(series / "s_*.cells"), out=str(keep), tf="ramp", spp=1, **SMALL)
    assert keep.is_dir() and not any(keep.iterdir())
    rendered = []
    for fps, kind in ((0, ValueError), ("abc", TypeError)):
        with pytest.raises(kind, match="^fps"):
            amrvk.render_series(str(series / "s_1.cells"), out=str(tmp_path / "m.mp4"), fps=fps, spp=1,
                                progress=lambda k, n: rendered.append(k), **SMALL)
    assert rendered == [] and not (tmp_path / "m.mp4").exists()


def test_a_yt_dataset_series(amrvk, yt):
    ts = yt.DatasetSeries([str(need(ENZO))])
    with pytest.raises(TypeError, match="^data: a yt DatasetSeries is a series: amrvk.render_series"):
        amrvk.Volume.from_yt(ts, ("gas", "density"))
    frames = amrvk.render_series(ts, field=("gas", "density"), log=True, frames=2, orbit=180, tf="ramp", spp=1, width=16,
                                 height=16)
    assert len(frames) == 2 and frames[0].shape == (16, 16, 4)
    assert not np.array_equal(frames[0], frames[1]), "the second frame is turned by 90 degrees"


def test_a_camera_path_from_a_session_or_a_list(amrvk, series, tmp_path):
    """Issue 53: camera_path= takes frame k's camera from a session's cameraPath (the frames the
    path's, each keyframe's camera exactly at its frame, orbiting about the target in between) or
    from a list of cameras, one per frame; each frame is the Renderer's picture of its camera;
    contradicting keywords and bad values are one line."""
    one = str(series / "s_1.cells")
    vol = amrvk.Volume(one, scale="linear")
    tf = amrvk.TransferFunction.preset("ramp", vol)
    start = amrvk.Camera.frame(vol)
    keys = [(0, start), (4, start.orbit(170))]

    def picture(camera):
        with amrvk.Renderer(vol, tf, camera, quiet=True, **SMALL) as r:
            return r.render(spp=1)

    session, plain = tmp_path / "path.json", tmp_path / "plain.json"
    with amrvk.Renderer(vol, tf, start, quiet=True, **SMALL) as r:
        r.save_session(str(plain))
    s = json.loads(plain.read_text())
    s["cameraPath"] = {"fps": 6, "keyframes": [
        {"frame": f, "camera": {"eye": c.eye, "target": c.target, "up": c.up, "fovY": c.fov}} for f, c in keys]}
    session.write_text(json.dumps(s))
    cameras, fps = amrvk._amrvk._session_camera_path(str(session))
    assert len(cameras) == 5 and fps == 6
    assert cameras[0] == start and cameras[4] == keys[1][1]
    r0 = np.linalg.norm(np.subtract(start.eye, start.target))
    for c in cameras:  # about the target, at the keyframes' distance
        assert abs(np.linalg.norm(np.subtract(c.eye, c.target)) / r0 - 1) < 1e-9, c
    frames = amrvk.render_series(one, camera_path=str(session), tf="ramp", spp=1, **SMALL)
    assert len(frames) == 5
    for k in (0, 2, 4):
        np.testing.assert_allclose(frames[k], picture(cameras[k]), atol=1e-5)
    assert np.abs(frames[2] - frames[0]).mean() > 1e-3 and np.abs(frames[2] - frames[4]).mean() > 1e-3
    # A list: one frame per camera.
    listed = amrvk.render_series(one, camera_path=[start.orbit(90), start], tf="ramp", spp=1, **SMALL)
    assert len(listed) == 2
    np.testing.assert_allclose(listed[0], picture(start.orbit(90)), atol=1e-5)
    np.testing.assert_allclose(listed[1], frames[0], atol=1e-5)
    cases = [
        (dict(camera_path=3), TypeError, "^camera_path: expected a session file or a list of amrvk.Camera"),
        (dict(camera_path=[start, "x"]), TypeError, "^camera_path: expected a session file"),
        (dict(camera_path=[]), ValueError, "^camera_path: an empty list"),
        (dict(camera_path=str(plain)), ValueError, "^camera_path: .*plain.json has no cameraPath"),
        (dict(camera_path=[start], camera=start), TypeError, "^camera: not with camera_path"),
        (dict(camera_path=[start], frames=2), TypeError, "^frames: not with camera_path"),
        (dict(camera_path=[start], orbit=90), TypeError, "^orbit: not with camera_path"),
        (dict(inputs=str(series / "s_*.cells"), camera_path=[start, start]), ValueError,
         "^camera_path: 3 data sets over 2 frames"),
    ]
    for kw, kind, pattern in cases:
        with pytest.raises(kind, match=pattern) as e:
            amrvk.render_series(**{"inputs": one, **SMALL, "spp": 1, **kw})
        assert "\n" not in str(e.value)
