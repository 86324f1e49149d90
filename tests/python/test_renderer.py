"""The Renderer: it renders what `amrvk render` renders for the same description, continues an
estimate, follows every edit, saves images and sessions the command line reads, releases the GIL
while the device works, stops on Ctrl-C within a second, and refuses a closed renderer."""
import json
import os
import pathlib
import select
import shutil
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from conftest import SAMPLE, SOURCE, amrvk_binary, run_cli

# The bundled cloud as these tests were written for it (not the first picture's defaults): linear
# values, the ramp over [0.3, 2] and a white background.
SMALL = dict(width=32, height=24, density_scale=3.0, tf_range=(0.3, 2.0), grid="16", background=(1, 1, 1), quiet=True)
CLI_SMALL = ["--scale", "linear", "--tf", "ramp", "--background", "1", "1", "1"]


def picture(amrvk, **kw):
    kw.setdefault("tf", amrvk.TransferFunction.preset("ramp", 0.3, 2.0))
    return amrvk.Renderer(amrvk.Volume(str(SAMPLE), scale="linear"), **{**SMALL, **kw})


def test_it_renders_what_the_command_line_renders(amrvk, tmp_path):
    r = picture(amrvk, mode="ss", seed=3, lights=[amrvk.Light.directional([1, -1, 2], [3, 3, 3])])
    image = r.render(spp=8)
    assert image.shape == (24, 32, 4) and image.dtype == np.float32
    assert np.all(image[..., 3] == 1.0)
    run_cli("render", SAMPLE, *CLI_SMALL, "--size", "32x24", "--density-scale", "3", "--tf-range", "0.3", "2", "--grid", "16",
            "--mode", "ss", "--seed", "3", "--light-dir", "1", "-1", "2", "3", "3", "3", "--spp", "8",
            "-o", tmp_path / "cli.pfm")
    from amrvk import _amrvk  # noqa: F401  (the reader below is the command line's own PFM)
    cli = read_pfm(tmp_path / "cli.pfm")
    assert np.max(np.abs(cli - image[..., :3]) / np.maximum(np.abs(cli), 1e-3)) < 1e-5, "same samples, same image"
    stats = r.stats
    assert stats["spp"] == 8 and stats["width"] == 32 and stats["mode"] == "ss"
    assert stats["majorantViolations"] == 0 and stats["densityLookups"] > 0
    assert abs(stats["meanRGB"][0] - float(image[..., 0].mean())) < 1e-5


def read_pfm(path):
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4").reshape(h, w, 3)
    return data[::-1]  # PFM rows run bottom to top


def test_accumulate_continues_the_same_estimate(amrvk):
    r = picture(amrvk)
    whole = r.render(spp=8).copy()
    r.reset()
    assert r.spp == 0
    r.accumulate(3)
    r.accumulate(5)
    assert r.spp == 8
    assert np.max(np.abs(r.image() - whole)) < 1e-5
    var = r.variance()
    assert var.shape == (24, 32, 3) and np.all(var >= 0) and var.max() > 0


def test_render_until_a_target_noise(amrvk):
    # render(until=E): checks at 16 spp and each doubling, stops at the first whose noise is at most
    # E (spp the cap); noise is the mean relative standard error of the visible pixels, recomputed
    # here from the image and its variance.
    r = picture(amrvk)
    assert r.noise is None
    r.render(spp=4096, until=0.03)
    assert 16 < r.spp < 4096 and (r.spp & (r.spp - 1)) == 0, r.spp  # doubled, then stopped early
    m, v = r.image()[..., :3].mean(axis=2), r.variance().mean(axis=2)
    n = m.size
    visible = (m > 0) & (m >= np.sort(m.ravel())[min(n - 1, int(0.99 * n))] / 256)
    mine = float(np.mean(np.sqrt(v[visible]) / m[visible]))
    assert r.noise <= 0.03 and abs(mine - r.noise) < 1e-3 * r.noise + 1e-5, (mine, r.noise)
    r.render(spp=8, until=1e-6)
    assert r.spp == 8 and r.noise > 1e-6  # capped
    for bad, kind, text in ((0, ValueError, "until: 0 is outside (0, 1]"), ("a", TypeError, "until: expected")):
        with pytest.raises(kind, match=text.replace("(", r"\(").replace(")", r"\)").replace("[", r"\[")):
            r.render(spp=8, until=bad)


