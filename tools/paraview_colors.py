#!/usr/bin/python3
"""The same colour map in ParaView 5.11 and amrvk, side by side (docs/formats.md, "Side by side
with ParaView"): Enzo DD0018's log10(Density) resampled by yt to a uniform 128^3 grid (level 2's
covering grid, a raw float32 file both tools read), volume rendered emission-absorption on black
with ParaView's "Viridis (matplotlib)" preset, one camera.

    tools/paraview_colors.py OUT_DIR [DD0018] [--amrvk PATH] [--spp N]

Needs yt (python3), Debian's paraview and python3-paraview (pvbatch) and Xvfb (ParaView's Debian
build renders through X; tests/with_xvfb.sh runs it). Writes into OUT_DIR: the raw grid, ParaView's
picture (paraview.png), the preset as ParaView holds it after rescaling (viridis.json, opacity
turned into amrvk's extinction), amrvk's pictures with --tf-colors srgb and linear, and prints the
measured colours. Then ParaView's colours of two constant slabs four cells thick seen from above
(the answers of tests/gpu/tf_colors_gpu_test.cpp): opaque with colour (0.2, 0.4, 0.6), and of
optical depth 0.7 with colour (0.9, 0.5, 0.2). ParaView's opacity a per unit distance (one cell) is extinction -ln(1 - a) per
cell in amrvk, so the two media agree at the opacity nodes.
"""
import argparse
import json
import math
import os
import subprocess
import sys

LO, HI = -30.6, -26.0
OPACITY = [(LO, 0.0), (-29.4, 0.0), (-29.0, 0.15), (-28.3, 0.6), (-27.5, 0.9), (HI, 0.95)]
CAMERA = {"eye": [330.0, -150.0, 260.0], "target": [64.0, 64.0, 64.0], "up": [0.0, 0.0, 1.0], "fov": 30.0}
PRESET = "Viridis (matplotlib)"
SIZE = 512

# Both pvbatch scripts start here: a black, unlabelled view volume rendering "value" of reader r.
PRELUDE = r'''
import json, math, sys
import paraview
from paraview.simple import *
paraview.simple._DisableFirstRenderCameraReset()
def volume_view(r, size):
    view = CreateView("RenderView")
    view.ViewSize = [size, size]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    view.OrientationAxesVisibility = 0
    d = Show(r, view)
    d.Representation = "Volume"
    ColorBy(d, ("POINTS", "value"))
    return view, d
'''

PVBATCH = PRELUDE + r'''
raw, png, out, lo, hi, opacity, cam, preset, size = sys.argv[1], sys.argv[2], sys.argv[3], *json.loads(sys.argv[4])
r = ImageReader(FileNames=[raw])
r.DataScalarType = "float"
r.DataByteOrder = "LittleEndian"
r.DataExtent = [0, 127, 0, 127, 0, 127]
r.DataOrigin = [0.5, 0.5, 0.5]  # point data at amrvk's cell centres
r.DataSpacing = [1.0, 1.0, 1.0]
r.ScalarArrayName = "value"
view, d = volume_view(r, size)
lut = GetColorTransferFunction("value")
lut.ApplyPreset(preset, True)
lut.RescaleTransferFunction(lo, hi)
GetOpacityTransferFunction("value").Points = [v for x, a in opacity for v in (x, a, 0.5, 0.0)]
d.ScalarOpacityUnitDistance = 1.0
d.Shade = 0
view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = cam["eye"], cam["target"], cam["up"]
view.CameraViewAngle = cam["fov"]
Render(view)
SaveScreenshot(png, view, ImageResolution=[size, size])
space = str(lut.ColorSpace).strip("'")
json.dump([{"Name": preset, "ColorSpace": space, "RGBPoints": list(lut.RGBPoints),
            "Points": [v for x, a in opacity for v in (x, -math.log(1.0 - a), 0.5, 0.0)]}], open(out, "w"))
'''


SLAB = PRELUDE + r'''
raw, png, rgb, opacity, unit = sys.argv[1], sys.argv[2], *json.loads(sys.argv[3])
r = ImageReader(FileNames=[raw])
r.DataScalarType = "float"
r.DataByteOrder = "LittleEndian"
r.DataExtent = [0, 63, 0, 63, 0, 4]  # points 0..4: four cells thick
r.ScalarArrayName = "value"
view, d = volume_view(r, 32)
GetColorTransferFunction("value").RGBPoints = [0, *rgb, 2, *rgb]
GetOpacityTransferFunction("value").Points = [0, opacity, 0.5, 0, 2, opacity, 0.5, 0]
d.ScalarOpacityUnitDistance = unit
d.Shade = 0
view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [31.5, 31.5, 100], [31.5, 31.5, 0], [0, 1, 0]
view.CameraViewAngle = 2
Render(view)
SaveScreenshot(png, view, ImageResolution=[32, 32])
'''


