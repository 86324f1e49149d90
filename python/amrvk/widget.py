"""A Jupyter widget (ipywidgets; Debian: python3-ipywidgets) that shows a Renderer's progressive
image and orbits it with sliders: ``amrvk.Widget(renderer, spp=256)`` as a cell's last expression.

Where the renderer holds no sample it first shows the renderer's first frame (the picture
ray-marched; Renderer.first_frame), and again after each slider move. A background thread adds
`batch` samples per pixel at a time until the image has `spp`; the first frame stays on screen until
the path-traced image's noise (mean relative standard error) is as low as the first frame's, or
below 0.05 where the first frame's is lower, or the image has `spp` (never a grainier picture
than the one it replaces); from then on the image (the PNG that ``renderer.png()`` makes, legend
included where the renderer has one) and the samples and mean standard error so far are shown
after each batch. Moving a slider sets the renderer's
camera from the camera it had when the widget was made: turned by `azimuth` degrees about the
target around the up vector, then by `elevation` degrees over the view's right vector, then
`zoom` times closer (Camera.orbit, Camera.zoom); the estimate restarts and refines again. Only
sliders: orbiting by mouse drag needs a browser-side event widget (ipyevents) that Debian lacks.
``close()`` stops the thread (the renderer stays open); the renderer serves one call at a time, in
the order they come, so using it from the notebook while the widget refines is safe: a long
``r.render(spp=4096)`` yields to the widget between its quarter-second chunks, and a slider moved
meanwhile restarts that call's count (it returns the samples it was asked for, of the new view).
With `series` (a glob or a list of paths) a step slider shows each data set of a time series with
the same camera, TF and settings (``Renderer.input``), its first frame first.
Works with ipywidgets 6 (Debian 12), 7 and 8: it uses Image, FloatSlider, IntSlider, Label, Layout,
HBox and VBox and ``observe(names="value")``, which all three have.
"""
import math
import os
import threading
import time

import numpy as np

from . import _amrvk
from .cameras import orbit, zoom
from .one_line_errors import _shown  # a value in a message: one short line


