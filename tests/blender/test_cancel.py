"""Cancelling: the render loop stops soon after test_break() turns True and keeps the partial image."""

import time

import bpy
import numpy as np

import scenes
from fake_engine import FakeEngine
from candela import native, render_loop
from candela.export import export_scene, render_camera
from candela.params import to_native_params


def _render_and_cancel(scene, depsgraph, camera):
    arrays = export_scene(depsgraph, camera)
    session = native.require().Session(arrays, to_native_params(scene, camera.data))
    session.start()
    engine = FakeEngine(break_after=0.3)
    lines = []
    render_loop.drive(engine, session, integrator="PATH", out=lines.append)
    returned = time.monotonic()
    assert engine.break_time is not None, "the render finished before the break: raise the sample count"
    return session, engine, lines, returned - engine.break_time


class RecordingSession:
    """A stand-in Session: wait() returns False (still rendering) until cancelled, and records the order of calls."""

    width, height, error = 8, 6, None

    def __init__(self):
        self.calls = []
        self.cancelled = False

    def wait(self, timeout_s):
        self.calls.append("wait")
        return self.cancelled

    def cancel(self):
        self.calls.append("cancel")
        self.cancelled = True

    def join(self):
        self.calls.append("join")

    def progress(self):
        return {"phase": "cancelled" if self.cancelled else "rendering", "samples_done": 1, "samples_total": 9,
                "fraction": 0.1, "elapsed_s": 0.0}

    def stats(self):
        return {"render_seconds": 0.0, "samples_per_second": 0.0}

    def take_log(self):
        return []

    def get_pass(self, name):
        return np.zeros((self.width * self.height, 4), np.float32)


def test_the_loop_cancels_the_session_on_the_poll_that_sees_esc():
    """Deterministic: Esc (test_break() True) is acted on in the same poll — cancel, then join, then the result —
    so Esc → stop is at most one poll interval (POLL_S) plus the native stop, which is at most one pixel row of work
    per worker (tests/native/cancel_test.cpp)."""
    session = RecordingSession()
    engine = FakeEngine(break_on_call=3)
    render_loop.drive(engine, session, integrator="PATH", out=lambda line: None)
    assert session.calls == ["wait", "wait", "wait", "cancel", "join"]
    assert engine.calls == 3 and engine.ended


# From the poll that sees Esc to the end of drive() on a real render, measured on the 2-core development machine:
# 0.7–3.7 ms over 12 runs at load average 5 (2026-12-01); the worst ever seen in CI was 86 ms. The bound is 5× that
# worst case, so only a cancel that no longer stops the workers (a hang, a whole pass finished before the flag is
# seen) fails it, not the scheduler; the promise itself (< 100 ms from Esc to stop: one 50 ms poll plus at most one
# pixel row of work per worker) rests on the deterministic checks above and in tests/native/cancel_test.cpp.
CANCEL_LATENCY_BOUND_S = 0.45


def test_cancel_stops_and_keeps_partial_image():
    scene = scenes.tiny_scene(width=64, height=48, samples=100000)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    camera = render_camera(scene)
    session, engine, lines, latency = _render_and_cancel(scene, depsgraph, camera)
    print(f"cancel latency {latency * 1000:.1f} ms after the break was seen (poll interval {render_loop.POLL_S * 1000:.0f} ms)")
    assert latency < CANCEL_LATENCY_BOUND_S, f"{latency * 1000:.0f} ms after the break was seen"
    assert engine.ended
    assert session.progress()["phase"] == "cancelled"
    partial = engine.image()
    assert partial is not None and partial.shape == (64 * 48, 4)
    assert np.all(np.isfinite(partial)) and partial[:, :3].max() > 0.0
    assert lines and lines[0].startswith("Candela: rendered 64x48")


def test_status_line_format():
    line = render_loop.status_line("PATH", {"phase": "rendering", "samples_done": 37, "samples_total": 256,
                                            "fraction": 0.25, "elapsed_s": 12.0})
    assert line == "Path | Sample 37/256 | Elapsed 00:12 | Remaining 00:36"


def test_status_line_names_autos_choice_and_reason():
    line = render_loop.status_line("AUTO", {"phase": "rendering", "samples_done": 3, "samples_total": 4,
                                            "fraction": 0.75, "elapsed_s": 3.0,
                                            "method": "Auto: BDPT \u2014 caustic paths"})
    assert line == "Auto: BDPT \u2014 caustic paths | Sample 3/4 | Elapsed 00:03 | Remaining 00:01"


def test_status_line_shows_noise_and_why_the_render_stopped():
    progress = {"phase": "done", "samples_done": 48, "samples_total": 1024, "fraction": 48 / 1024,
                "elapsed_s": 3.0, "relative_error": 0.0198, "stop_reason": "noise threshold"}
    assert render_loop.status_line("PATH", progress) == \
        "Path | Sample 48/1024 | Elapsed 00:03 | Noise 2.0 % | Stopped: noise threshold"


def test_status_line_says_noise_n_a_without_an_honest_estimate():
    progress = {"phase": "rendering", "samples_done": 5, "samples_total": 10, "fraction": 0.5, "elapsed_s": 2.0,
                "relative_error": None, "noise_unavailable": True}
    assert render_loop.status_line("SPPM", progress) == \
        "SPPM | Sample 5/10 | Elapsed 00:02 | Noise n/a | Remaining 00:02"
    progress["noise_unavailable"] = False  # not known yet (before the first pass): nothing shown
    assert render_loop.status_line("PATH", progress) == "Path | Sample 5/10 | Elapsed 00:02 | Remaining 00:02"


def test_status_line_shows_a_stage_in_percent_and_the_integrators_note():
    progress = {"phase": "rendering", "stage": "Irradiance cache", "stage_done": 41, "stage_total": 100,
                "stage_percent": True, "note": "1234 records", "elapsed_s": 4.0}
    assert render_loop.status_line("IRRADIANCE_CACHE", progress) == \
        "Irradiance Cache | Irradiance cache 41 % | 1234 records | Elapsed 00:04"
    progress = {"phase": "rendering", "samples_done": 3, "samples_total": 16, "fraction": 0.1875, "elapsed_s": 3.0,
                "note": "1300 records", "stage": ""}
    assert render_loop.status_line("IRRADIANCE_CACHE", progress) == \
        "Irradiance Cache | Sample 3/16 | 1300 records | Elapsed 00:03 | Remaining 00:13"


def test_backoff_grows_and_caps():
    b = render_loop.Backoff(0.5, 2.0, 4.0, now=0.0)
    due = [t / 10 for t in range(0, 200) if b.due(t / 10)]
    assert due[:4] == [0.5, 1.5, 3.5, 7.5] and all(b - a <= 4.0 + 1e-9 for a, b in zip(due, due[1:]))