def test_every_edit_follows_the_session(amrvk, tmp_path):
    r = picture(amrvk)
    base = r.render(spp=4).copy()
    cam = r.camera
    r.camera = amrvk.Camera([c * 1.3 for c in cam.eye], cam.target, cam.up, 30.0)
    moved = r.render(spp=4)
    assert np.abs(moved - base).max() > 1e-2
    r.camera = cam
    r.density_scale = 6.0
    r.mode = "ae"
    r.seed = 5
    r.lights = [amrvk.Light.point([256, 256, 900], [20, 20, 20])]
    r.tf = amrvk.TransferFunction.preset("foggy", 0.3, 2.0)
    r.size = (16, 12)
    r.background = [0.1, 0.2, 0.3]
    r.g = 0.4
    r.transmittance = "ubrm"
    r.control_extinction = "minorant"
    assert r.background == [0.1, 0.2, 0.3] and r.g == 0.4 and r.transmittance == "ubrm"
    assert r.control_extinction == "minorant"
    r.set_structure(traversal="abr", sampler="abr", backend="sw")
    assert r.structure["traversal"] == "abr" and r.structure["sampler"] == "abr"
    edited = r.render(spp=4)
    assert edited.shape == (12, 16, 4)
    r.save_session(tmp_path / "s.json")
    s = json.loads((tmp_path / "s.json").read_text())
    assert s["render"]["mode"] == "ae" and s["render"]["densityScale"] == 6.0 and s["image"]["width"] == 16
    assert s["structure"]["traversal"] == "abr" and s["transferFunction"]["Name"] == "foggy"
    assert s["render"]["background"] == [0.1, 0.2, 0.3] and s["render"]["g"] == 0.4
    assert s["render"]["transmittance"] == "ubrm" and s["render"]["controlExtinction"] == "minorant"
    # The command line renders the saved session as this renderer does (same seed: same samples).
    run_cli("render", "--session", tmp_path / "s.json", "--spp", "4", "-o", tmp_path / "s.pfm")
    assert np.max(np.abs(read_pfm(tmp_path / "s.pfm") - edited[..., :3])) < 1e-4
    again = amrvk.Renderer.from_session(str(tmp_path / "s.json"), quiet=True)
    assert np.max(np.abs(again.render(spp=4) - edited)) < 1e-5
    # A rejected edit changes nothing.
    with pytest.raises(ValueError, match="^sampler dense needs traversal grid-dda or grid-bvh"):
        r.set_structure(sampler="dense")
    assert r.structure["sampler"] == "abr"
    with pytest.raises(ValueError, match=r"^density_scale: -1 is outside \[0, inf\)"):
        r.density_scale = -1
    assert r.density_scale == 6.0
    with pytest.raises(ValueError, match="^background"):
        r.background = [0, -1, 0]
    assert r.background == [0.1, 0.2, 0.3]
    with pytest.raises(ValueError, match="^mode: 'pt' is not one of"):
        r.mode = "pt"
    with pytest.raises(ValueError, match="^transmittance: 'delta' is not one of ratio"):
        r.transmittance = "delta"
    assert r.transmittance == "ubrm"
    with pytest.raises(ValueError, match="^control_extinction: 'mean' is not one of none"):
        r.control_extinction = "mean"
    assert r.control_extinction == "minorant"


