"""yt's default volume rendering beside amrvk's default picture (docs/python.md, section 1).

    /usr/bin/python3 tools/yt_side_by_side.py OUT_DIR [DATA_DIR]

For Enzo DD0018, AMReX PeleLM and the RAMSES galaxy (DATA_DIR: ../shared/data/amr beside the
checkout), each in its own process after yt.load: yt.create_scene(ds, field) at 384x384 and its
first render (the AMR kd-tree, the default TF, the render); amrvk's Volume.from_yt(ds, field)
with the defaults, rendered by multiple scattering at 16 spp and ray-marched (dvr) at 4 spp. Writes
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
    for mode, spp in (("ms", 16), ("dvr", 4)):
        t0 = time.perf_counter()
        vol = amrvk.Volume.from_yt(ds, field)
        r = amrvk.Renderer(vol, width=SIDE, height=SIDE, mode=mode, quiet=True)
        r.render(spp=spp)
        res[f"amrvk_{mode}_s"] = time.perf_counter() - t0
        res[f"amrvk_{mode}_noise"] = r.noise
        r.save(str(out / f"{name}-amrvk-{mode}.png"))
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
                (f"{n}-amrvk-ms.png", f"amrvk ms, 16 spp: {r['amrvk_ms_s']:.1f} s, noise {r['amrvk_ms_noise']:.2f}"),
                (f"{n}-amrvk-dvr.png", f"amrvk dvr, 4 spp: {r['amrvk_dvr_s']:.1f} s, noise {r['amrvk_dvr_noise']:.3f}")]
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
