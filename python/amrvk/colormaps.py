"""Colormaps by name: matplotlib's (where matplotlib is installed; Debian: python3-matplotlib) as
transfer functions, next to amrvk's built-in presets.

``TransferFunction.preset(name, ...)`` takes a built-in preset first (layers, ramp, grey, spiky, foggy,
constant, empty) and otherwise a matplotlib colormap of that name (viridis, magma, inferno, ...);
``TransferFunction.from_colormap(name, lo, hi)`` (or ``(name, volume)``) takes the colormap always.
The map's colours are taken as given (display colours, as matplotlib states them) at `nodes`
evenly spaced nodes over [lo, hi]; the opacity is that of the ``ramp`` preset over the same range
(transparent at lo, rising towards hi), so the colormap changes colours only.
"""

import math

from . import _amrvk
from .one_line_errors import _shown  # a value in a message: one short line

_builtin_preset = _amrvk.TransferFunction.preset


def _colormap(name):
    if not isinstance(name, str):
        raise TypeError(f"name: expected a preset or colormap name, got {_shown(name)}")
    try:
        import matplotlib
    except ImportError:
        raise ValueError(f"name: '{name}' is not a built-in preset, and colormaps by name need matplotlib "
                         "(Debian: python3-matplotlib)") from None
    try:
        return matplotlib.colormaps[name]
    except KeyError:
        raise ValueError(f"name: '{name}' is neither a built-in preset (layers, ramp, grey, spiky, foggy, constant, empty) "
                         "nor a matplotlib colormap (see matplotlib.colormaps)") from None


def from_colormap(name, lo, hi=None, *, nodes=16):
    """A TF with matplotlib colormap `name`'s colours and the ramp preset's opacity: over [lo, hi],
    or over a Volume's value range when `lo` is a Volume (hi omitted)."""
    import numpy as np

    cmap = _colormap(name)
    if isinstance(nodes, bool) or not isinstance(nodes, int) or not 2 <= nodes <= 4096:
        raise ValueError(f"nodes: expected a whole number in [2, 4096], got {_shown(nodes)}")
    _check_over(lo, hi)
    if isinstance(lo, _amrvk.Volume):
        if hi is not None:
            raise TypeError("hi: not given with a volume (its value range is used)")
        opacity = _builtin_preset("ramp", lo)
    else:
        if hi is None:
            raise TypeError("hi: expected a number with lo (or give a Volume instead of lo)")
        opacity = _builtin_preset("ramp", lo, hi)
    first, last = opacity.range
    positions = np.linspace(first, last, nodes).astype(np.float32)
    colors = np.asarray(cmap(np.linspace(0.0, 1.0, nodes)), dtype=np.float32)
    colors[:, 3] = opacity.evaluate(positions)[:, 3]
    return _amrvk.TransferFunction.from_nodes(positions, colors, name=name)


# The built-in presets (scene/tf_presets.cpp's makePreset); other names are colormaps.
BUILT_IN = ("ramp", "grey", "spiky", "foggy", "constant", "empty", "layers")


def _check_over(lo, hi):
    """(volume) or (lo, hi): one line naming the argument of a wrong type."""
    import numbers

    if hi is None:
        if not isinstance(lo, _amrvk.Volume):
            raise TypeError(f"volume: expected an amrvk.Volume (or lo, hi), got {_shown(lo)}")
        return
    for name, value in (("lo", lo), ("hi", hi)):
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError(f"{name}: expected a number, got {_shown(value)}")
        if not math.isfinite(value):
            raise ValueError(f"{name}: expected a finite number, got {_shown(value)}")


def preset(name, volume_or_lo=None, hi=None, **kwargs):
    """A built-in preset (``preset(name, volume)`` or ``preset(name, lo, hi)``), else the matplotlib
    colormap of that name (from_colormap)."""
    if not isinstance(name, str):
        raise TypeError(f"name: expected a preset or colormap name, got {_shown(name)}")
    _check_over(volume_or_lo, hi)
    if name in BUILT_IN:
        return _builtin_preset(name, volume_or_lo, **kwargs) if hi is None else _builtin_preset(name, volume_or_lo, hi)
    return from_colormap(name, volume_or_lo, hi, **kwargs)