def test_a_renderer_with_no_sample_shows_its_dvr_first_frame(amrvk):
    # The first frame is the same picture ray-marched at 2 spp with the step it reports: a dvr
    # renderer of the same description at that dt gives it sample for sample (independently: it
    # is that renderer's own render).
    r = picture(amrvk, mode="ms", seed=5)
    assert r.first_frame is None, "not made until shown"
    first = r.image()
    f = r.first_frame
    assert f["mode"] == "dvr" and f["spp"] == 2 and f["frames"] >= 1 and f["gpu_seconds"] > 0
    halvings = round(np.log2(0.5 / f["dt"]))  # from the session's 0.5, at least once per frame after the first
    assert f["dt"] == 0.5 / 2 ** halvings and halvings >= f["frames"] - 1 and (halvings == 0) == (f["frames"] == 1)
    dvr = picture(amrvk, mode="dvr", seed=5, dt=f["dt"]).render(spp=2)
    assert np.max(np.abs(first - dvr)) < 1e-6 * max(1.0, float(np.abs(dvr).max()))
    assert r.spp == 0 and r.mode == "ms", "the renderer's own mode and (empty) image stay"
    assert 0 < f["noise"] < 1
    assert f["noise"] <= 0.05 or f["frames"] > 1 or f["gpu_seconds"] * 3 > 1.0, "refined while noisy and cheap"
    assert f"shown: the dvr first frame, 2 spp, dt {f['dt']:g}, noise" in repr(r)
    ms = picture(amrvk, mode="ms", seed=5).render(spp=2)
    assert np.abs(first - ms)[..., :3].mean() > 1e-3, "the first frame is not the path-traced image"
    assert r.png() == r._repr_png_() and r._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    # Path tracing then refines it: from the first sample on the image is the renderer's own.
    image = r.render(spp=2)
    assert np.max(np.abs(image - ms)) < 1e-6 * max(1.0, float(np.abs(ms).max()))
    assert r.first_frame is None and "first frame" not in repr(r)
    # An edit that empties the image makes the next first frame anew, for the new picture.
    r.density_scale = 1.0
    assert r.spp == 0 and r.first_frame is None
    again = r.image()
    g = r.first_frame
    thinner = picture(amrvk, mode="dvr", seed=5, density_scale=1.0, dt=g["dt"]).render(spp=2)
    assert np.max(np.abs(again - thinner)) < 1e-6 * max(1.0, float(np.abs(thinner).max()))
    assert np.abs(again - first)[..., :3].mean() > 1e-4
    # A dvr renderer shows a first frame too, and then renders with its own step (0.5), not the
    # first frame's.
    d = picture(amrvk, mode="dvr", seed=5)
    d.image()
    assert d.spp == 0 and d.first_frame is not None
    own = picture(amrvk, mode="dvr", seed=5).render(spp=2)
    assert np.max(np.abs(d.render(spp=2) - own)) < 1e-6 * max(1.0, float(np.abs(own).max()))


def test_images_sessions_and_notebooks(amrvk, tmp_path):
    r = picture(amrvk)
    assert r._repr_png_() == r.png() and r.spp == 0, "nothing rendered yet: the first frame"
    r.render(spp=2)
    for name in ("a.png", "a.exr", "a.pfm"):
        r.save(str(tmp_path / name))
        assert (tmp_path / name).stat().st_size > 0
    png = r._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and png == r.png()
    assert (tmp_path / "a.png").read_bytes() == png
    shown = amrvk.show(r.image())._repr_png_()
    assert shown[:8] == b"\x89PNG\r\n\x1a\n"
    with pytest.raises(ValueError, match="unknown image extension '.jpg'"):
        r.save(str(tmp_path / "a.jpg"))
    arrays = amrvk.Renderer(amrvk.Volume.from_arrays(np.zeros((1, 3), np.int32), np.zeros(1, np.int32),
                                                     np.ones(1, np.float32)), width=8, height=8, quiet=True)
    with pytest.raises(ValueError, match="made from arrays"):
        arrays.save_session(str(tmp_path / "x.json"))


def test_outputs_never_replace_the_data_they_were_rendered_from(amrvk, tmp_path):
    # A copy of the sample (the check failing must not touch the repository's own file).
    for ext in (".cells", ".scalars"):
        shutil.copy(SAMPLE.with_suffix(ext), tmp_path / f"cloud{ext}")
    cells = tmp_path / "cloud.cells"
    before = cells.read_bytes()
    (tmp_path / "out.pfm").symlink_to(cells)
    r = amrvk.Renderer(amrvk.Volume(str(cells), scale="linear"), width=8, height=8, grid="16", quiet=True)
    r.render(spp=1)
    with pytest.raises(ValueError, match=r"save .*out.pfm.* is the input the volume's data .*cloud.cells"):
        r.save(str(tmp_path / "out.pfm"))
    with pytest.raises(ValueError, match=r"save_session .* is the input the volume's data .*cloud.scalars"):
        r.save_session(str(tmp_path / "cloud.scalars"))
    assert cells.read_bytes() == before and (tmp_path / "out.pfm").is_symlink()
    again = amrvk.Renderer.from_session(str(session_of(r, tmp_path)), quiet=True)
    with pytest.raises(ValueError, match="is the input the volume's data"):
        again.save(str(cells))
    r.save(str(tmp_path / "fine.pfm"))  # anything else is written


