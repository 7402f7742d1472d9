"""Bad input through Blender (run inside blender -b by tests/blender/run.py): each case gives a clear message
naming the object and the problem, or renders with a warning, as a user would expect — never a crash, a hang
or a silently black frame."""

import math
import sys

import bpy
import numpy as np
import pytest

import scenes


def render_error(scene):
    """The error message of an in-process render, or None if it rendered."""
    try:
        bpy.ops.render.render()
    except RuntimeError as e:
        return str(e)
    return None


def last_stats():
    return sys.modules["candela.render_loop"].last_render_stats


def test_empty_scene_names_the_problem():
    scene = scenes.empty_scene(16, 12)
    scenes.add_camera(scene)
    error = render_error(scene)
    assert error and "nothing to render" in error and scene.name in error


def test_nan_vertex_names_the_object():
    scene = scenes.tiny_scene(16, 12, samples=1)
    plane = scene.objects["Plane"]
    plane.data.vertices[2].co = (math.nan, 0.0, 0.0)
    error = render_error(scene)
    assert error and "'Plane'" in error and "non-finite" in error and "vertex 2" in error


def test_infinite_scale_names_the_object():
    scene = scenes.tiny_scene(16, 12, samples=1)
    scene.objects["Cube"].scale = (math.inf, 1.0, 1.0)
    error = render_error(scene)
    assert error and "'Cube'" in error and "transform" in error


def test_mesh_without_faces_is_skipped():
    scene = scenes.tiny_scene(16, 12, samples=2)
    me = bpy.data.meshes.new("Points")
    me.from_pydata([(0, 0, 0), (1, 0, 0)], [(0, 1)], [])
    scenes.link(scene, bpy.data.objects.new("Points", me))
    assert render_error(scene) is None


def test_ngons_and_non_manifold_meshes_render():
    scene = scenes.tiny_scene(16, 12, samples=2)
    me = bpy.data.meshes.new("Ngon")
    ring = [(math.cos(a), math.sin(a), 1.0) for a in np.linspace(0, 2 * math.pi, 9)[:-1]]
    # An octagon (n-gon) and a fin sharing one edge with it (non-manifold: three faces on an edge).
    me.from_pydata(ring + [(0, 0, 2), (0, 0, 0)], [], [tuple(range(8)), (0, 1, 8), (0, 1, 9)])
    scenes.link(scene, bpy.data.objects.new("Ngon", me))
    assert render_error(scene) is None
    assert last_stats()["nan_samples"] == 0


def test_no_lights_and_black_world_warns_but_renders():
    scene = scenes.empty_scene(16, 12)
    scenes.add_camera(scene)
    scenes.link(scene, bpy.data.objects.new("Plane", scenes.grid_mesh("Plane", 5.0)))
    scene.world = None
    assert render_error(scene) is None
    assert last_stats()["phase"] == "done"
    assert any("no lights" in w for w in last_stats()["warnings"]), last_stats()["warnings"]


def test_unsupported_node_warns_and_falls_back():
    scene = scenes.tiny_scene(16, 12, samples=2)
    mat = scene.objects["Plane"].data.materials[0]
    nodes = mat.node_tree.nodes
    toon = nodes.new("ShaderNodeBsdfToon")
    mat.node_tree.links.new(toon.outputs[0], nodes["Material Output"].inputs["Surface"])
    assert render_error(scene) is None  # renders with the material's viewport colour, and a warning
    assert any("Toon" in w and mat.name in w for w in last_stats()["warnings"]), last_stats()["warnings"]


def test_zero_resolution_is_refused_by_blender_or_candela():
    scene = scenes.tiny_scene(16, 12, samples=1)
    scene.render.resolution_percentage = 1  # 16 px at 1 % rounds to 0
    error = render_error(scene)
    # Blender refuses it itself ("Image too small") before calling the engine; Candela would say "resolution".
    assert error is not None and ("too small" in error or "resolution" in error.lower())


def test_cancel_during_export_hands_back_a_result():
    from candela import render_loop  # noqa: F401  (the add-on's modules are importable)
    from candela.export import export_scene, render_camera

    scene = scenes.tiny_scene(16, 12, samples=1)
    for i in range(1200):  # enough instances for export to poll test_break()
        ob = scenes.link(scene, bpy.data.objects.new(f"C{i}", scene.objects["Cube"].data))
        ob.location = (i % 30 * 0.1, i // 30 * 0.1, 0.0)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    assert export_scene(depsgraph, render_camera(scene), test_break=lambda: True) is None


def test_render_then_render_again_many_times():
    scene = scenes.tiny_scene(16, 12, samples=4)
    for _ in range(20):
        assert render_error(scene) is None
        assert last_stats()["phase"] == "done"


def test_scene_too_large_for_memory_names_the_biggest_object():
    scene = scenes.tiny_scene(16, 12, samples=1)
    bpy.ops.mesh.primitive_uv_sphere_add(segments=256, ring_count=128)   # 65,024 triangles: ~12 MB to build
    bpy.context.active_object.name = "BigSphere"
    argv = list(sys.argv)
    # The predicted need is compared with MemAvailable; a lowered limit (the farm option) triggers the refusal
    # without exhausting the machine.
    sys.argv[:] = argv + ["--candela-memory-limit-mb", "4"]
    try:
        error = render_error(scene)
    finally:
        sys.argv[:] = argv
    assert error and "'BigSphere'" in error and "65,024 triangles" in error, error
    assert "memory_limit_mb" in error and "4 MB are available" in error, error
    assert render_error(scene) is None   # without the limit it fits


def test_zero_scale_names_the_object():
    scene = scenes.tiny_scene(16, 12, samples=1)
    scene.objects["Cube"].scale = (0.0, 1.0, 1.0)
    error = render_error(scene)
    assert error and "'Cube'" in error and "zero-scale" in error, error
