"""yt's default volume rendering beside amrvk's default picture (docs/python.md, section 1).

    /usr/bin/python3 tools/yt_side_by_side.py OUT_DIR [DATA_DIR]

For Enzo DD0018, AMReX PeleLM and the RAMSES galaxy (DATA_DIR: ../shared/data/amr beside the
checkout), each in its own process after yt.load: yt.create_scene(ds, field) at 384x384 and its
first render (the AMR kd-tree, the default TF, the render); amrvk's first picture with the
defaults: Volume.from_yt(ds, field), Renderer(...) and the PNG a notebook shows (the dvr first
frame, 2 spp); then path tracing's refinement on the same renderer, render(spp=16) (ms). Writes
into OUT_DIR only: each picture, results.jsonl (wall seconds and amrvk's noise, the mean relative
standard error over the visible pixels) and yt-default-vs-amrvk.png (one row per data set).
"""
import json
import pathlib
import subprocess
import sys
import time

SIDE = 384
SETS = [("enzo", "enzo_tiny_cosmology/DD0018/DD0018", ("gas", "density")),
        ("amrex", "amrex_pelelm_3d/example_plt_3d", ("boxlib", "temp")),
        ("ramses", "ramses_galaxy_3d/output_00010", ("gas", "density"))]


def one(name, path, field, out):
    import yt
    import amrvk
    yt.set_log_level(40)
    ds = yt.load(path)
    ds.index
    res = {"data": name, "field": list(field)}
    t0 = time.perf_counter()
    sc = yt.create_scene(ds, field)
    sc.camera.resolution = SIDE
    sc.render()
    res["yt_s"] = time.perf_counter() - t0
    sc.save(str(out / f"{name}-yt.png"), sigma_clip=None)
    t0 = time.perf_counter()
    vol = amrvk.Volume.from_yt(ds, field)
    t1 = time.perf_counter()
    r = amrvk.Renderer(vol, width=SIDE, height=SIDE, quiet=True)
    t2 = time.perf_counter()
    png = r._repr_png_()  # what the notebook shows: the dvr first frame
    t3 = time.perf_counter()
    res.update(amrvk_first_s=t3 - t0, amrvk_first_noise=r.first_frame["noise"], first_frame=r.first_frame, from_yt_s=t1 - t0,
               renderer_s=t2 - t1, first_frame_s=t3 - t2)
    (out / f"{name}-amrvk-first.png").write_bytes(png)
    t0 = time.perf_counter()
    r.render(spp=16)  # path tracing refines it
    res.update(amrvk_ms_s=time.perf_counter() - t0, amrvk_ms_noise=r.noise)
    r.save(str(out / f"{name}-amrvk-ms.png"))
    res["volume"] = repr(vol)
    return res


def montage(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(len(rows), 3, figsize=(9.6, 3.3 * len(rows)))
    for i, r in enumerate(rows):
        n = r["data"]
        cols = [(f"{n}-yt.png", f"yt create_scene + render: {r['yt_s']:.1f} s"),
                (f"{n}-amrvk-first.png",
                 f"amrvk first picture (dvr): {r['amrvk_first_s']:.1f} s, noise {r['amrvk_first_noise']:.3f}"),
                (f"{n}-amrvk-ms.png", f"then ms, 16 spp: +{r['amrvk_ms_s']:.1f} s, noise {r['amrvk_ms_noise']:.2f}")]
        for j, (f, title) in enumerate(cols):
            ax[i][j].imshow(mpimg.imread(str(out / f)))
            ax[i][j].set_title(title, fontsize=8)
            ax[i][j].axis("off")
        ax[i][0].text(-0.04, 0.5, n, transform=ax[i][0].transAxes, rotation=90, va="center", ha="right")
    fig.tight_layout()
    fig.savefig(str(out / "yt-default-vs-amrvk.png"), dpi=80)


def main():
    if len(sys.argv) == 5 and sys.argv[1] == "--one":  # a child: one data set
        _, _, name, path, out = sys.argv
        field = next(f for n, _, f in SETS if n == name)
        print(json.dumps(one(name, path, field, pathlib.Path(out))))
        return
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: yt_side_by_side.py OUT_DIR [DATA_DIR]")
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    data = pathlib.Path(sys.argv[2]) if len(sys.argv) == 3 else pathlib.Path(__file__).resolve().parents[2] / "shared/data/amr"
    rows = []
    for name, rel, _ in SETS:
        p = subprocess.run([sys.executable, __file__, "--one", name, str(data / rel), str(out)],
                           capture_output=True, text=True, check=True)
        rows.append(json.loads(p.stdout.strip().splitlines()[-1]))
        print(rows[-1], flush=True)
    (out / "results.jsonl").write_text("".join(json.dumps(r) + "\n" for r in rows))
    montage(rows, out)


if __name__ == "__main__":
    main()
