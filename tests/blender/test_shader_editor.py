"""The Shader Editor while Candela is the engine: Candela's Shift+A categories (registered with the add-on, removed
with it) list the supported nodes for material and world trees, and the material, world, camera-DOF and object
visibility panels draw for CANDELA."""

from types import SimpleNamespace

import addon_utils
import bpy
import nodeitems_utils

import scenes


def node_context(engine, shader_type):
    space = SimpleNamespace(type='NODE_EDITOR', tree_type='ShaderNodeTree', shader_type=shader_type, edit_tree=None)
    return SimpleNamespace(engine=engine, space_data=space)


def items(context):
    """Node types the Shift+A menu offers in `context`, by Candela's categories only."""
    from candela.ui import node_categories
    offered = []
    for cat in node_categories.categories():
        if cat.poll(context):
            offered += [item.nodetype for item in cat.items(context) if hasattr(item, "nodetype")]
    return offered


def test_categories_register_with_the_addon_and_go_with_it():
    scenes.ensure_addon()
    from candela.ui import node_categories
    assert node_categories.MENU_ID in nodeitems_utils._node_categories
    assert hasattr(bpy.types, "NODE_MT_category_CANDELA_SH_NEW_SHADER")
    addon_utils.disable("candela", default_set=True)
    try:
        assert node_categories.MENU_ID not in nodeitems_utils._node_categories
        assert not hasattr(bpy.types, "NODE_MT_category_CANDELA_SH_NEW_SHADER")
    finally:
        addon_utils.enable("candela", default_set=True)
    assert node_categories.MENU_ID in nodeitems_utils._node_categories


def test_every_listed_node_is_a_blender_node_type():
    scenes.ensure_addon()
    from candela.ui import node_categories
    missing = [n for n in node_categories.node_types() if not hasattr(bpy.types, n)]
    assert not missing, missing


def test_categories_poll_for_candela_and_list_tree_specific_nodes():
    scenes.ensure_addon()
    material = items(node_context('CANDELA', 'OBJECT'))
    world = items(node_context('CANDELA', 'WORLD'))
    for node in ("ShaderNodeBsdfPrincipled", "ShaderNodeBsdfDiffuse", "ShaderNodeMixShader", "ShaderNodeEmission",
                 "ShaderNodeOutputMaterial", "ShaderNodeHoldout"):
        assert node in material, node
    assert "ShaderNodeBackground" not in material and "ShaderNodeOutputWorld" not in material
    assert "ShaderNodeBackground" in world and "ShaderNodeOutputWorld" in world
    assert "ShaderNodeBsdfPrincipled" not in world
    assert items(node_context('CYCLES', 'OBJECT')) == []   # Cycles keeps its own menus


def test_panels_poll_for_candela():
    scene = scenes.tiny_scene()
    mat = bpy.data.materials["Grey"]
    cam = scene.camera
    for engine, expected in (('CANDELA', True), ('BLENDER_EEVEE', False)):
        ctx = SimpleNamespace(engine=engine, material=mat, world=bpy.data.worlds.new("W"), camera=cam.data,
                              object=bpy.data.objects["Cube"], scene=scene)
        assert bool(bpy.types.CANDELA_MATERIAL_PT_surface.poll(ctx)) is expected
        assert bool(bpy.types.CANDELA_WORLD_PT_surface.poll(ctx)) is expected
        assert bool(bpy.types.CANDELA_OBJECT_PT_visibility_ray_visibility.poll(ctx)) is expected
    ctx = SimpleNamespace(engine='CANDELA', camera=cam.data, object=cam, scene=scene)
    assert bpy.types.DATA_PT_camera_dof.poll(ctx) and bpy.types.DATA_PT_camera_dof_aperture.poll(ctx)
    assert bpy.types.OBJECT_PT_visibility.poll(ctx)
    assert 'CANDELA' in bpy.types.EEVEE_MATERIAL_PT_context_material.COMPAT_ENGINES


def test_surface_panel_reads_the_cycles_output():
    """The panel draws the Cycles output's Surface input (the node tree Candela renders), like Cycles' own panel."""
    scenes.ensure_addon()
    from candela.ui import surfaces
    mat = scenes.diffuse_material("Drawn", (0.5, 0.5, 0.5))
    calls = []

    class Layout:
        use_property_split = False

        def template_node_view(self, tree, node, socket):
            calls.append((tree, node.bl_idname, socket.name))

        def prop(self, *args, **kwargs):
            calls.append(("prop", args))

        def label(self, **kwargs):
            calls.append(("label", kwargs))

    surfaces._draw_output(Layout(), mat, "diffuse_color")
    assert calls == [(mat.node_tree, "ShaderNodeOutputMaterial", "Surface")], calls
