#!/usr/bin/python3
"""yt's volume renderer against amrvk on the same data set, camera and resolution (docs/benchmarks.md).

    tools/bench_yt.py OUT_DIR [DATA_SET] [--size N] [--spp N]

Each contender runs in its own fresh interpreter, so "wall from import" counts what a new notebook
pays: the imports, reading the data, building what the renderer needs, the first picture.
  yt      yt.create_scene(ds, ("gas", "density")) (log10 density, yt's default transfer function),
          a perspective lens at amrvk's default camera; render() twice (the first builds the AMR
          kd-tree and the bricks).
  amrvk   Volume.from_yt(ds, ("gas", "density"), log=True); Renderer(mode="dvr", spp=1) (the
          emission-absorption picture yt draws) and mode="ms" (multiple scattering); render twice.
Writes OUT_DIR/{yt,amrvk-dvr,amrvk-ms}.png, side-by-side.png and results.json, nothing else.
Also measures from_yt's own cost: yt reading the field for every grid against the whole from_yt.
"""
import json
import pathlib
import subprocess
import sys
import time

SOURCE = pathlib.Path(__file__).resolve().parents[1]


def yt_child(path, out, size):
    t0 = time.perf_counter()
    import numpy as np
    import yt

    yt.set_log_level(40)
    import amrvk  # only for its default camera (three-quarter view, 40 degrees), not to render

    ds = yt.load(path)
    t_load = time.perf_counter()
    sc = yt.create_scene(ds, ("gas", "density"))
    cam = sc.camera
    lo, hi = ds.domain_left_edge.d, ds.domain_right_edge.d
    view = amrvk.Camera.frame(_box(amrvk, lo, hi))
    eye, target = np.array(view.eye), np.array(view.target)
    distance = np.linalg.norm(eye - target)
    cam.set_lens("perspective")
    cam.resolution = (size, size)
    cam.set_position(ds.arr(eye, "code_length"), north_vector=ds.arr(view.up, "dimensionless"))
    cam.focus = ds.arr(target, "code_length")
    width = 2 * distance * np.tan(np.radians(view.fov) / 2)  # the image plane through the focus
    cam.set_width(ds.arr([width, width, distance], "code_length"))
    t1 = time.perf_counter()
    sc.render()
    first = time.perf_counter() - t1
    sc.save(str(out / "yt.png"), sigma_clip=4.0)
    wall = time.perf_counter() - t0
    t2 = time.perf_counter()
    sc.render()
    second = time.perf_counter() - t2
    return {"load_seconds": t_load - t0, "first_render_seconds": first, "second_render_seconds": second,
            "wall_from_import_to_first_image_seconds": wall}


def _box(amrvk, lo, hi):
    """A two-cell volume spanning [lo, hi] (only for Camera.frame's bounds)."""
    import numpy as np

    volume = amrvk.Volume.from_arrays(np.array([[0, 0, 0], [1, 1, 1]]), np.zeros(2, np.int32), np.ones(2, np.float32),
                                      origin=list(lo), spacing=list((np.asarray(hi) - lo) / 2))
    return volume


def amrvk_child(path, out, size, spp, mode):
    t0 = time.perf_counter()
    import yt

    yt.set_log_level(40)
    import amrvk

    ds = yt.load(path)
    volume = amrvk.Volume.from_yt(ds, ("gas", "density"), log=True)
    t_volume = time.perf_counter()
    lo, hi = volume.value_range
    tf = amrvk.TransferFunction.from_file(str(SOURCE / "assets/tf/cosmic-web.json")).rescaled(lo + 0.2 * (hi - lo), hi)
    options = dict(width=size, height=size, mode=mode, density_scale=0.5 if mode != "dvr" else 0.05, quiet=True,
                   background=[0.004, 0.004, 0.008])
    if mode != "dvr":
        options.update(lights=[amrvk.Light.directional([1, -1, 2], [5, 4.5, 3.8])], ambient=[0.1, 0.1, 0.14])
    r = amrvk.Renderer(volume, tf, **options)
    t_build = time.perf_counter()
    t1 = time.perf_counter()
    r.render(spp=spp)
    first = time.perf_counter() - t1
    r.save(str(out / f"amrvk-{mode}.png"))
    wall = time.perf_counter() - t0
    t2 = time.perf_counter()
    r.render(spp=spp)
    second = time.perf_counter() - t2
    return {"from_yt_seconds": t_volume - t0, "renderer_build_seconds": t_build - t_volume,
            "first_render_seconds": first, "second_render_seconds": second,
            "wall_from_import_to_first_image_seconds": wall, "spp": spp, "device": r.stats["device"],
            "gpu_seconds": r.stats["seconds"], "structure": r.structure}