def session_of(r, tmp_path):
    path = tmp_path / "s.json"
    r.save_session(str(path))
    return path


def test_progress_and_the_fitted_choices(amrvk):
    calls = []
    r = picture(amrvk)
    r.render(spp=6, progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (6, 6) and all(t == 6 for _, t in calls)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)
    r.render(spp=2, progress=True)  # tqdm or a stderr line, whichever is there
    sparse = amrvk.Volume.from_arrays(np.array([[0, 0, 0], [4095, 0, 0], [0, 0, 4095]]), np.zeros(3, np.int32),
                                      np.array([1, 2, 3], np.float32))
    fitted = amrvk.Renderer(sparse, width=8, height=8, quiet=True)
    assert fitted.notes[0].startswith("traversal abr and sampler abr"), fitted.notes
    assert fitted.structure["traversal"] == "abr"


def test_a_closed_renderer_refuses_every_call(amrvk):
    with picture(amrvk) as r:
        r.render(spp=1)
    assert r.closed
    for call in (lambda: r.render(spp=1), r.image, lambda: r.stats, r.reset, lambda: r.camera):
        with pytest.raises(ValueError, match="the renderer is closed"):
            call()


def test_close_from_another_thread_raises_instead_of_crashing(amrvk, tmp_path):
    # Issue 52, point 2: threads looping png(), image(), save() or variance() while another calls
    # close() killed the interpreter (SIGSEGV in PathTracePass::read: a thread that had passed the
    # closed check waited for the device lock while close() freed the renderer). Three threads a
    # call, so that some wait on the lock when it closes; each must end with ValueError.
    calls = {"png": lambda r, k: r.png(), "image": lambda r, k: r.image(), "variance": lambda r, k: r.variance(),
             "save": lambda r, k: r.save(str(tmp_path / f"x{k}.pfm"))}
    for name, call in calls.items():
        for _ in range(2):
            r = picture(amrvk, width=16, height=16)
            r.render(spp=2)
            outcomes, running = [], threading.Barrier(4)

            def loop(k):
                running.wait(30)
                try:
                    while True:
                        call(r, k)
                except ValueError as e:
                    outcomes.append(str(e))

            threads = [threading.Thread(target=loop, args=(k,)) for k in range(3)]
            for t in threads:
                t.start()
            running.wait(30)
            time.sleep(0.05)
            r.close()
            for t in threads:
                t.join(30)
            assert not any(t.is_alive() for t in threads), name
            assert outcomes == ["the renderer is closed"] * 3, (name, outcomes)


def test_settings_edited_while_a_first_frame_is_made_keep_the_mode(amrvk):
    # Issue 52, point 11: png() before any sample makes the ray-marched first frame, switching the
    # renderer to dvr while it runs; an edit from another thread then copied dvr into the settings
    # for good. Edits now read the settings under the device lock.
    r = picture(amrvk, width=24, height=16, mode="ms")
    stop = threading.Event()

    def shows():
        while not stop.is_set():
            r.png()  # each edit resets the image: every call makes a first frame

    t = threading.Thread(target=shows)
    t.start()
    try:
        for k in range(40):
            r.density_scale = 2.0 + 0.01 * k
            time.sleep(0.005)
    finally:
        stop.set()
        t.join(60)
    assert r.mode == "ms" and r.stats["mode"] != "dvr"
    r.close()


