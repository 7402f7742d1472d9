"""A stand-in for bpy.types.RenderEngine with the methods render_loop.render_frame() and drive() call, so tests can
press Esc (test_break) at chosen moments and inspect the result handed back, which Blender's own engine cannot do
in the background (-b never breaks)."""

import time

import numpy as np


class FakeRect:
    def __init__(self):
        self.data = None

    def foreach_set(self, buf):
        assert buf.ndim == 2 and buf.shape[1] == 4   # Blender 3.4 crashes on flat arrays
        self.data = np.array(buf, copy=True)


class FakePass:
    def __init__(self, name, channels=4):
        self.name, self.channels, self.rect = name, channels, FakeRect()


class FakeLayer:
    def __init__(self):
        self.passes = [FakePass("Combined")]


class FakeResult:
    def __init__(self, width, height):
        self.size = (width, height)
        self.layers = [FakeLayer()]


class FakeEngine:
    """test_break() turns True `break_after` s after construction, from its `break_on_call`-th call on, or from the
    first call after a status line containing `break_on_stats` was shown (None: never). `break_time` records when it
    first returned True."""

    camera_override = None

    def __init__(self, break_after=None, break_on_call=None, break_on_stats=None):
        self.start = time.monotonic()
        self.break_after, self.break_on_call, self.break_on_stats = break_after, break_on_call, break_on_stats
        self.calls = 0
        self.break_time = None
        self.result = None
        self.results_begun = 0
        self.ended = False
        self.reports = []
        self.stats = []
        self.error = None   # the render result's message (error_set), shown after the render

    def test_break(self):
        self.calls += 1
        now = time.monotonic()
        hit = (self.break_after is not None and now - self.start >= self.break_after) or \
              (self.break_on_call is not None and self.calls >= self.break_on_call) or \
              (self.break_on_stats is not None and any(self.break_on_stats in line for line in self.stats))
        if hit and self.break_time is None:
            self.break_time = now
        return hit

    def begin_result(self, x, y, w, h, layer="", view=""):
        self.results_begun += 1
        self.result = FakeResult(w, h)
        return self.result

    def update_result(self, result):
        pass

    def end_result(self, result, cancel=False, highlight=False, do_merge_results=False):
        assert result is self.result
        self.ended = True

    def update_progress(self, fraction):
        pass

    def update_stats(self, stats, info):
        self.stats.append(info)

    def frame_set(self, frame, subframe=0.0):
        """RenderEngine.frame_set: motion blur samples the scene at subframes (export/motion.py)."""
        import bpy
        self.frames = getattr(self, "frames", []) + [(frame, subframe)]
        bpy.context.scene.frame_set(frame, subframe=subframe)

    def report(self, kind, message):
        self.reports.append((kind, message))

    def error_set(self, message):
        self.error = message

    def image(self):
        """The Combined pixels handed back ((W·H, 4) float32), or None if none were copied."""
        return self.result.layers[0].passes[0].rect.data if self.result else None
