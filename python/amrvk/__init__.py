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

from ._amrvk import Camera, Light, Renderer, TransferFunction, Volume, devices
from . import yt_bridge as _yt_bridge

__all__ = ["Camera", "Light", "Renderer", "TransferFunction", "Volume", "devices", "show"]

Volume.from_yt = staticmethod(_yt_bridge.from_yt)


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
    """Jupyter shows a Renderer as its image so far (tone-mapped sRGB PNG)."""
    return self.png() if not self.closed and self.spp > 0 else None


def _enter(self):
    return self


def _exit(self, *exc):
    self.close()
    return False


def _one_line_type_errors(function, name):
    """pybind11 refuses arguments of the wrong type with a TypeError of many lines (every overload's
    signature, then the reprs of the arguments: whole arrays). Every error of amrvk is one line:
    "NAME: incompatible arguments (GOT); expected SIGNATURE", the arguments by type only."""

    def wrapped(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as e:
            text = str(e)
            if "incompatible function arguments" not in text and "incompatible constructor arguments" not in text:
                args = kwargs = None  # a failed __init__'s self is half made: no traceback may show it
                raise
            expected = " or ".join(line.strip().split(". ", 1)[-1].split(" -> ")[0]
                                   for line in text.splitlines()[1:] if line[:5].strip()[:1].isdigit())
            got = ", ".join([type(a).__name__ for a in args] + [f"{k}={type(v).__name__}" for k, v in kwargs.items()])
            args = kwargs = None
            raise TypeError(f"{name}: incompatible arguments ({got}); expected {expected}") from None
        except BaseException:
            args = kwargs = None
            raise

    wrapped.__doc__ = getattr(function, "__doc__", None)
    wrapped.__name__ = getattr(function, "__name__", name)
    return wrapped


def _wrap_class(cls):
    for key, member in list(vars(cls).items()):
        if key.startswith("__") and key != "__init__":
            continue
        name = f"{cls.__name__}.{key}"
        if isinstance(member, property):
            if member.fset is not None:
                setattr(cls, key, property(member.fget, _one_line_type_errors(member.fset, name), member.fdel,
                                           member.__doc__))
        elif isinstance(member, staticmethod):
            setattr(cls, key, staticmethod(_one_line_type_errors(member.__func__, name)))
        elif callable(member):
            setattr(cls, key, _one_line_type_errors(member, name))


for _cls in (Camera, Light, Renderer, TransferFunction, Volume):
    _wrap_class(_cls)
devices = _one_line_type_errors(devices, "devices")

Renderer._repr_png_ = _repr_png_
Renderer.__enter__ = _enter
Renderer.__exit__ = _exit


def show(image):
    """An image array (height, width, 3 or 4), linear radiance, as an object Jupyter displays inline."""
    import numpy as np

    class _Image:
        def __init__(self, pixels):
            self.pixels = np.ascontiguousarray(pixels, dtype=np.float32)

        def _repr_png_(self):
            return _png_of(self.pixels)

    return _Image(image)


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