class Widget:
    def __init__(self, renderer, spp=256, batch=4, series=None):
        try:
            import ipywidgets
        except ImportError:
            raise ImportError("amrvk.Widget needs ipywidgets (Debian: python3-ipywidgets)") from None
        if not isinstance(renderer, _amrvk.Renderer):
            raise TypeError(f"renderer: expected an amrvk.Renderer, got {type(renderer).__name__}")
        for name, value, hi in (("spp", spp, 1 << 24), ("batch", batch, 1 << 24)):
            if isinstance(value, bool) or not isinstance(value, int):
                raise TypeError(f"{name}: expected a whole number in [1, {hi}], got {_shown(value)}")
            if not 1 <= value <= hi:
                raise ValueError(f"{name}: {value} is outside [1, {hi}]")
        self.renderer = renderer
        self.spp = spp
        self.batch = batch
        self.base = renderer.camera
        w = ipywidgets
        # At the image's own size, not stretched to the cell's width (issue 52, point 13).
        width, height = renderer.size
        self.image = w.Image(format="png", layout=w.Layout(width=f"{width}px", height=f"{height}px"))
        self.azimuth = w.FloatSlider(value=0.0, min=-180.0, max=180.0, step=1.0, description="azimuth")
        self.elevation = w.FloatSlider(value=0.0, min=-80.0, max=80.0, step=1.0, description="elevation")
        self.zoom = w.FloatSlider(value=1.0, min=0.25, max=4.0, step=0.05, description="zoom")
        self.status = w.Label(layout=w.Layout(width="auto"))  # the whole line, not cut to 72 px
        for slider in (self.azimuth, self.elevation, self.zoom):
            slider.observe(self._moved, names="value")
        rows = [self.image, w.HBox([self.azimuth, self.elevation, self.zoom])]
        # A time series: a step slider over the data sets (a glob or a list of paths, natural order);
        # a step shows that data set with the same camera, TF and settings (Renderer.input).
        self.series = None
        if series is not None:
            if isinstance(series, (str, os.PathLike)):
                series = [series]
            if not isinstance(series, (list, tuple)) or not all(isinstance(p, (str, os.PathLike)) for p in series):
                raise TypeError(f"series: expected a glob or a list of paths, got {type(series).__name__}")
            if renderer.input is None:
                raise ValueError("series: the renderer shows arrays or yt data, not a file a step can replace")
            self.series = _amrvk._expand_inputs([os.fspath(p) for p in series])
            shown = os.path.abspath(renderer.input)
            at = next((k for k, p in enumerate(self.series) if os.path.abspath(p) == shown), None)
            if at is None:
                renderer.input, at = self.series[0], 0
            self.step = w.IntSlider(value=at, min=0, max=len(self.series) - 1, step=1, description="step")
            self.step_label = w.Label(value=os.path.basename(self.series[at]))
            self.step.observe(self._stepped, names="value")
            rows.append(w.HBox([self.step, self.step_label]))
        self.box = w.VBox(rows + [self.status])
        self.first_frame = None  # the PNG shown before any sample: the renderer's dvr first frame
        self.shown = None  # what the image is: "first frame" or "estimate"
        self._shown_spp = 0  # the samples of the image shown
        self._hold = renderer.spp == 0  # the first frame stays until the estimate is as clean
        self._restarted = False  # a slider restarted the estimate: a first frame of the new view next
        if renderer.spp == 0:  # shown at once, while the first batch runs
            self._show_first_frame()
        else:  # the samples it has, shown at once (issue 52, point 12: with spp already reached it stayed blank)
            self._show()
        self._wake = threading.Event()
        self._idle = threading.Event()
        self._stop = False
        self._error = None
        self._thread = threading.Thread(target=self._refine, name="amrvk.Widget", daemon=True)
        self._thread.start()

    def camera(self):
        """The camera the sliders give: the first camera orbited, raised and zoomed."""
        turned = orbit(self.base, self.azimuth.value)
        forward = np.subtract(turned.target, turned.eye)
        right = np.cross(forward, turned.up)
        raised = orbit(turned, self.elevation.value, axis=right.tolist()) if self.elevation.value else turned
        return zoom(raised, self.zoom.value)

    def _moved(self, change):
        self._idle.clear()
        self.renderer.camera = self.camera()  # restarts the estimate
        self._restarted = True
        self._wake.set()

    def _stepped(self, change):
        self._idle.clear()
        path = self.series[self.step.value]
        self.renderer.input = path  # read and built; the estimate starts again
        self.step_label.value = os.path.basename(path)
        self._restarted = True
        self._wake.set()

    def _show_first_frame(self):
        png = self.renderer.png()  # without a sample: the first frame, made now
        f = self.renderer.first_frame
        if f is None:  # another call added samples meanwhile: those are shown next
            return
        self.first_frame = self.image.value = png
        self.shown = "first frame"
        self._hold = True
        self.status.value = f"first frame (dvr, {f['spp']} spp, dt {f['dt']:g}, noise {f['noise']:.3g}); path tracing"

    def _refine(self):
        r = self.renderer
        try:
            while not self._stop and not r.closed:
                if r.spp < self.spp:
                    self._idle.clear()
                    if self._restarted:
                        self._restarted = False
                        if r.spp == 0:
                            self._show_first_frame()
                    left = self.spp - r.spp  # another call may have added samples meanwhile
                    if left > 0:
                        r.accumulate(min(self.batch, left))
                    self._show()
                else:
                    if r.spp != self._shown_spp:  # another call (a long render) changed the image
                        self._show()
                    self._idle.set()
                    self._wake.wait(0.25)
                    self._wake.clear()
        except Exception as e:  # shown in the status line; wait() raises it
            self._error = e
            self.status.value = f"stopped: {type(e).__name__}: {e}"
        finally:
            self._idle.set()

    def _show(self):
        # One call reads the count, the image and its error together (issue 52, point 15: a long
        # render() on the same renderer added samples between three calls, "16/64" over 72).
        r = self.renderer
        if r.closed:
            return
        try:
            s = r._shown(self.spp, self._hold)  # the first frame until the estimate is as clean
        except ValueError:
            if r.closed:
                return
            raise
        if s["spp"] == 0:  # no sample yet, or a slider restarted the estimate meanwhile
            return
        self._shown_spp = s["spp"]
        if s["shown"] == "first frame":
            noise = "not measured" if s["noise"] is None else f"noise {s['noise']:.3g}"
            self.status.value = (f"first frame (dvr, noise {s['first_frame_noise']:.3g}) shown until the estimate is "
                                 f"as clean: {s['spp']}/{self.spp} spp, {noise}")
            return
        self._hold = False  # shown once, the estimate stays until a slider restarts it
        self.shown = "estimate"
        self.image.value = s["png"]
        noise = f", mean standard error {s['error']:.4g}" if s["error"] is not None else ""
        self.status.value = f"{s['spp']}/{self.spp} spp{noise}"

    def wait(self, timeout=None):
        """Blocks until the image has `spp` samples per pixel and is shown (True), or `timeout` seconds
        passed (False)."""
        if timeout is not None and (isinstance(timeout, bool) or not isinstance(timeout, (int, float))
                                    or math.isnan(timeout)):
            raise TypeError(f"timeout: expected a number of seconds or None, got {type(timeout).__name__}")
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            left = 0.1 if deadline is None else max(0.0, min(0.1, deadline - time.monotonic()))
            idle = self._idle.wait(left)
            if self._error is not None:
                raise self._error
            # Idle with fewer samples: a slider has just restarted the estimate; the thread goes on.
            # Idle with another image than shown: another call changed it; the thread shows it next.
            r = self.renderer
            if idle and (r.closed or (r.spp >= self.spp and r.spp == self._shown_spp)):
                return True
            if deadline is not None and time.monotonic() >= deadline:
                return False
            if idle:
                time.sleep(0.01)

    def close(self):
        """Stops refining (the renderer stays open)."""
        self._stop = True
        self._wake.set()
        self._thread.join()
        self.box.close()

    def _ipython_display_(self):
        from IPython.display import display

        display(self.box)

    def _repr_png_(self):
        """Where no widget can be shown (nbconvert, a static notebook): the image so far."""
        return self.image.value or None

    def __repr__(self):
        return (f"Widget({self.renderer.spp}/{self.spp} spp, azimuth {self.azimuth.value:g}, "
                f"elevation {self.elevation.value:g}, zoom {self.zoom.value:g})")