def test_the_gil_is_released_while_the_device_works(amrvk):
    # A thread that sleeps 1 ms per tick needs the GIL once a tick: while C code holds the GIL it
    # counts about one tick per chunk (a quarter second), and about 1,800 a second when the device
    # work runs with the GIL released (a busy counter would not tell: it counts thousands in the
    # gaps between chunks even when the GIL is held).
    r = picture(amrvk, width=96, height=96)
    r.render(spp=1)  # the pipelines are built and the first chunk's cost is known
    start = time.time()
    r.render(spp=8)
    spp = int(min(max(8 * 2.0 / (time.time() - start), 16), 1 << 16))  # about 2 s on this device
    counter = [0]
    stop = threading.Event()

    def count():
        while not stop.is_set():
            time.sleep(0.001)
            counter[0] += 1

    t = threading.Thread(target=count)
    t.start()
    start = time.time()
    r.render(spp=spp)
    elapsed = time.time() - start
    stop.set()
    t.join()
    assert elapsed > 0.5, f"{spp} spp took {elapsed:.2f} s: too short to tell a held GIL from a released one"
    assert counter[0] > max(100, 0.2 * elapsed * 1000), (
        f"a thread sleeping 1 ms per tick counted {counter[0]} ticks in {elapsed:.2f} s ({spp} spp): "
        "the render holds the GIL while the device works")


def test_ctrl_c_stops_a_long_render_within_a_second(tmp_path):
    script = tmp_path / "long.py"
    script.write_text(
        "import signal, sys, time, amrvk\n"
        # A shell that starts jobs in the background hands them SIGINT ignored, and Python then
        # installs no handler: give the child the one an interactive Python has.
        "signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        f"r = amrvk.Renderer(amrvk.Volume({str(SAMPLE)!r}, scale='linear'), width=256, height=256, quiet=True)\n"
        "r.render(spp=1)\n"
        "print('ready', flush=True)\n"
        "try:\n"
        "    r.render(spp=100000)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', r.spp, flush=True)\n"
    )
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    p = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True, env=env)

    def line_within(seconds):
        # A line from the child, or a failure (and the child killed) after `seconds`: never a hang.
        if not select.select([p.stdout], [], [], seconds)[0]:
            p.kill()
            p.wait()
            pytest.fail(f"no output from the child within {seconds} s")
        return p.stdout.readline()

    try:
        assert line_within(600).strip() == "ready"
        time.sleep(1.0)
        sent = time.time()
        p.send_signal(signal.SIGINT)
        line = line_within(60).split()
        stopped = time.time() - sent
        p.wait(timeout=30)
    finally:
        if p.poll() is None:
            p.kill()
    assert line[:1] == ["interrupted"], line
    assert stopped < 1.0, f"{stopped:.2f} s after Ctrl-C"
    assert int(line[1]) < 100000


def test_devices(amrvk):
    devices = amrvk.devices()
    assert any(d["usable"] for d in devices)
    assert all({"name", "type", "ray_query", "rounding_mode_rte_float32", "reject_reason"} <= set(d) for d in devices)
    assert all(d["rounding_mode_rte_float32"] for d in devices if d["usable"])


def test_cut_aways_follow_the_command_line_and_the_session(amrvk, tmp_path):
    crop = ([0, 0, 0], [512, 512, 256])
    clip = [([256, 256, 256], [1, 1, 0])]
    r = picture(amrvk, crop=crop, clip=clip, seed=4)
    assert r.crop == crop and r.clip == clip
    cut = r.render(spp=4).copy()
    run_cli("render", SAMPLE, *CLI_SMALL, "--size", "32x24", "--density-scale", "3", "--tf-range", "0.3", "2", "--grid", "16",
            "--seed", "4", "--crop", "0", "0", "0", "512", "512", "256", "--clip", "256", "256", "256", "1", "1", "0",
            "--spp", "4", "-o", tmp_path / "cli.pfm")
    assert np.max(np.abs(read_pfm(tmp_path / "cli.pfm") - cut[..., :3])) < 1e-4, "same cut, same samples"
    r.save_session(tmp_path / "s.json")
    s = json.loads((tmp_path / "s.json").read_text())
    assert s["cut"]["crop"] == {"lo": [0.0, 0.0, 0.0], "hi": [512.0, 512.0, 256.0]}
    assert s["cut"]["clip"] == [{"point": [256.0, 256.0, 256.0], "normal": [1.0, 1.0, 0.0]}]
    # Removing the cut brings the whole picture back; a bad cut changes nothing.
    r.crop = None
    r.clip = []
    assert r.crop is None and r.clip == []
    assert np.abs(r.render(spp=4) - cut).max() > 1e-2
    with pytest.raises(ValueError, match="^crop: lower corner 5 is not below upper corner 1 on axis x"):
        r.crop = ([5, 0, 0], [1, 1, 1])
    assert r.crop is None
    with pytest.raises(ValueError, match="^clip: at most 4 planes"):
        r.clip = [([0, 0, 0], [1, 0, 0])] * 5


