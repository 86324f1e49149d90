"""Series and movies from Python, as ``amrvk render`` makes them (docs/movies.md): one frame per
data set of a time series (a glob, a list of paths, or a yt ``DatasetSeries``), or a turntable of
one data set; every frame with the same camera, settings and TF range; frames as arrays, numbered
image files, or an MP4 (Debian's ffmpeg). The planning is the command line's (session/series.cpp:
natural order of a glob's matches, a turntable's azimuths, the frame files); each frame is one
Renderer, all on one device.

TF range (`tf_range`): ``"first"`` (the first data set's value range, this function's default),
``"union"`` (every data set's: a pass over them first, one in memory at a time; the CLI's default,
``--series-range union``) or ``(lo, hi)``.
`tf`: None (the layers preset), a preset or colormap name, fitted over that range; or a
TransferFunction, used as it is (its own range is the one range). As the CLI fits them: over
several data sets, spiky, foggy and layers follow the percentiles and volume histogram of the
first one ("first") or of all of them pooled ("union"); a turntable's preset is fitted to its data
set like one picture.
"""
import numbers
import os
import tempfile

from . import _amrvk
from .colormaps import preset
from .one_line_errors import _shown  # a value in a message: one short line


def _is_yt(item):
    return hasattr(item, "index") and hasattr(item, "domain_dimensions")


def _sources(inputs):
    """The series' data sets in order: paths (globs expanded, natural order) or yt data sets."""
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    if hasattr(inputs, "piter") or (isinstance(inputs, (list, tuple)) and inputs and all(_is_yt(d) for d in inputs)):
        return inputs, True  # a yt DatasetSeries (loads each data set as it is iterated) or data sets
    if not isinstance(inputs, (list, tuple)) or not all(isinstance(p, (str, os.PathLike)) for p in inputs):
        raise TypeError("inputs: expected a path or glob, a list of them, a yt DatasetSeries or a list of yt data "
                        f"sets, got {type(inputs).__name__}")
    return _amrvk._expand_inputs([os.fspath(p) for p in inputs]), False


def _volume(source, from_yt, field, log):
    if from_yt:
        from .yt_bridge import from_yt as make

        if field is None:
            raise TypeError("field: a yt series needs a field, e.g. ('gas', 'density')")
        return make(source, field, log=log)
    return _amrvk.Volume(source, field=field or "", scale="log" if log else "linear")


def _range(tf_range, volume_of, order):
    """The one TF range of the series over the data sets `order` names (indices into the inputs),
    and the percentiles of each data set it was taken from (None for a given range)."""
    if isinstance(tf_range, str):
        if tf_range not in ("first", "union"):
            raise ValueError(f"tf_range: '{tf_range}' is not 'first', 'union' or (lo, hi)")
        ranges, parts = [], []
        for i in order[:1] if tf_range == "first" else sorted(set(order)):
            ranges.append(volume_of(i).value_range)
            parts.append(_amrvk._distribution(volume_of(i)))
        return min(r[0] for r in ranges), max(r[1] for r in ranges), parts
    if (not isinstance(tf_range, (tuple, list)) or len(tf_range) != 2
            or not all(isinstance(x, numbers.Real) and not isinstance(x, bool) for x in tf_range)):
        raise TypeError(f"tf_range: expected 'first', 'union' or (lo, hi), got {_shown(tf_range)}")
    lo, hi = map(float, tf_range)
    if not lo < hi:
        raise ValueError(f"tf_range: {lo:g} is not below {hi:g}")
    return lo, hi, None


def _path_cameras(camera_path, camera, frames, orbit):
    """The camera of every frame and the path's fps (None: a list gives none) from `camera_path`: a
    session file with a "cameraPath" (each frame's camera as amrvk render takes it) or a list of
    amrvk.Camera, one per frame."""
    for name, value in (("camera", camera), ("frames", frames), ("orbit", orbit)):
        if value is not None:
            raise TypeError(f"{name}: not with camera_path (the path gives every frame's camera and the frame count)")
    if isinstance(camera_path, (str, os.PathLike)):
        path = _amrvk._session_camera_path(os.fspath(camera_path))
        if path is None:
            raise ValueError(f"camera_path: {os.fspath(camera_path)} has no cameraPath (keyframes saved by the viewer)")
        return list(path[0]), path[1]
    if not isinstance(camera_path, (list, tuple)) or not all(isinstance(c, _amrvk.Camera) for c in camera_path):
        raise TypeError("camera_path: expected a session file or a list of amrvk.Camera (one per frame), got "
                        f"{_shown(camera_path)}")
    if not camera_path:
        raise ValueError("camera_path: an empty list (one amrvk.Camera per frame)")
    return list(camera_path), None


