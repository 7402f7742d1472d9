"""Depsgraph → arrays: schema dtypes/shapes, instancing, hidden objects, modifiers, lights, world, params, dumps."""

import json
import math

import bpy
import numpy as np
import pytest

import scenes
from candela import cmdline, dump, schema
from candela.export import ExportError, Warnings, export_scene, render_camera
from candela.params import to_native_params

SCHEMA = {   # key: (dtype, trailing shape)
    "positions": (np.float32, (3,)),
    "triangles": (np.uint32, (3,)),
    "vertex_normals": (np.float32, (3,)),    # or "normals" (T, 3, 3) with auto smooth / custom normals
    "tri_smooth": (np.uint8, ()),
    "tri_material": (np.uint32, ()),
    "mesh_tri_start": (np.uint32, ()),
    "instance_mesh": (np.uint32, ()),
    "instance_transform": (np.float32, (4, 4)),
    "instance_flags": (np.uint8, ()),
    "instance_pass_index": (np.uint32, ()),
    "material_holdout": (np.float32, ()),
    "material_type": (np.uint32, ()),
    "materials": (np.float32, (len(schema.material_columns()),)),
    "light_type": (np.uint32, ()),
    "lights": (np.float32, (len(schema.light_columns()),)),
    "camera_to_world": (np.float32, (4, 4)),
    "world_color": (np.float32, (3,)),
    "closure_material": (np.uint32, ()),
    "closure_type": (np.uint32, ()),
    "closure_params": (np.float32, (len(schema.closure_columns()),)),
    "instance_color": (np.float32, (4,)),
    "instance_random": (np.float32, ()),
    "instance_terminator": (np.float32, ()),
}


def export(scene, warnings=None):
    depsgraph = bpy.context.evaluated_depsgraph_get()
    return export_scene(depsgraph, render_camera(scene), warnings=warnings)


def test_schema_dtypes_and_shapes():
    scene = scenes.tiny_scene()
    a = export(scene)
    assert set(a) == set(SCHEMA)
    for key, (dtype, trailing) in SCHEMA.items():
        assert a[key].dtype == dtype, key
        assert a[key].flags["C_CONTIGUOUS"], key
        if key not in ("camera_to_world", "world_color"):
            assert a[key].shape[1:] == trailing, key
    T, M, I = len(a["triangles"]), len(a["mesh_tri_start"]) - 1, len(a["instance_mesh"])
    assert (T, M, I) == (2 + 12, 2, 2)
    assert a["camera_to_world"].shape == (4, 4) and a["world_color"].shape == (3,)
    assert a["vertex_normals"].shape == a["positions"].shape
    assert a["tri_smooth"].shape == (T,) and a["tri_material"].shape == (T,)
    assert a["mesh_tri_start"][0] == 0 and a["mesh_tri_start"][-1] == T
    assert a["triangles"].max() < len(a["positions"])
    assert a["tri_material"].max() < len(a["materials"])
    assert a["instance_mesh"].max() < M
    assert len(a["light_type"]) == len(a["lights"]) == 1


def test_materials_diffuse_and_emission():
    scene = scenes.tiny_scene()
    a = export(scene)
    cols = schema.material_columns()
    grey = [0.0] * len(cols)
    glow = [0.0] * len(cols)
    for name, value in zip(("base_r", "base_g", "base_b"), (0.8, 0.8, 0.8)):
        grey[cols.index(name)] = value
    for name, value in zip(("emission_r", "emission_g", "emission_b"), (5.0, 2.5, 1.0)):
        glow[cols.index(name)] = value
    assert np.any(np.all(np.isclose(a["materials"], grey), axis=1)), a["materials"]
    assert np.any(np.all(np.isclose(a["materials"], glow), axis=1)), a["materials"]