def bridge_child(path):
    """from_yt's own work: the whole call against yt reading the same field grid by grid."""
    import yt

    yt.set_log_level(40)
    import amrvk

    ds = yt.load(path)
    ds.index  # the hierarchy is parsed before either timing
    t0 = time.perf_counter()
    cells = 0
    for g in ds.index.grids:
        cells += int(g[("gas", "density")].size)
    read = time.perf_counter() - t0
    ds2 = yt.load(path)
    ds2.index
    t1 = time.perf_counter()
    volume = amrvk.Volume.from_yt(ds2, ("gas", "density"), log=True)
    whole = time.perf_counter() - t1
    result = {"grid_cells": cells, "leaf_cells": volume.cells, "yt_field_read_seconds": read,
              "from_yt_seconds": whole, "overhead_seconds": whole - read,
              "overhead_seconds_per_million_leaf_cells": (whole - read) / volume.cells * 1e6}
    # A bigger block-structured set: yt's in-memory 256^3 random data in 512 grids (16.8 M cells).
    from yt.testing import fake_random_ds

    big = fake_random_ds(256, nprocs=512, fields=[("gas", "density")], units=["g/cm**3"])
    t2 = time.perf_counter()
    for g in big.index.grids:
        g[("gas", "density")]
    big_read = time.perf_counter() - t2
    big2 = fake_random_ds(256, nprocs=512, fields=[("gas", "density")], units=["g/cm**3"])
    big2.index
    t3 = time.perf_counter()
    big_volume = amrvk.Volume.from_yt(big2, ("gas", "density"))
    big_whole = time.perf_counter() - t3
    result["stream_256"] = {"leaf_cells": big_volume.cells, "yt_field_read_seconds": big_read,
                            "from_yt_seconds": big_whole,
                            "overhead_seconds_per_million_leaf_cells": (big_whole - big_read) / big_volume.cells * 1e6}
    return result


def run_child(*args):
    p = subprocess.run([sys.executable, __file__, "--child", *map(str, args)], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"bench_yt: {' '.join(map(str, args))} failed:\n{p.stderr[-3000:]}")
    return json.loads(p.stdout.strip().splitlines()[-1])


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--child":
        kind, path, out, size, spp = sys.argv[2], sys.argv[3], pathlib.Path(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6])
        result = (yt_child(path, out, size) if kind == "yt" else bridge_child(path) if kind == "bridge"
                  else amrvk_child(path, out, size, spp, kind))
        print(json.dumps(result))
        return
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("data", nargs="?", default=str(SOURCE.parent / "shared/data/amr/enzo_tiny_cosmology/DD0018/DD0018"))
    parser.add_argument("--size", type=int, default=384)
    parser.add_argument("--spp", type=int, default=16, help="samples per pixel of the ms picture (dvr: 1)")
    a = parser.parse_args()
    out = pathlib.Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    results = {"data": a.data, "size": a.size}
    results["yt"] = run_child("yt", a.data, out, a.size, 1)
    results["amrvk_dvr"] = run_child("dvr", a.data, out, a.size, 1)
    results["amrvk_ms"] = run_child("ms", a.data, out, a.size, a.spp)
    results["from_yt"] = run_child("bridge", a.data, out, a.size, 1)
    (out / "results.json").write_text(json.dumps(results, indent=1) + "\n")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    names = [("yt.png", "yt create_scene", results["yt"]), ("amrvk-dvr.png", "amrvk dvr, 1 spp", results["amrvk_dvr"]),
             ("amrvk-ms.png", f"amrvk ms, {a.spp} spp", results["amrvk_ms"])]
    fig, axes = plt.subplots(1, 3, figsize=(12, 4.8))
    for ax, (name, title, r) in zip(axes, names):
        ax.imshow(mpimg.imread(out / name))
        ax.set_title(f"{title}\nrender {r['first_render_seconds']:.2f} s / {r['second_render_seconds']:.2f} s, "
                     f"wall {r['wall_from_import_to_first_image_seconds']:.1f} s", fontsize=9)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(out / "side-by-side.png", dpi=80)
    print(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
