"""GUI test of Rendered viewport shading (issue 20), in Blender's window under Xvfb (run by gui_run.py):

the Rendered view shows the scene and refines (less noise later); the view's own camera puts things where Blender
draws them (perspective, orthographic, camera view with zoom and pan); a transform-only edit updates the image
without reading a mesh or building a mesh BVH; a colour-management edit does not restart it; an error shows in
the viewport header; deleting an object, undo, switching the engine, leaving Rendered shading and closing the
view's area never crash and leave no viewport thread behind; Material Preview draws the geometry (EEVEE);
quitting Blender while a viewport renders is clean (gui_run.py checks the exit status).

Quick mode (gui_steps.QUICK, in `make test`): the scene and its refinement, the three view modes, the transform-only
edit, the colour-management edit, switching the engine and quitting while it renders; the error header, delete
and undo, Material Preview and closing the area (EEVEE's shader
compilation under software OpenGL is the slowest step) only in the full run (`make test-gui`)."""

import math
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_steps as G  # noqa: E402


def is_red(rgb):
    return rgb[0] > rgb[1] + 0.15 and rgb[0] > rgb[2] + 0.15


def patch(pixels, xy, r=3):
    x, y = int(round(xy[0])), int(round(xy[1]))
    return pixels[max(0, y - r):y + r + 1, max(0, x - r):x + r + 1].reshape(-1, 3).mean(axis=0)


def final_image(vp, min_samples, after=None):
    """The drawn image's metadata once it is the finest level with min_samples (and, with `after`, rendered for
    a request after that one: an edit's or view change's own image, not more samples of the old one)."""
    m = vp.display.meta
    if not m or m["pixel_size"] > vp.pixel_size or m["samples"] < min_samples:
        return None
    if after is not None and m["request"] <= after:
        return None
    return m


def marker_centroid(vp, region):
    """Centroid (region pixels) of the brightest spot of the native image: the emissive marker."""
    image = vp.session.image(0)
    lum = image["pixels"][..., :3].mean(axis=2)
    ys, xs = np.nonzero(lum > 0.5 * lum.max())
    sx, sy = region.width / image["frame_width"], region.height / image["frame_height"]
    return ((xs.mean() + image["x0"] + 0.5) * sx, (ys.mean() + image["y0"] + 0.5) * sy), sx


