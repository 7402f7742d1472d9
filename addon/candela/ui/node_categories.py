"""Shift+A in the Shader Editor while Candela is the engine: one list of exactly the nodes Candela renders.

The list is generated, never written by hand: the node types come from the exporter's own tables (materials.py's
SUPPORTED_SHADER_NODES, the NodeCompiler's SUPPORTED_INPUT_NODES, the world's Background and the outputs), and
each sits in the category, with the label and settings, under which Blender's own menu lists it (nodeitems_builtins),
so Candela's menu looks like Blender's minus what Candela cannot render. Node groups, frames and reroutes stay
(the exporter follows groups and reroutes).

Blender's own shader categories poll only for a shader tree, whatever the engine, so with Candela they would appear
too and every category twice; while Candela is the engine they are hidden (their poll is wrapped on register and
restored on unregister).
"""

import nodeitems_builtins
import nodeitems_utils
from nodeitems_utils import NodeCategory, NodeItem

from ..export.materials import SUPPORTED_SHADER_NODES
from ..export.shader_nodes import SUPPORTED_INPUT_NODES

ENGINE = "CANDELA"
MENU_ID = "CANDELA_SHADER"   # nodeitems_utils' registry key for these categories

# Where the exporter reads a node: material trees only, world trees only (other nodes: both).
MATERIAL_ONLY = set(SUPPORTED_SHADER_NODES) - {"ShaderNodeEmission", "ShaderNodeMixShader", "ShaderNodeAddShader"} | {
    "ShaderNodeHoldout", "ShaderNodeOutputMaterial", "ShaderNodeNormalMap", "ShaderNodeTexImage", "ShaderNodeUVMap"}
WORLD_ONLY = {"ShaderNodeBackground", "ShaderNodeOutputWorld", "ShaderNodeTexEnvironment"}
LAYOUT = {"NodeFrame", "NodeReroute"}


def supported_nodes():
    """Every node type the exporter reads."""
    return (set(SUPPORTED_SHADER_NODES) | set(SUPPORTED_INPUT_NODES) | MATERIAL_ONLY | WORLD_ONLY) | LAYOUT


def _object_tree(context):
    return context.space_data.shader_type == 'OBJECT'


def _world_tree(context):
    return context.space_data.shader_type == 'WORLD'


def _poll_for(node):
    return _object_tree if node in MATERIAL_ONLY else _world_tree if node in WORLD_ONLY else None


class CandelaShaderNodeCategory(NodeCategory):
    @classmethod
    def poll(cls, context):
        space = getattr(context, "space_data", None)
        return (context.engine == ENGINE and space is not None and space.type == 'NODE_EDITOR'
                and space.tree_type == 'ShaderNodeTree')


def _builtin_items(category):
    """A built-in category's items (its item generator with no context yields them all)."""
    try:
        return list(category.items(None))
    except Exception:   # a generator that needs a context (node groups): not a static list
        return None


def categories():
    """Candela's categories: Blender's shader categories restricted to the supported nodes, in Blender's order."""
    supported = supported_nodes()
    out = []
    for builtin in nodeitems_builtins.shader_node_categories:
        identifier = "CANDELA_" + builtin.identifier
        if builtin.identifier == "SH_NEW_GROUP":   # node groups: Blender's own generator (it polls itself)
            out.append(CandelaShaderNodeCategory(identifier, builtin.name, items=builtin.items))
            continue
        items = _builtin_items(builtin) or []
        chosen = []
        for item in items:
            node = getattr(item, "nodetype", None)
            if node in supported:
                chosen.append(NodeItem(node, label=item._label, settings=item.settings, poll=_poll_for(node)))
        if chosen:
            out.append(CandelaShaderNodeCategory(identifier, builtin.name, items=chosen))
    return out


def node_types():
    """Every node type the categories list (tests check each is a real Blender node type)."""
    return [item.nodetype for cat in categories() for item in (_builtin_items(cat) or []) if hasattr(item, "nodetype")]


_builtin_poll = None   # the built-in categories' original poll while ours is installed


def _hide_builtins():
    global _builtin_poll
    cls = nodeitems_builtins.ShaderNodeCategory
    if _builtin_poll is not None:
        return
    original = cls.__dict__["poll"]   # the classmethod object itself

    def poll(c, context):
        return getattr(context, "engine", None) != ENGINE and original.__func__(c, context)

    _builtin_poll = original
    cls.poll = classmethod(poll)


def _restore_builtins():
    global _builtin_poll
    if _builtin_poll is not None:
        nodeitems_builtins.ShaderNodeCategory.poll = _builtin_poll
        _builtin_poll = None


def register():
    if MENU_ID in nodeitems_utils._node_categories:   # a previous registration was not undone (reload)
        nodeitems_utils.unregister_node_categories(MENU_ID)
    nodeitems_utils.register_node_categories(MENU_ID, categories())
    _hide_builtins()


def unregister():
    _restore_builtins()
    if MENU_ID in nodeitems_utils._node_categories:
        nodeitems_utils.unregister_node_categories(MENU_ID)