def render_series(inputs, out=None, *, field=None, log=False, tf=None, tf_range="first", spp=None, camera=None,
                  frames=None, orbit=None, camera_path=None, fps=None, progress=None, **options):
    """Renders a series and returns its frames: a list of float32 (H, W, 4) arrays when `out` is
    None, else the files written (numbered frames: ``"frames/f_%04d.png"`` or a directory), or
    ``[out]`` for an MP4 (``"movie.mp4"``, at `fps` frames per second).

    inputs: a path or glob ("output_*"), a list of them, a yt DatasetSeries or a list of yt data
      sets (`field` then names a yt field: ``("gas", "density")``); field/log: as Volume(path,
      field=, scale="log") or from_yt(..., log=True).
    frames, orbit: a turntable of one data set, `frames` frames over `orbit` degrees; with a series,
      `orbit` degrees spread over its frames.
    camera: every frame's (before its orbit); default: the view that frames the first data set.
    camera_path: a session file whose "cameraPath" gives frame k's camera (as `amrvk render --session
      FILE -o movie.mp4` renders it: the same cameras, the same frame count, its fps unless `fps` is
      given), or a list of amrvk.Camera, one per frame; not with camera, frames or orbit. Over a
      series of S data sets, frame k of N shows data set floor(k * S / N).
    fps: the movie's frames per second (default: the session path's, else 24).
    options: Renderer's (width, height, mode, density_scale, legend, ...); `legend` draws into PNGs.
    progress: callable(frame, frames) after each frame.
    """
    if orbit is not None and (isinstance(orbit, bool) or not isinstance(orbit, numbers.Real)):
        raise TypeError(f"orbit: expected degrees (a number), got {_shown(orbit)}")
    if frames is not None and (isinstance(frames, bool) or not isinstance(frames, int)):
        raise TypeError(f"frames: expected a whole number, got {_shown(frames)}")
    path_cameras, path_fps = _path_cameras(camera_path, camera, frames, orbit) if camera_path is not None else (None, None)
    if fps is None:
        fps = path_fps if path_fps is not None else 24.0
    movie = out is not None and os.fspath(out).lower().endswith(".mp4")
    if movie:  # before any frame is rendered (issue 52, point 17: refused after all of them)
        if isinstance(fps, bool) or not isinstance(fps, numbers.Real):
            raise TypeError(f"fps: expected frames per second (a number), got {_shown(fps)}")
        if not 0 < fps <= 1000:
            raise ValueError(f"fps: {fps:g} is outside (0, 1000]")
    sources, from_yt = _sources(inputs)
    # A DatasetSeries is indexed (ts[i] loads data set i when asked), never loaded whole.
    names = [str(i) for i in range(len(sources))] if from_yt else sources
    if path_cameras is None:
        plan = _amrvk._plan_frames(names, frames, orbit is not None)  # the CLI's checks and turntables
        order = [names.index(p) for p in plan]  # the input of each frame
    else:  # as amrvk render plans a camera path's frames
        if len(names) > len(path_cameras):
            raise ValueError(f"camera_path: {len(names)} data sets over {len(path_cameras)} frames: some would show in "
                             "no frame")
        order = [_amrvk._step_of_frame(k, len(path_cameras), len(names)) for k in range(len(path_cameras))]
    count = len(order)
    scratch = tempfile.TemporaryDirectory(prefix="amrvk-movie-") if movie else None
    created, written, done = [], [], False
    try:
        pattern, files = (None, None)
        if out is not None:
            target = os.path.join(scratch.name, "f_%06d.png") if movie else os.fspath(out)
            pattern, files = _amrvk._frame_files(target, count)
            created = _make_dirs(os.path.dirname(files[0]) or ".")
        cache = {}

        def volume_of(i):
            if i not in cache:
                cache.clear()  # one data set in memory at a time (a turntable keeps its one)
                cache[i] = _volume(sources[i], from_yt, field, log)
            return cache[i]

        lo, hi, parts = _range(tf_range, volume_of, order)
        if tf is None or isinstance(tf, str):
            name = tf or "layers"
            if parts is not None and len(set(order)) == 1:
                tf = preset(name, volume_of(order[0]))  # a turntable: fitted like one picture
            elif parts is not None and name in ("spiky", "foggy", "layers"):
                tf = _amrvk._series_preset(name, parts)
            else:
                tf = preset(name, lo, hi)
        elif not isinstance(tf, _amrvk.TransferFunction):
            raise TypeError(f"tf: expected None, a preset or colormap name or an amrvk.TransferFunction, got {_shown(tf)}")
        first = camera if camera is not None or path_cameras is not None else _amrvk.Camera.frame(volume_of(order[0]))
        images = []
        for k in range(count):
            if path_cameras is not None:
                view = path_cameras[k]
            else:
                view = first.orbit(_amrvk._frame_azimuth(k, count, float(orbit))) if orbit else first
            with _amrvk.Renderer(volume_of(order[k]), tf, view, **{"quiet": True, **options}) as r:
                image = r.render(spp=spp) if spp is not None else r.render()
                if files is None:
                    images.append(image)
                else:
                    r.save(files[k])
                    written.append(files[k])
            if progress is not None:
                progress(k + 1, count)
        if files is None:
            done = True
            return images
        if movie:
            _amrvk._encode_mp4(pattern, count, float(fps), os.fspath(out))
            done = True
            return [os.fspath(out)]
        done = True
        return files
    finally:
        if scratch is not None:
            scratch.cleanup()
        if not done and not movie:  # a failed series leaves nothing it made (issue 52, point 9)
            for f in written:
                try:
                    os.remove(f)
                except OSError:
                    pass
            for d in reversed(created):
                try:
                    os.rmdir(d)  # only where empty: never what the user put there
                except OSError:
                    pass


def _make_dirs(path):
    """os.makedirs(path, exist_ok=True), returning the directories it created, outermost first."""
    missing = []
    path = os.path.abspath(path)
    while not os.path.isdir(path):
        missing.append(path)
        parent = os.path.dirname(path)
        if parent == path:
            break
        path = parent
    missing.reverse()
    for d in missing:
        os.makedirs(d, exist_ok=True)
    return missing