def test_unsupported_node_warns_once_and_falls_back():
    scene = scenes.tiny_scene()
    mat = bpy.data.materials.new("Shiny")
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    toon = nodes.new("ShaderNodeBsdfToon")
    mat.node_tree.links.new(toon.outputs[0], nodes["Material Output"].inputs["Surface"])
    mat.diffuse_color = (0.1, 0.2, 0.3, 1.0)
    for i in range(3):   # three objects, one material: one warning
        ob = scenes.link(scene, bpy.data.objects.new(f"S{i}", scenes.cube_mesh(f"S{i}")))
        ob.data.materials.append(mat)
    warnings = Warnings()
    a = export(scene, warnings)
    hits = [m for m in warnings.messages if "Shiny" in m]
    assert len(hits) == 1 and "Toon" in hits[0], warnings.messages
    cols = schema.material_columns()
    base = a["materials"][:, [cols.index("base_r"), cols.index("base_g"), cols.index("base_b")]]
    assert np.any(np.all(np.isclose(base, (0.1, 0.2, 0.3)), axis=1))


def test_linked_duplicates_share_one_mesh():
    scene = scenes.empty_scene()
    scenes.add_camera(scene)
    mesh = scenes.cube_mesh("Shared")
    for i in range(10):
        ob = scenes.link(scene, bpy.data.objects.new(f"Dup{i}", mesh))
        ob.location = (i * 2.0, 0.0, 0.0)
    a = export(scene)
    assert len(a["mesh_tri_start"]) - 1 == 1
    assert len(a["triangles"]) == 12
    assert len(a["instance_mesh"]) == 10 and not a["instance_mesh"].any()
    xs = sorted(a["instance_transform"][:, 0, 3])
    assert np.allclose(xs, [i * 2.0 for i in range(10)])


def test_hidden_object_is_skipped():
    scene = scenes.empty_scene()
    scenes.add_camera(scene)
    scenes.link(scene, bpy.data.objects.new("Visible", scenes.cube_mesh("V")))
    hidden = scenes.link(scene, bpy.data.objects.new("Hidden", scenes.grid_mesh("H")))
    hidden.hide_render = True
    a = export(scene)
    assert len(a["instance_mesh"]) == 1 and len(a["triangles"]) == 12


def test_modifier_is_applied():
    scene = scenes.empty_scene()
    scenes.add_camera(scene)
    ob = scenes.link(scene, bpy.data.objects.new("Sub", scenes.cube_mesh("Sub")))
    mod = ob.modifiers.new("Subdivision", 'SUBSURF')
    mod.levels = mod.render_levels = 2
    a = export(scene)
    assert len(a["triangles"]) == 6 * 16 * 2


