"""Shift+A in the Shader Editor while Candela is the engine: the Cycles shader nodes Candela renders.

Blender's own shader categories (nodeitems_builtins) poll `context.engine in {'CYCLES', 'BLENDER_EEVEE'}` for most
shading nodes, so without these a Candela user could not add a Principled BSDF. Each category polls for the
CANDELA engine and a shader node tree; items for material trees only (BSDFs, Material Output) or world trees only
(Background, World Output, Environment Texture) poll the tree's shader type, as Blender's do.
"""

import nodeitems_utils
from nodeitems_utils import NodeCategory, NodeItem

ENGINE = "CANDELA"
MENU_ID = "CANDELA_SHADER"   # nodeitems_utils' registry key for these categories


def _object_tree(context):
    return context.space_data.shader_type == 'OBJECT'


def _world_tree(context):
    return context.space_data.shader_type == 'WORLD'


class CandelaShaderNodeCategory(NodeCategory):
    @classmethod
    def poll(cls, context):
        space = getattr(context, "space_data", None)
        return (context.engine == ENGINE and space is not None and space.type == 'NODE_EDITOR'
                and space.tree_type == 'ShaderNodeTree')


# (identifier, label, [(node type, poll or None, NodeItem kwargs)]): the nodes Candela's exporter reads (materials:
# export/materials.py; world: export/world.py) — the set issue #3 defines: shader nodes with constant inputs, and the
# textures (UV / Generated coordinates), Normal Map, Mix Color, Math and Color Ramp that feed BSDF inputs. Keep this
# list in step with the exporter.
CATEGORIES = (
    ("CANDELA_SHADER_INPUT", "Input", [
        ("ShaderNodeTexCoord", None, {}),
    ]),
    ("CANDELA_SHADER_OUTPUT", "Output", [
        ("ShaderNodeOutputMaterial", _object_tree, {}),
        ("ShaderNodeOutputWorld", _world_tree, {}),
    ]),
    ("CANDELA_SHADER_SHADER", "Shader", [
        ("ShaderNodeBsdfPrincipled", _object_tree, {}),
        ("ShaderNodeBsdfDiffuse", _object_tree, {}),
        ("ShaderNodeBsdfGlossy", _object_tree, {}),
        ("ShaderNodeBsdfAnisotropic", _object_tree, {}),
        ("ShaderNodeBsdfGlass", _object_tree, {}),
        ("ShaderNodeBsdfRefraction", _object_tree, {}),
        ("ShaderNodeBsdfTranslucent", _object_tree, {}),
        ("ShaderNodeBsdfTransparent", _object_tree, {}),
        ("ShaderNodeEmission", None, {}),
        ("ShaderNodeHoldout", _object_tree, {}),
        ("ShaderNodeMixShader", None, {}),
        ("ShaderNodeAddShader", None, {}),
        ("ShaderNodeBackground", _world_tree, {}),
    ]),
    ("CANDELA_SHADER_TEXTURE", "Texture", [
        ("ShaderNodeTexImage", _object_tree, {}),
        ("ShaderNodeTexEnvironment", _world_tree, {}),
    ]),
    ("CANDELA_SHADER_COLOR", "Color", [
        ("ShaderNodeMix", None, {"label": "Mix Color", "settings": {"data_type": "'RGBA'"}}),
    ]),
    ("CANDELA_SHADER_VECTOR", "Vector", [
        ("ShaderNodeNormalMap", _object_tree, {}),
    ]),
    ("CANDELA_SHADER_CONVERTER", "Converter", [
        ("ShaderNodeMath", None, {}),
        ("ShaderNodeValToRGB", None, {}),
    ]),
    ("CANDELA_SHADER_LAYOUT", "Layout", [
        ("NodeFrame", None, {}),
        ("NodeReroute", None, {}),
    ]),
)


def node_types():
    """Every node type the categories list (tests check each is a real Blender node type)."""
    return [node for _, _, items in CATEGORIES for node, _, _ in items]


def categories():
    return [CandelaShaderNodeCategory(identifier, label,
                                      items=[NodeItem(node, poll=poll, **kwargs) for node, poll, kwargs in items])
            for identifier, label, items in CATEGORIES]


def register():
    if MENU_ID in nodeitems_utils._node_categories:   # a previous registration was not undone (reload)
        nodeitems_utils.unregister_node_categories(MENU_ID)
    nodeitems_utils.register_node_categories(MENU_ID, categories())


def unregister():
    if MENU_ID in nodeitems_utils._node_categories:
        nodeitems_utils.unregister_node_categories(MENU_ID)
