#!/usr/bin/python3
"""docs/python.md's worked session, run as a script: python_tour.py OUT_DIR [DATA_DIR].

Writes the session's pictures (PNG) and one session file into OUT_DIR and nothing elsewhere;
prints what a notebook would show. Needs the built module (PYTHONPATH=build/python, or the .pth
file tools/run.sh installs), numpy and yt; the real data beside the checkout (../shared/data/amr).
"""
import pathlib
import sys
import time

t_import = time.perf_counter()
import numpy as np  # noqa: E402
import yt  # noqa: E402

import amrvk  # noqa: E402

if len(sys.argv) < 2:
    sys.exit("usage: python_tour.py OUT_DIR [DATA_DIR]")
out = pathlib.Path(sys.argv[1])
out.mkdir(parents=True, exist_ok=True)
source = pathlib.Path(__file__).resolve().parents[1]
data = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else source.parent / "shared" / "data" / "amr"
yt.set_log_level(40)


def step(title):
    print(f"\n## {title}")


# 1. Three lines from yt to a picture ------------------------------------------------------------
step("1. yt data set -> amrvk image")
ds = yt.load(str(data / "enzo_tiny_cosmology/DD0018/DD0018"))
vol = amrvk.Volume.from_yt(ds, ("gas", "density"))   # log10, as yt takes densities
r = amrvk.Renderer(vol, width=384, height=384)
r.save(out / "1-first-picture.png")  # no sample yet: the first frame, what a notebook shows of r
print(vol, "|", vol.units, "| first picture", f"{time.perf_counter() - t_import:.1f} s after import:", r.first_frame)
print("structure:", r.structure, *r.notes)
t = time.perf_counter()
image = r.render(spp=16)  # path tracing refines it
print(image.shape, image.dtype, f"| ms, 16 spp: {time.perf_counter() - t:.1f} s, noise {r.noise:.3f}")
r.save(out / "1-path-traced.png")

# 2. A transfer function and light ---------------------------------------------------------------
step("2. transfer function, lights, multiple scattering")
lo, hi = vol.value_range
tf = amrvk.TransferFunction.from_file(str(source / "assets/tf/cosmic-web.json")).rescaled(-29.5, hi)
r.tf = tf
r.mode = "ms"
r.density_scale = 0.5
r.lights = [amrvk.Light.directional([1, -1, 2], [5, 4.5, 3.8])]
r.ambient = [0.1, 0.1, 0.14]
r.background = [0.004, 0.004, 0.008]  # escaping rays see a dark sky instead of the ambient light
image = r.render(spp=32, progress=False)
print(f"{r.spp} spp, {r.stats['pathsPerSecond'] / 1e6:.2f} M paths/s on {r.stats['device']}")
r.save(out / "2-lit.png")

# 3. More samples continue the same estimate -----------------------------------------------------
step("3. accumulate: the same estimate, less noise")
noise_before = float(np.sqrt(r.variance().mean()))
r.accumulate(96)
noise_after = float(np.sqrt(r.variance().mean()))
print(f"{r.spp} spp: mean standard error {noise_before:.4f} -> {noise_after:.4f}")
r.save(out / "3-128spp.png")

# 4. A derived field ------------------------------------------------------------------------------
step("4. a derived field: velocity magnitude")
speed = amrvk.Volume.from_yt(ds, ("gas", "velocity_magnitude"))
lo, hi = speed.value_range
print(speed, "|", speed.units, f"| {lo:.3g} .. {hi:.3g}")
with amrvk.Renderer(speed, amrvk.TransferFunction.preset("ramp", 0.3 * hi, hi), width=384, height=384,
                    mode="ss", density_scale=2.0, lights=r.lights, ambient=[0.05, 0.05, 0.07],
                    background=r.background) as s:
    s.render(spp=48)
    s.save(out / "4-velocity-magnitude.png")

# 5. Octree data (RAMSES) -------------------------------------------------------------------------
step("5. octree data: RAMSES through yt's leaf-cell selection")
galaxy = yt.load(str(data / "ramses_galaxy_3d/output_00010/info_00010.txt"))
gas = amrvk.Volume.from_yt(galaxy, ("gas", "density"), log=True)
print(gas, "|", gas.units, "| cells per level (0 = finest):", gas.summary()["cells_per_level"])
lo, hi = gas.value_range
view = amrvk.Camera.frame(gas)
closer = amrvk.Camera([t + 0.45 * (e - t) for e, t in zip(view.eye, view.target)], view.target, view.up, view.fov)
with amrvk.Renderer(gas, tf.rescaled(lo + 0.55 * (hi - lo), hi), closer, width=384, height=384, mode="ms",
                    density_scale=0.3, lights=r.lights, ambient=[0.1, 0.1, 0.14], background=r.background) as g:
    g.render(spp=32)
    g.save(out / "5-ramses-galaxy.png")

# 6. Cells from numpy ----------------------------------------------------------------------------
step("6. a volume from numpy arrays")
n = 32  # a 32^3 grid of level-1 cells with a refined (level-0) octant
i, j, k = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
coarse = np.stack([i, j, k], axis=-1).reshape(-1, 3) * 2
keep = ~np.all(coarse < n, axis=1)  # the octant x, y, z < 16 coarse cells is refined
fi, fj, fk = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
fine = np.stack([fi, fj, fk], axis=-1).reshape(-1, 3)
lower = np.concatenate([coarse[keep], fine])
level = np.concatenate([np.ones(keep.sum(), np.int32), np.zeros(len(fine), np.int32)])
centre = (lower + 0.5 * 2.0 ** level[:, None]) / (2 * n) - 0.5
values = np.exp(-40 * (np.linalg.norm(centre, axis=1) - 0.3) ** 2).astype(np.float32)
shell = amrvk.Volume.from_arrays(lower, level, values, field="shell")
print(shell, shell.summary()["cells_per_level"])
with amrvk.Renderer(shell, amrvk.TransferFunction.preset("ramp", 0.2, 1.0), width=256, height=256, mode="ss",
                    density_scale=4.0, lights=r.lights, background=r.background) as b:
    b.render(spp=32)
    b.save(out / "6-numpy-shell.png")
r.close()

# 7. amrvk's own readers, and sessions -----------------------------------------------------------
step("7. amrvk's own reader; a session file for amrvk view and amrvk render")
native = amrvk.Volume(str(data / "enzo_tiny_cosmology/DD0018/DD0018"), field="Density")
print(native, "|", native.summary()["cells_per_level"])
with amrvk.Renderer(native, amrvk.TransferFunction.preset("ramp", 0, 4), width=128, height=128) as n:
    n.render(spp=4)
    n.save_session(out / "tour.session.json")  # amrvk view --session FILE opens this picture
    again = amrvk.Renderer.from_session(str(out / "tour.session.json"))
    print("from_session:", again.size, again.mode, again.tf.name, again.camera == n.camera)
    again.close()
print(f"\nwhole session {time.perf_counter() - t_import:.1f} s from import")