def test_a_bad_sample_count_is_one_line_naming_the_keyword(amrvk):
    """spp and n take the CLI's --spp range, [1, 2^24]; 0 rendered a black image and 10**9 was
    accepted, and -1 or 2.5 gave pybind11's list of signatures."""
    import re
    r = picture(amrvk)
    bad = [(0, ValueError, "spp: 0 is outside [1, 16777216]"),
           (1 << 24 | 1, ValueError, "spp: 16777217 is outside [1, 16777216]"),
           (10**9, ValueError, "spp: 1000000000 is outside"),
           (10**30, ValueError, "spp: 1000000000000000000000000000000 is outside"),
           (-1, ValueError, "spp: -1 is outside"),
           (2.5, TypeError, "spp: expected a whole number in [1, 16777216], got 2.5"),
           (True, TypeError, "spp: expected a whole number in [1, 16777216], got True"),
           ("8", TypeError, "spp: expected a whole number in [1, 16777216], got '8'")]
    for spp, kind, message in bad:
        with pytest.raises(kind, match=re.escape(message)) as e:
            r.render(spp=spp)
        assert "\n" not in str(e.value), str(e.value)
    with pytest.raises(ValueError, match=re.escape("n: -5 is outside [1, 16777216]")):
        r.accumulate(-5)
    with pytest.raises(ValueError, match=re.escape("n: 0 is outside [1, 16777216]")):
        r.accumulate(0)
    assert r.spp == 0  # nothing was rendered by the refused calls
    with pytest.raises(ValueError, match=re.escape("spp: 0 is outside [1, 16777216]")):
        picture(amrvk, spp=0)
    # The edges of the range are accepted.
    r.render(spp=1)
    assert r.spp == 1
    r.accumulate(1)
    assert r.spp == 2


def test_reprs_say_what_a_scientist_checks(amrvk):
    """Volume, TransferFunction, Renderer and Light print their content, not `<... object at 0x...>`
    (issue 33, point 3): field, cells, levels, value range, world bounds; the TF's name, nodes and
    range; the renderer's size, mode, TF, samples so far and their mean standard error."""
    v = amrvk.Volume(str(SAMPLE), scale="linear")
    levels = sum(1 for n in v.summary()["cells_per_level"] if n > 0)
    lo, hi = v.value_range
    assert repr(v) == (f"Volume({SAMPLE}, field 'scalars', {v.cells} cells on {levels} levels, "
                       f"values {lo:.4g}..{hi:.4g}, world (0, 0, 0)..(512, 512, 512))")
    tf = amrvk.TransferFunction.preset("ramp", 0.3, 2.0)
    assert repr(tf) == f"TransferFunction('ramp', {len(tf.nodes[0])} nodes over [0.3, 2], alpha up to 1)"
    r = picture(amrvk)
    assert repr(r) == (f"Renderer({SAMPLE} 'scalars', 32x24 ms, tf 'ramp' over [0.3, 2], density_scale 3, "
                       "0 spp so far, grid-dda/grid/sw)")
    r.render(spp=4)
    error = float(np.sqrt(r.variance()).mean())
    text = repr(r)
    assert ", 4 spp so far, mean standard error " in text, text
    assert abs(float(text.split("mean standard error ")[1].split(",")[0]) - error) <= 1e-3 * error + 1e-6, text
    assert repr(amrvk.Light.directional([1, -1, 2], [5, 4.5, 3.8])) == "Light.directional((1, -1, 2), radiance (5, 4.5, 3.8))"
    r.close()
    assert repr(r) == "Renderer(closed)"
