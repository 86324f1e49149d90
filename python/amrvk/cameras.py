"""Camera helpers: orbit and zoom about the target, and conversion from and to yt's camera.

World space is code_length, in amrvk's readers and in the yt bridge alike, so a yt camera's
position and focus are amrvk's eye and target. yt's default lens is plane-parallel (an
orthographic view ``width`` wide); amrvk's camera is a pinhole, so the conversion keeps the eye,
target and up and takes the field of view that shows yt's height (``width[1]``) at the focus:
``fov = 2 atan(width[1] / 2 / distance)``. The other way, ``to_yt`` sets yt's position, focus,
north vector and a width that shows the same height at the focus.
"""
import math

from . import _amrvk
from .one_line_errors import _shown  # a value in a message: one short line

Camera = _amrvk.Camera


def _number(value, name):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise TypeError(f"{name}: expected a finite number, got {_shown(value)}")
    return float(value)


def orbit(camera, degrees, axis=None):
    """The camera turned by `degrees` about its target, around `axis` (default its up vector),
    counter-clockwise seen from the axis' tip; target, up and fov kept."""
    import numpy as np

    angle = math.radians(_number(degrees, "degrees"))
    try:
        k = np.asarray(camera.up if axis is None else axis, dtype=np.float64)
    except (TypeError, ValueError):
        k = None  # not numbers: 'z', [1, 'a', 0]
    if k is None or k.shape != (3,) or not np.all(np.isfinite(k)) or not np.linalg.norm(k) > 0:
        raise ValueError(f"axis: expected 3 finite numbers, not all 0, got {_shown(axis)}")
    k = k / np.linalg.norm(k)
    target = np.asarray(camera.target)
    v = np.asarray(camera.eye) - target
    # Rodrigues' rotation of the eye's offset from the target.
    turned = v * math.cos(angle) + np.cross(k, v) * math.sin(angle) + k * np.dot(k, v) * (1 - math.cos(angle))
    return Camera((target + turned).tolist(), camera.target, camera.up, camera.fov)


def zoom(camera, factor):
    """The camera `factor` times closer to its target (2: half the distance; 0.5: twice as far)."""
    f = _number(factor, "factor")
    if not f > 0:
        raise ValueError(f"factor: {_shown(factor)} must be > 0")
    eye = [t + (e - t) / f for e, t in zip(camera.eye, camera.target)]
    return Camera(eye, camera.target, camera.up, camera.fov)


def from_yt(yt_camera):
    """An amrvk Camera from a yt camera (``scene.camera`` of ``yt.create_scene``)."""
    import numpy as np

    try:
        eye = np.asarray(yt_camera.position.to("code_length").d, dtype=np.float64)
        target = np.asarray(yt_camera.focus.to("code_length").d, dtype=np.float64)
        up = np.asarray(yt_camera.north_vector, dtype=np.float64)
        height = float(yt_camera.width[1].to("code_length").d)
    except AttributeError:
        raise TypeError(f"yt_camera: expected a yt Camera (scene.camera), got {type(yt_camera).__name__}") from None
    distance = float(np.linalg.norm(eye - target))
    if not distance > 0:
        raise ValueError("yt_camera: its position and focus coincide")
    if not (math.isfinite(height) and height > 0):
        raise ValueError(f"yt_camera: its width's height {height:g} must be finite and > 0")
    fov = math.degrees(2 * math.atan(0.5 * height / distance))
    return Camera(eye.tolist(), target.tolist(), up.tolist(), fov)


def to_yt(camera, yt_camera):
    """Sets a yt camera (``scene.camera``) to this camera's position, focus, north vector and a width
    that shows the same height at the focus; returns the yt camera."""
    import numpy as np

    ds = getattr(getattr(yt_camera, "data_source", None), "ds", None)
    if ds is None or not hasattr(yt_camera, "set_position"):
        raise TypeError(f"yt_camera: expected a yt Camera (scene.camera), got {type(yt_camera).__name__}")
    eye, target = np.asarray(camera.eye), np.asarray(camera.target)
    distance = float(np.linalg.norm(eye - target))
    height = 2 * distance * math.tan(math.radians(camera.fov) / 2)
    yt_camera.focus = ds.arr(target, "code_length")
    yt_camera.set_position(ds.arr(eye, "code_length"), north_vector=list(camera.up))
    aspect = float(yt_camera.width[0] / yt_camera.width[1]) if yt_camera.width[1] > 0 else 1.0
    yt_camera.width = ds.arr([height * aspect, height, float(yt_camera.width[2].to("code_length").d)], "code_length")
    return yt_camera