def steps():
    window, area, region, space = G.view3d()
    rv3d = space.region_3d
    scene = bpy.context.scene
    cube = bpy.data.objects["Cube"]
    space.overlay.show_overlays = False   # screenshots of the render alone
    # The first image is compared at one sample: the viewport stops there (its own sample limit, raised to the
    # scene's 16 below), so the noise check does not depend on how many samples the machine made before the
    # screenshot (a faster build had reached 8, where 8 -> 16 samples is within the display's 8-bit rounding).
    refined_limit = scene.candela.viewport_samples
    scene.candela.viewport_samples = 1
    space.shading.type = 'RENDERED'

    ok = yield from G.wait_until(lambda: len(G.viewports()) == 1, 30)
    G.check("Rendered shading starts one Candela viewport", ok, f"{len(G.viewports())} open")
    vp = G.viewports()[0]
    G.check("one viewport thread while it renders", G.viewport_threads() == 1, G.viewport_threads())

    # ---- the scene, refining ----
    ok = yield from G.wait_until(lambda: final_image(vp, 1) is not None, 60)
    G.check("a first full-resolution image", ok, vp.header)
    first_samples = vp.display.meta["samples"]
    first = G.screenshot("first")
    cube_xy = G.project(region, rv3d, cube.location)
    floor_xy = G.project(region, rv3d, (-3.5, 2.5, 0.0))
    sky = first[-5:, :5].reshape(-1, 3).mean(axis=0)
    G.check("the viewport shows the scene, not the background",
            is_red(patch(first, cube_xy)) and abs(sky[0] - sky[1]) < 0.05, f"cube {patch(first, cube_xy)} sky {sky}")
    scene.candela.viewport_samples = refined_limit
    ok = yield from G.wait_until(lambda: final_image(vp, 16) is not None, 120)
    G.check("it refines to the viewport sample limit", ok, vp.header)
    refined = G.screenshot("refined")
    noise_first = G.high_pass_noise(first[int(floor_xy[1]) - 20:int(floor_xy[1]) + 20,
                                           int(floor_xy[0]) - 20:int(floor_xy[0]) + 20])
    noise_refined = G.high_pass_noise(refined[int(floor_xy[1]) - 20:int(floor_xy[1]) + 20,
                                              int(floor_xy[0]) - 20:int(floor_xy[0]) + 20])
    # Pixel noise falls as 1/√n: from ≤ 2 to 16 samples by at least √8 ≈ 2.8; 0.7 leaves room for the 8-bit
    # display's rounding and the filter.
    G.check("less noise later", noise_refined < 0.7 * noise_first,
            f"{noise_first:.4f} at {first_samples} samples -> {noise_refined:.4f} at 16")

    # ---- the view's own camera: the marker where Blender draws it ----
    for mode in ('PERSP', 'ORTHO', 'CAMERA'):
        request = vp.session.image_request()
        if mode == 'CAMERA':
            rv3d.view_camera_zoom, rv3d.view_camera_offset = 12.0, (0.04, -0.03)
        after = request if rv3d.view_perspective != mode else None   # switching restarts the render
        rv3d.view_perspective = mode
        ok = yield from G.wait_until(lambda: final_image(vp, 2, after=after) is not None, 60)
        yield 0.3   # the view's matrices are those of the last redraw
        got, scale = marker_centroid(vp, region)
        want = G.project(region, rv3d, bpy.data.objects["Marker"].location)
        error = math.dist(got, want) if want else float("inf")
        G.check(f"{mode.lower()} view: the marker is where Blender draws it", ok and error < 1.5 * scale + 1.0,
                f"rendered at ({got[0]:.1f}, {got[1]:.1f}), Blender at {want}, {error:.2f} px")
    request = vp.session.image_request()
    rv3d.view_perspective = 'PERSP'
    yield from G.wait_until(lambda: final_image(vp, 4, after=request) is not None, 60)
    yield 0.5   # and Blender's own redraw of the new view
    before = G.screenshot("before_move")

    # ---- a transform-only edit ----
    reads, built = vp.meshes.reads, vp.session.status()["bvh_built"]
    old_xy = G.project(region, rv3d, cube.location)
    request = vp.session.image_request()
    cube.location.x -= 3.0
    ok = yield from G.wait_until(lambda: final_image(vp, 4, after=request) is not None, 60)
    moved = G.screenshot("moved")
    new_xy = G.project(region, rv3d, cube.location)
    G.check("a transform change updates the image",
            ok and is_red(patch(moved, new_xy)) and not is_red(patch(moved, old_xy)) and is_red(patch(before, old_xy)),
            f"old place {old_xy}: {patch(moved, old_xy)}, new place {new_xy}: {patch(moved, new_xy)}")
    status = vp.session.status()
    G.check("the transform edit read no mesh and built no mesh BVH",
            vp.meshes.reads == reads and status["bvh_built"] == built,
            f"mesh reads {reads} -> {vp.meshes.reads}, BVHs built {built} -> {status['bvh_built']}, "
            f"reused {status['bvh_reused']}")

    # ---- colour management: Blender applies it when drawing, the render goes on ----
    yield from G.wait_until(lambda: final_image(vp, 8) is not None, 60)
    updates, original_update = [0], vp.update

    def counted_update(context, depsgraph):
        updates[0] += 1
        original_update(context, depsgraph)

    vp.update = counted_update
    request, exports, samples = vp.session.image_request(), vp.exports, vp.display.meta["samples"]
    view = scene.view_settings
    transform = view.view_transform
    view.exposure, view.gamma, view.view_transform = 0.5, 1.1, 'Standard' if transform != 'Standard' else 'Filmic'
    yield 2.0
    G.check("a colour-management edit reaches view_update but does not restart the render",
            updates[0] >= 1 and vp.session.image_request() == request and vp.exports == exports
            and vp.display.meta["samples"] >= samples,
            f"{updates[0]} view_update calls, request {request} -> {vp.session.image_request()}, exports {exports} "
            f"-> {vp.exports}, samples {samples} -> {vp.display.meta['samples']}")
    view.exposure, view.gamma, view.view_transform = 0.0, 1.0, transform
    del vp.update

    if G.QUICK:
        yield from quick_end(scene)
        return

    # ---- an error goes to the header ----
    floor = bpy.data.objects["Floor"]
    keep = tuple(floor.data.vertices[0].co)
    floor.data.vertices[0].co = (math.nan, 0.0, 0.0)
    floor.data.update()
    ok = yield from G.wait_until(lambda: vp.header.startswith("Candela:") and "Floor" in vp.header, 20)
    G.check("an export error shows in the viewport header", ok, vp.header)
    floor.data.vertices[0].co = keep
    floor.data.update()
    ok = yield from G.wait_until(lambda: not vp.header.startswith("Candela:") and final_image(vp, 1), 60)
    G.check("fixing it renders again", ok, vp.header)

    # ---- deleting an object, undo, switching the engine, closing the view ----
    request = vp.session.image_request()
    bpy.data.objects.remove(bpy.data.objects["Marker"])
    ok = yield from G.wait_until(lambda: final_image(vp, 1, after=request) is not None, 60)
    G.check("deleting an object while rendering: it renders on", ok and vp.session.status()["error"] is None,
            vp.header)
    bpy.ops.ed.undo_push(message="before lift")
    cube.location.z += 1.0
    bpy.ops.ed.undo_push(message="lift")
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.ed.undo()
    yield 3.0
    scene, cube = bpy.context.scene, bpy.data.objects["Cube"]   # undo replaced the data blocks
    live = G.viewports()
    G.check("undo while rendering: one viewport, one thread", len(live) <= 1 and G.viewport_threads() == len(live),
            f"{len(live)} viewports, {G.viewport_threads()} threads")
    scene.render.engine = 'BLENDER_EEVEE'
    ok = yield from G.wait_until(lambda: not G.viewports() and G.viewport_threads() == 0, 20)
    G.check("switching the engine stops the viewport and its thread", ok,
            f"{len(G.viewports())} viewports, {G.viewport_threads()} threads")
    scene.render.engine = 'CANDELA'
    ok = yield from G.wait_until(lambda: len(G.viewports()) == 1, 20)
    G.check("switching back starts it again", ok)

    # ---- Material Preview: EEVEE draws Candela's scene ----
    space.shading.type = 'MATERIAL'
    ok = yield from G.wait_until(lambda: not G.viewports() and G.viewport_threads() == 0, 20)
    G.check("leaving Rendered shading stops the viewport and its thread", ok,
            f"{len(G.viewports())} viewports, {G.viewport_threads()} threads")
    cube = bpy.data.objects["Cube"]
    seen = [None]

    def eevee_shows_the_cube():
        seen[0] = patch(G.screenshot("material_preview"), G.project(region, rv3d, cube.location))
        return is_red(seen[0])

    ok = yield from G.wait_until(eevee_shows_the_cube, 180, poll=3.0)
    G.check("Material Preview draws the geometry", ok, f"cube pixel {seen[0]}")

    # ---- closing the Rendered view's area while it renders (quitting while it renders: the quick mode) ----
    space.shading.type = 'RENDERED'
    ok = yield from G.wait_until(lambda: G.viewports() and G.viewports()[0].display.meta is not None, 60)
    G.check("rendering again", ok)
    with bpy.context.temp_override(window=window, screen=window.screen, area=area):
        bpy.ops.screen.area_close()
    ok = yield from G.wait_until(lambda: not G.viewports() and G.viewport_threads() == 0, 30)
    G.check("closing the Rendered view's area stops its viewport and thread", ok,
            f"{len(G.viewports())} viewports, {G.viewport_threads()} threads")


def quick_end(scene):
    """Quick mode's end: switching the engine stops the viewport and its thread, switching back starts it, and
    Blender quits while it renders."""
    scene.render.engine = 'BLENDER_EEVEE'
    ok = yield from G.wait_until(lambda: not G.viewports() and G.viewport_threads() == 0, 20)
    G.check("switching the engine stops the viewport and its thread", ok,
            f"{len(G.viewports())} viewports, {G.viewport_threads()} threads")
    scene.render.engine = 'CANDELA'
    ok = yield from G.wait_until(lambda: G.viewports() and G.viewports()[0].display.meta is not None, 60)
    G.check("switching back renders again before quitting", ok)


G.run(steps)
