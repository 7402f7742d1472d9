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


def test_cancel_stops_quickly_and_keeps_partial_image():
    scene = scenes.tiny_scene(width=64, height=48, samples=100000)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    camera = render_camera(scene)
    # Esc is seen within one poll interval; from then the workers must stop and the partial image be handed
    # back. Together that must stay under the 100 ms the issue promises. On a busy 2-core machine (CI runs
    # two tests at once) one attempt can lose tens of milliseconds to the OS scheduler, which says nothing about
    # the renderer: up to three attempts, judged by the best one.
    latencies = []
    for _ in range(3):
        session, engine, lines, latency = _render_and_cancel(scene, depsgraph, camera)
        latencies.append(latency)
        if latency + render_loop.POLL_S < 0.1:
            break
    print("cancel latencies " + ", ".join(f"{x * 1000:.0f} ms" for x in latencies))
    assert min(latencies) + render_loop.POLL_S < 0.1, f"{min(latencies) * 1000:.0f} ms after the break was seen"
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


def test_status_line_shows_noise_and_why_the_render_stopped():
    progress = {"phase": "done", "samples_done": 48, "samples_total": 1024, "fraction": 48 / 1024,
                "elapsed_s": 3.0, "relative_error": 0.0198, "stop_reason": "noise threshold"}
    assert render_loop.status_line("PATH", progress) == \
        "Path | Sample 48/1024 | Elapsed 00:03 | Noise 2.0 % | Stopped: noise threshold"


def test_backoff_grows_and_caps():
    b = render_loop.Backoff(0.5, 2.0, 4.0, now=0.0)
    due = [t / 10 for t in range(0, 200) if b.due(t / 10)]
    assert due[:4] == [0.5, 1.5, 3.5, 7.5] and all(b - a <= 4.0 + 1e-9 for a, b in zip(due, due[1:]))