def slabs(out, xvfb):
    import numpy as np
    from PIL import Image

    raw = os.path.join(out, "slab.raw")
    np.ones((5, 64, 64), np.float32).tofile(raw)
    script = os.path.join(out, "pvbatch_slab.py")
    with open(script, "w") as f:
        f.write(SLAB)
    tau = 0.7
    for name, rgb, opacity, unit, answer in [
            ("opaque", [0.2, 0.4, 0.6], 1.0, 0.01, "amrvk: 51 102 153"),
            ("tau 0.7", [0.9, 0.5, 0.2], 1 - math.exp(-tau / 4), 1.0,
             "display-space c(1-exp(-tau)) = 115.5 64.2 25.7; amrvk: encode(decode(c)(1-exp(-tau))) = 169 92 35")]:
        png = os.path.join(out, f"slab-{name.replace(' ', '')}.png")
        subprocess.run(["bash", xvfb, "1024x768x24", "pvbatch", script, raw, png, json.dumps([rgb, opacity, unit])],
                       check=True)
        px = np.asarray(Image.open(png).convert("RGB")).reshape(-1, 3)
        print(f"ParaView slab {name}: colour {rgb}, pixels {px.min(0)} .. {px.max(0)}; {answer}")


def resample(data_set, raw):
    import numpy as np
    import yt

    ds = yt.load(data_set)
    g = ds.covering_grid(level=2, left_edge=ds.domain_left_edge, dims=ds.domain_dimensions * 4)
    d = np.log10(g["gas", "density"].to_ndarray()).astype(np.float32)
    np.ascontiguousarray(d.transpose(2, 1, 0)).tofile(raw)  # x fastest, as amrvk's raw reader reads


def measure(out):
    import numpy as np
    from PIL import Image

    def load(name):
        return np.asarray(Image.open(os.path.join(out, name)).convert("RGB")).astype(float)

    pv, srgb, linear = load("paraview.png"), load("amrvk-srgb.png"), load("amrvk-linear.png")
    gas = (pv.sum(2) > 60) & (srgb.sum(2) > 60)

    def blocks(im, b=16):
        h, w = im.shape[:2]
        return im.reshape(h // b, b, w // b, b, -1).mean((1, 3))

    inside = blocks(gas[..., None].astype(float))[..., 0] > 0.9
    print(f"pixels where both show gas: {gas.sum()}; 16x16 blocks wholly inside: {inside.sum()}")
    for name, im in [("paraview", pv), ("amrvk srgb", srgb), ("amrvk linear", linear)]:
        m = im[gas]
        sat = ((m.max(1) - m.min(1)) / np.maximum(m.max(1), 1)).mean()
        line = f"{name:13s} mean RGB {m.mean(0).round(1)}  saturation {sat:.3f}"
        if im is not pv:
            d = np.abs(blocks(im) - blocks(pv))[inside]
            line += f"  |block mean - paraview| median {np.median(d, 0).round(1)} p90 {np.percentile(d, 90, 0).round(1)}"
        print(line)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out")
    p.add_argument("data_set", nargs="?", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared", "data",
                                                               "amr", "enzo_tiny_cosmology", "DD0018", "DD0018"))
    p.add_argument("--amrvk", default=os.path.join(os.path.dirname(__file__), "..", "build", "bin", "amrvk"))
    p.add_argument("--spp", type=int, default=32)
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    raw = os.path.join(a.out, "enzo_128x128x128_float32.raw")
    if not os.path.exists(raw):
        resample(a.data_set, raw)
    script = os.path.join(a.out, "pvbatch_colors.py")
    with open(script, "w") as f:
        f.write(PVBATCH)
    tf = os.path.join(a.out, "viridis.json")
    xvfb = os.path.join(os.path.dirname(__file__), "..", "tests", "with_xvfb.sh")
    subprocess.run(["bash", xvfb, "1024x768x24", "pvbatch", script, raw, os.path.join(a.out, "paraview.png"), tf,
                    json.dumps([LO, HI, OPACITY, CAMERA, PRESET, SIZE])], check=True)
    camera = [str(v) for v in CAMERA["eye"] + CAMERA["target"] + CAMERA["up"]]
    for colors in ("srgb", "linear"):
        subprocess.run([a.amrvk, "render", raw, "--tf", tf, "--tf-colors", colors, "--mode", "ae", "--background",
                        "0", "0", "0", "--density-scale", "1", "--camera", *camera, "--fov", str(CAMERA["fov"]),
                        "--size", f"{SIZE}x{SIZE}", "--spp", str(a.spp), "-o",
                        os.path.join(a.out, f"amrvk-{colors}.png")], check=True)
    measure(a.out)
    slabs(a.out, xvfb)


if __name__ == "__main__":
    sys.exit(main())
