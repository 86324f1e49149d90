"""amrvk: unbiased volumetric path tracing of adaptive-mesh-refinement data on any Vulkan device.

Three lines from a data set to a picture::

    import amrvk
    r = amrvk.Renderer(amrvk.Volume("DD0018/DD0018", field="Density"), density_scale=0.05)
    image = r.render(spp=64)          # numpy float32 (height, width, 4), row 0 = top, linear radiance

or from yt: ``amrvk.Volume.from_yt(ds, ("gas", "density"), log=True)``. docs/python.md has a
worked session. Every call goes through the same entry as ``amrvk render`` (a picture
description fitted to the data), so a Renderer renders what the command line renders and saves
the same session files (``save_session``; ``amrvk view --session FILE`` opens them).
"""

from ._amrvk import Camera, Light, Renderer, TransferFunction, Volume, devices, _initialized
from . import one_line_errors as _one_line_errors

_one_line_errors.install([Camera, Light, Renderer, TransferFunction, Volume], _initialized)
devices = _one_line_errors.wrap_function(devices, "devices")
from . import cameras as _cameras
from . import colormaps as _colormaps
from . import yt_bridge as _yt_bridge
from .series import render_series
from .widget import Widget

__all__ = ["Camera", "Light", "Renderer", "TransferFunction", "Volume", "Widget", "devices", "render_series", "show"]

Volume.from_yt = staticmethod(_yt_bridge.from_yt)
TransferFunction.preset = staticmethod(_colormaps.preset)
TransferFunction.from_colormap = staticmethod(_colormaps.from_colormap)
Camera.orbit = _cameras.orbit
Camera.zoom = _cameras.zoom
Camera.from_yt = staticmethod(_cameras.from_yt)
Camera.to_yt = _cameras.to_yt


def _renderer_orbit(self, degrees, axis=None):
    """Turns the renderer's camera by `degrees` about its target (Camera.orbit); the estimate restarts."""
    self.camera = self.camera.orbit(degrees, axis)
    return self


def _renderer_zoom(self, factor):
    """Moves the renderer's camera `factor` times closer to its target (Camera.zoom)."""
    self.camera = self.camera.zoom(factor)
    return self


Renderer.orbit = _renderer_orbit
Renderer.zoom = _renderer_zoom


def _progress_arg(progress):
    """progress=True: a tqdm bar where tqdm is installed (Debian: python3-tqdm), else a stderr line."""
    if progress is True:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            import sys

            def line(done, total):
                sys.stderr.write(f"\ramrvk: {done}/{total} spp")
                if done >= total:
                    sys.stderr.write("\n")
                sys.stderr.flush()

            return line, None
        bar = tqdm(unit="spp")

        def update(done, total):
            bar.total = total
            bar.n = done
            bar.refresh()

        return update, bar
    if progress is None or progress is False:
        return None, None
    if not callable(progress):
        raise TypeError("progress: expected True, False, None or a callable(done, total)")
    return progress, None


def _with_progress(method):
    def wrapped(self, *args, progress=None, **kwargs):
        callback, bar = _progress_arg(progress)
        try:
            return method(self, *args, progress=callback, **kwargs)
        finally:
            if bar is not None:
                bar.close()

    wrapped.__doc__ = method.__doc__
    wrapped.__name__ = method.__name__
    return wrapped


Renderer.render = _with_progress(Renderer.render)
Renderer.accumulate = _with_progress(Renderer.accumulate)


def _repr_png_(self):
    """Jupyter shows a Renderer as its image so far (tone-mapped sRGB PNG); before any sample, its
    first frame (the same TF ray-marched, a clean picture in about a second; first_frame)."""
    return None if self.closed else self.png()


def _enter(self):
    return self


def _exit(self, *exc):
    self.close()
    return False



Renderer._repr_png_ = _repr_png_
Renderer.__enter__ = _enter
Renderer.__exit__ = _exit


def show(image):
    """An image array (height, width, 3 or 4), linear radiance, as an object Jupyter displays inline."""
    import numpy as np

    try:
        pixels = np.asarray(image)
    except Exception:
        raise TypeError(f"image: expected an array (height, width, 3 or 4), got {type(image).__name__}") from None
    if pixels.dtype.kind not in "iuf":
        raise TypeError(f"image: expected numbers, got dtype {pixels.dtype}")
    if pixels.ndim != 3 or pixels.shape[2] not in (3, 4) or pixels.shape[0] < 1 or pixels.shape[1] < 1:
        raise ValueError(f"image: expected shape (height, width, 3) or (height, width, 4), got {pixels.shape}")

    class _Image:
        def __init__(self, pixels):
            self.pixels = np.ascontiguousarray(pixels, dtype=np.float32)

        def _repr_png_(self):
            return _png_of(self.pixels)

    return _Image(pixels)


def _png_of(pixels):
    import io
    import numpy as np

    rgb = np.clip(pixels[..., :3], 0.0, 1.0)
    srgb = np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * np.power(rgb, 1.0 / 2.4) - 0.055)
    rgba = np.concatenate([np.round(srgb * 255.0), np.full(rgb.shape[:2] + (1,), 255.0)], axis=2).astype(np.uint8)
    import matplotlib.image

    buffer = io.BytesIO()
    matplotlib.image.imsave(buffer, rgba, format="png")
    return buffer.getvalue()
