"""Cancelling through the add-on's render loop (run inside blender -b by tests/blender/run.py): Esc during export,
during the BVH build and during rendering, then cancel-and-render-again 50 times. Each must hand Blender a result
(the partial image when there is one), never crash or hang, and the process must not grow by more than 5 % of its
resident memory after warm-up. Blender's own engine never breaks in the background, so a fake engine (fake_engine.py)
presses Esc at chosen moments while render_loop.render_frame() runs exactly as it does for F12."""

import gc
import time

import bpy
import numpy as np

import scenes
from fake_engine import FakeEngine
from candela import render_loop


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


def render(scene, engine):
    """One F12 of the add-on with `engine`; returns (render_frame's progress or None, seconds from Esc to return)."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    progress = render_loop.render_frame(engine, depsgraph, background=True)
    returned = time.monotonic()
    latency = returned - engine.break_time if engine.break_time is not None else None
    return progress, latency


def test_cancel_during_export_hands_back_a_blank_result():
    scene = scenes.tiny_scene(16, 12, samples=4)
    cube = scene.objects["Cube"]
    for i in range(1200):   # export polls Esc every 1,000 instances
        ob = scenes.link(scene, bpy.data.objects.new(f"C{i}", cube.data))
        ob.location = (i % 30 * 0.1, i // 30 * 0.1, 0.0)
    engine = FakeEngine(break_on_call=1)
    progress, latency = render(scene, engine)
    assert progress is None                      # stopped before any session existed
    assert engine.ended and engine.results_begun == 1 and engine.result.size == (16, 12)
    assert latency is not None and latency < 1.0, latency


def test_cancel_during_the_bvh_build_stops_it():
    scene = scenes.tiny_scene(32, 24, samples=16)
    # ~1.3M triangles: building their BVH takes seconds on this machine, exporting them about one.
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=800, y_subdivisions=800, size=8.0)
    engine = FakeEngine(break_on_call=1)         # the first poll after session.start(): the build is running
    progress, latency = render(scene, engine)
    stats = render_loop.last_render_stats
    print(f"cancel during the BVH build: returned {latency * 1000:.0f} ms after Esc")
    assert progress["phase"] == "cancelled"
    assert stats["paths"] == 0 and stats["samples_done"] == 0, stats   # no sample was rendered: it was building
    assert "Building scene" in engine.stats
    assert engine.ended and engine.image() is not None and np.isfinite(engine.image()).all()
    assert latency < 1.0, f"{latency:.2f} s from Esc to the end of the render"


def test_cancel_during_rendering_keeps_the_partial_image():
    scene = scenes.tiny_scene(64, 48, samples=100000)
    engine = FakeEngine(break_after=0.6)
    progress, latency = render(scene, engine)
    assert progress["phase"] == "cancelled" and progress["samples_done"] > 0
    image = engine.image()
    assert image is not None and image.shape == (64 * 48, 4)
    assert np.isfinite(image).all() and image[:, :3].max() > 0.0
    # The bound of tests/blender/test_cancel.py (5× the worst latency measured; the deterministic checks are there).
    assert latency < 0.45, f"{latency * 1000:.0f} ms"


def test_cancel_then_render_again_fifty_times_without_growing():
    scene = scenes.tiny_scene(32, 24, samples=4)

    def cycle(i):
        if i % 2 == 0:   # Esc at the first, second or third poll: while building or rendering
            scene.candela.samples = 100000
            engine = FakeEngine(break_on_call=1 + (i // 2) % 3)
        else:            # then render again, to the end
            scene.candela.samples = 4
            engine = FakeEngine()
        progress, _ = render(scene, engine)
        assert engine.ended and engine.results_begun == 1
        image = engine.image()
        assert image is not None and np.isfinite(image).all()
        if i % 2 == 0:
            assert progress["phase"] == "cancelled", progress
        else:
            assert progress["phase"] == "done" and image[:, :3].max() > 0.0, progress

    start = time.monotonic()
    for i in range(10):   # warm-up: allocator pools, TBB and Embree threads, Python caches
        cycle(i)
    gc.collect()
    before = resident_bytes()
    for i in range(50):
        cycle(i)
    gc.collect()
    after = resident_bytes()
    print(f"60 render/cancel cycles in {time.monotonic() - start:.1f} s; resident {before / 1e6:.1f} MB -> "
          f"{after / 1e6:.1f} MB")
    assert after <= before * 1.05, f"resident memory grew from {before / 1e6:.1f} MB to {after / 1e6:.1f} MB"


def test_cancel_the_irradiance_cache_in_its_pre_pass_and_while_rendering():
    """The irradiance cache's stages: Esc during the pre-pass (its stage on the status line) and during the render
    passes, within the same bound as PATH's."""
    scene = scenes.tiny_scene(160, 120, samples=16)
    scene.objects["Plane"].data.materials[0] = scenes.lambert_material("Lambert", (0.8, 0.8, 0.8))  # cached lobes
    scene.candela.integrator = "IRRADIANCE_CACHE"
    scene.candela.ic_gather_rays = 65536            # a pre-pass of seconds: hundreds of records of 65,536 rays
    scene.candela.ic_max_spacing = 2.0
    engine = FakeEngine(break_on_stats="Irradiance cache")   # Esc once the status line shows the pre-pass
    progress, latency = render(scene, engine)
    assert latency is not None, (progress, engine.stats[:20])
    print(f"irradiance cache, Esc in the pre-pass: returned {latency * 1000:.0f} ms after Esc")
    assert progress["phase"] == "cancelled" and progress["samples_done"] == 0, progress
    assert any("Irradiance cache" in line and "%" in line for line in engine.stats), engine.stats
    assert engine.ended and engine.image() is not None and np.isfinite(engine.image()).all()
    assert latency < 0.45, f"{latency * 1000:.0f} ms"

    scene.candela.ic_gather_rays = 64
    scene.candela.samples = 100000
    engine = FakeEngine(break_after=0.8)
    progress, latency = render(scene, engine)
    print(f"irradiance cache, Esc while rendering: returned {latency * 1000:.0f} ms after Esc")
    assert progress["phase"] == "cancelled" and progress["samples_done"] > 0, progress
    image = engine.image()
    assert image is not None and np.isfinite(image).all() and image[:, :3].max() > 0.0
    assert latency < 0.45, f"{latency * 1000:.0f} ms"