def test_lights_columns():
    scene = scenes.empty_scene()
    scenes.add_camera(scene)
    scenes.link(scene, bpy.data.objects.new("Ground", scenes.grid_mesh("G")))
    area = scenes.link(scene, bpy.data.objects.new("Area", bpy.data.lights.new("Area", 'AREA')))
    area.data.shape, area.data.size, area.data.size_y = 'RECTANGLE', 2.0, 0.5
    area.data.energy, area.data.color = 100.0, (1.0, 0.5, 0.25)
    area.location, area.scale = (1.0, 2.0, 3.0), (2.0, 1.0, 1.0)
    sun = scenes.link(scene, bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", 'SUN')))
    sun.rotation_euler = (math.pi / 2, 0.0, 0.0)   # −Z rotated to +Y
    sun.data.energy, sun.data.angle = 3.0, 0.1
    a = export(scene)
    cols = {c: i for i, c in enumerate(schema.light_columns())}
    types = schema.light_types()
    by_type = {int(t): row for t, row in zip(a["light_type"], a["lights"])}
    ar = by_type[types["AREA"]]
    assert np.allclose(ar[[cols["strength_r"], cols["strength_g"], cols["strength_b"]]], (100, 50, 25))
    assert np.allclose(ar[[cols["pos_x"], cols["pos_y"], cols["pos_z"]]], (1, 2, 3))
    assert np.allclose(ar[[cols["dir_x"], cols["dir_y"], cols["dir_z"]]], (0, 0, -1), atol=1e-6)
    assert np.allclose(ar[[cols["u_x"], cols["u_y"], cols["u_z"]]], (4, 0, 0), atol=1e-6)   # size 2 × scale 2
    assert np.allclose(ar[[cols["v_x"], cols["v_y"], cols["v_z"]]], (0, 0.5, 0), atol=1e-6)
    assert ar[cols["shape"]] == 0
    assert ar[cols["visible_camera"]] == 0     # Blender 3.4 creates lights hidden from the camera (Cycles agrees)
    area.visible_camera = True
    assert export(scene)["lights"][:, cols["visible_camera"]].max() == 1
    su = by_type[types["SUN"]]
    assert np.allclose(su[[cols["dir_x"], cols["dir_y"], cols["dir_z"]]], (0, 1, 0), atol=1e-6)
    assert np.isclose(su[cols["strength_r"]], 3.0) and np.isclose(su[cols["angle"]], 0.1)


def test_world_color():
    scene = scenes.tiny_scene()
    world = bpy.data.worlds.new("W")
    scene.world = world
    world.use_nodes = True
    bg = world.node_tree.nodes["Background"]
    bg.inputs["Color"].default_value = (0.5, 0.25, 1.0, 1.0)
    bg.inputs["Strength"].default_value = 2.0
    assert np.allclose(export(scene)["world_color"], (1.0, 0.5, 2.0))
    world.use_nodes = False
    world.color = (0.1, 0.2, 0.3)
    assert np.allclose(export(scene)["world_color"], (0.1, 0.2, 0.3))
    scene.world = None
    assert np.allclose(export(scene)["world_color"], 0.0)


def test_camera_matrix_without_scale():
    scene = scenes.tiny_scene()
    scene.camera.scale = (2.0, 3.0, 4.0)
    m = export(scene)["camera_to_world"]
    assert np.allclose(np.linalg.norm(m[:3, :3], axis=0), 1.0, atol=1e-5)
    assert np.allclose(m[:3, 3], scene.camera.location)


def test_missing_camera_and_empty_scene_errors():
    scene = scenes.tiny_scene(with_camera=False)
    with pytest.raises(ExportError, match="has no camera"):
        render_camera(scene)
    scene = scenes.empty_scene()
    scenes.add_camera(scene)
    with pytest.raises(ExportError, match="nothing to render"):
        export(scene)


def test_params_mapping_border_and_overrides():
    scene = scenes.tiny_scene(width=100, height=70)
    r = scene.render
    r.use_border = True
    r.border_min_x, r.border_max_x, r.border_min_y, r.border_max_y = 0.25, 0.75, 0.0, 0.5
    scene.candela.seed, scene.candela.use_animated_seed = 5, True
    scene.frame_current = 3
    p = to_native_params(scene, scene.camera.data, argv=["blender", "--", "--candela-samples", "7"])
    assert (p["width"], p["height"]) == (100, 70)
    assert (p["crop_x0"], p["crop_y0"], p["crop_x1"], p["crop_y1"]) == (25, 0, 75, 35)
    assert p["samples"] == 7 and p["seed"] == 8
    assert p["lens"] == scene.camera.data.lens and p["camera_type"] == "PERSP"
    assert p["pixel_filter"] == "BLACKMAN_HARRIS" and p["integrator"] == "PATH"
    assert cmdline.overrides(["x", "--", "--candela-seed=9", "--other"]) == {"seed": 9}
    assert cmdline.overrides(["x", "--candela-seed", "9"]) == {}


def test_dump_operator(tmp_path):
    scenes.tiny_scene()
    assert bpy.ops.candela.export_dump(directory=str(tmp_path)) == {'FINISHED'}
    params = json.loads((tmp_path / "params.json").read_text())
    assert params["width"] == 32 and params["samples"] == 8
    for key, (dtype, _) in SCHEMA.items():
        assert np.load(tmp_path / f"{key}.npy").dtype == dtype, key


def test_mix_and_add_shaders_become_weighted_closures():
    """Mix Shader(fac 0.25) of Diffuse and (Glossy + Emission): weights 0.75 / 0.25, emission scaled by 0.25."""
    scene = scenes.tiny_scene()
    mat = bpy.data.materials.new("Layered")
    mat.use_nodes = True
    nt = mat.node_tree
    nt.nodes.clear()
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    mix = nt.nodes.new("ShaderNodeMixShader")
    mix.inputs["Fac"].default_value = 0.25
    diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (0.2, 0.4, 0.6, 1.0)
    glossy = nt.nodes.new("ShaderNodeBsdfGlossy")
    glossy.distribution = "BECKMANN"
    glossy.inputs["Roughness"].default_value = 0.3
    add = nt.nodes.new("ShaderNodeAddShader")
    emission = nt.nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 8.0
    nt.links.new(diffuse.outputs[0], mix.inputs[1])
    nt.links.new(glossy.outputs[0], add.inputs[0])
    nt.links.new(emission.outputs[0], add.inputs[1])
    nt.links.new(add.outputs[0], mix.inputs[2])
    nt.links.new(mix.outputs[0], out.inputs["Surface"])
    ob = scenes.link(scene, bpy.data.objects.new("Layered", scenes.cube_mesh("Layered")))
    ob.data.materials.append(mat)
    warnings = Warnings()
    a = export(scene, warnings)
    assert not [m for m in warnings.messages if "Layered" in m], warnings.messages
    types, cols = schema.closure_types(), schema.closure_columns()
    row = int(np.flatnonzero([np.allclose(r[cols.index("color_r"):cols.index("color_r") + 3], (0.2, 0.4, 0.6))
                              for r in a["closure_params"]])[0])
    material = a["closure_material"][row]
    mine = np.flatnonzero(a["closure_material"] == material)
    kinds = sorted(int(a["closure_type"][i]) for i in mine)
    assert kinds == sorted([types["DIFFUSE"], types["GLOSSY"]])
    weights = {int(a["closure_type"][i]): a["closure_params"][i][cols.index("weight_r")] for i in mine}
    assert weights[types["DIFFUSE"]] == pytest.approx(0.75) and weights[types["GLOSSY"]] == pytest.approx(0.25)
    glossy_row = a["closure_params"][[i for i in mine if a["closure_type"][i] == types["GLOSSY"]][0]]
    assert glossy_row[cols.index("roughness")] == pytest.approx(0.3)
    assert glossy_row[cols.index("distribution")] == schema.DISTRIBUTIONS["BECKMANN"]
    emission_cols = [schema.material_columns().index(f"emission_{c}") for c in "rgb"]
    assert a["materials"][material][emission_cols] == pytest.approx([2.0, 2.0, 2.0])  # 0.25 · 8


def test_every_sampling_option_reaches_the_native_session():
    """Each value of each sampling enum maps to a param the native side accepts (same identifiers)."""
    from candela import native

    scene = scenes.tiny_scene(width=8, height=6, samples=1)
    camera = render_camera(scene)
    arrays = export(scene)
    settings = scene.candela
    for prop in ("sampler", "hemisphere_sampling", "light_sampling", "mis_heuristic", "light_pdf",
                 "light_selection", "rr_mode", "pixel_filter", "integrator"):
        for item in settings.bl_rna.properties[prop].enum_items:
            setattr(settings, prop, item.identifier)
            params = to_native_params(scene, camera.data)
            assert params[prop] == item.identifier
            session = native.require().Session(arrays, params)   # raises ValueError on an unknown name
            assert not [line for line in session.take_log() if "unknown render parameter" in line], prop
        setattr(settings, prop, settings.bl_rna.properties[prop].default)


def _random_mesh(rng, n_faces, ngon=False):
    """Faces of 3 and 4 corners (planar, concave and folded quads) on random 3-D points; one pentagon if ngon."""
    verts, faces = [], []
    for f in range(n_faces):
        k = 3 if f % 3 == 0 else 4
        base = len(verts)
        if k == 4 and f % 3 == 1:      # a planar quad, convex or (dart) concave
            pts = [(0, 0), (1, 0), (rng.uniform(0.1, 1.2), rng.uniform(0.1, 1.2)), (0, 1)]
            verts += [(x + 2 * f, y, 0.0) for x, y in pts]
        else:
            verts += [tuple(rng.uniform(-1, 1, 3) + (2 * f, 0, 0)) for _ in range(k)]
        faces.append(tuple(range(base, base + k)))
    if ngon:
        base = len(verts)
        verts += [(math.cos(a), math.sin(a), 5.0) for a in np.linspace(0, 2 * math.pi, 5, endpoint=False)]
        faces.append(tuple(range(base, base + 5)))
    me = bpy.data.meshes.new("Random")
    me.from_pydata(verts, [], faces)
    me.update()
    return me


@pytest.mark.parametrize("ngon", [False, True])
def test_triangulation_matches_blenders_loop_triangles(ngon):
    """The numpy triangulation of tris and quads (export/mesh.py) must give exactly the evaluated mesh's loop
    triangles — the same diagonals, folded quads included — and n-gon meshes fall back to them."""
    from candela.export.mesh import read_mesh
    scene = scenes.empty_scene()
    rng = np.random.default_rng(7)
    ob = scenes.link(scene, bpy.data.objects.new("Random", _random_mesh(rng, 600, ngon)))
    for i, poly in enumerate(ob.data.polygons):
        poly.use_smooth = i % 2 == 0
    depsgraph = bpy.context.evaluated_depsgraph_get()
    evaluated = ob.evaluated_get(depsgraph)
    me = evaluated.data          # what Cycles triangulates (the original mesh may split folded quads otherwise)
    me.calc_loop_triangles()     # before read_mesh, so that nothing it computes can influence the reference
    expected = np.array([tuple(t.vertices) for t in me.loop_triangles], np.uint32)
    smooth = np.array([me.polygons[t.polygon_index].use_smooth for t in me.loop_triangles], np.uint8)
    data = read_mesh(evaluated)
    quads = [(tuple(t.vertices), tuple(me.polygons[t.polygon_index].vertices)) for t in me.loop_triangles
             if len(me.polygons[t.polygon_index].vertices) == 4]
    flips = sum(set(tv) == {pv[0], pv[1], pv[3]} for tv, pv in quads)
    assert flips > 50             # the random folded quads do exercise the 1–3 split
    assert np.array_equal(data.triangles, expected)
    assert np.array_equal(data.smooth, smooth)
    # Smooth corners carry Blender's split normals.
    me.calc_normals_split()
    split = np.array([[me.loops[l].normal for l in t.loops] for t in me.loop_triangles], np.float32)
    mask = smooth.astype(bool)
    assert np.allclose(data.corner_normals()[mask], split[mask], atol=1e-5)


def test_auto_smooth_exports_split_normals_per_corner():
    scene = scenes.tiny_scene()
    cube = scene.objects["Cube"]
    for poly in cube.data.polygons:
        poly.use_smooth = True
    cube.data.use_auto_smooth = True           # 30°: every cube edge is sharp, so corners get face normals
    a = export(scene)
    assert "normals" in a and "vertex_normals" not in a
    T = len(a["triangles"])
    assert a["normals"].shape == (T, 3, 3)
    cube_tris = slice(a["mesh_tri_start"][1], a["mesh_tri_start"][2]) if len(a["mesh_tri_start"]) > 2 else slice(0, T)
    n = a["normals"][cube_tris]
    # Face normals: the three corners of each triangle agree and are axis-aligned.
    assert np.allclose(n[:, 0], n[:, 1], atol=1e-5) and np.allclose(n[:, 0], n[:, 2], atol=1e-5)
    assert np.allclose(np.abs(n).max(axis=2), 1.0, atol=1e-5)
