"""GUI stress test of the Rendered viewport (issue 20), in Blender's window under Xvfb (run by gui_run.py):

100 view changes and 20 material edits in a row while the viewport renders: no crash (gui_run.py checks the exit
status), never more than one viewport worker thread and none after the view leaves Rendered shading, and the
resident memory after the run within 5 % of what it was after a warm-up of the same kind of changes (every
restart allocates and frees films and textures: a leak grows with their number).

Quick mode (gui_steps.QUICK, in `make test`): 20 view changes and 4 material edits after a warm-up of 10, the same
checks; the full run is `make test-gui`."""

import math
import os
import sys

import bpy
from mathutils import Quaternion

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_steps as G  # noqa: E402

VIEW_CHANGES, WARM_UP = (20, 10) if G.QUICK else (100, 30)
MATERIAL_EDITS = VIEW_CHANGES // 5   # every fifth change edits the material as well


def steps():
    window, area, region, space = G.view3d()
    rv3d = space.region_3d
    space.shading.type = 'RENDERED'
    ok = yield from G.wait_until(lambda: G.viewports() and G.viewports()[0].display.meta is not None, 60)
    G.check("the viewport renders", ok)
    vp = G.viewports()[0]
    red = bpy.data.materials["Red"].node_tree.nodes["Principled BSDF"].inputs["Base Color"]
    turn = Quaternion((0.0, 0.0, 1.0), math.radians(3.6))
    most_threads, uploads, baseline = 0, vp.display.uploads, None

    def change(i):
        rv3d.view_rotation = turn @ rv3d.view_rotation    # a view change: a restart, coarse to fine
        if i % 5 == 4:                                     # every fifth: a material edit as well
            red.default_value = (0.3 + 0.5 * ((i // 5) % 2), 0.05, 0.05 + 0.04 * (i // 5 % 3), 1.0)

    for i in range(WARM_UP):   # warm-up: the allocator and Blender's caches reach their working size
        change(i)
        yield 0.04
    yield from G.wait_until(lambda: vp.display.meta and vp.display.meta["pixel_size"] <= vp.pixel_size, 30)
    yield 1.0
    baseline = G.resident_mb()
    for i in range(VIEW_CHANGES):
        change(i)
        most_threads = max(most_threads, G.viewport_threads())
        yield 0.04
    G.check(f"{VIEW_CHANGES} view changes and {MATERIAL_EDITS} material edits: one viewport, one thread",
            len(G.viewports()) == 1 and most_threads == 1, f"at most {most_threads} threads")
    G.check("the viewport kept drawing new images", vp.display.uploads > uploads + VIEW_CHANGES // 5,
            f"{vp.display.uploads - uploads} uploads")
    ok = yield from G.wait_until(lambda: vp.display.meta and vp.display.meta["pixel_size"] <= vp.pixel_size, 30)
    yield 1.0
    after = G.resident_mb()
    G.check("resident memory within 5 % of the warm-up's", after <= 1.05 * baseline,
            f"{baseline:.1f} MB after warm-up, {after:.1f} MB after the run ({100 * (after / baseline - 1):+.1f} %)")
    space.shading.type = 'SOLID'
    ok = yield from G.wait_until(lambda: not G.viewports() and G.viewport_threads() == 0, 20)
    G.check("no viewport thread is left behind", ok, f"{G.viewport_threads()} threads")


G.run(steps)
