"""The world → a constant background radiance (`world_color`) or, when the Background's inputs vary with the
view direction (an Environment Texture, a Mapping rotating it, a Math node on it), a world shader program bound
as WORLD (docs/architecture.md): the renderer evaluates it per direction and importance-samples it."""

import numpy as np

from .shader_nodes import NodeCompiler, resolve
from .shader_tables import ShaderTables, const3, is_const


def world_arrays(world, warnings, tables=None):
    """{"world_color": (3,)} for a constant world; {} when the world is a program (bound in `tables`)."""
    if world is None:
        return {"world_color": np.zeros(3, np.float32)}
    if not world.use_nodes or world.node_tree is None:
        return {"world_color": np.array(world.color[:3], np.float32)}
    output = world.node_tree.get_output_node('CYCLES')
    out, _, ctx = resolve(output.inputs["Surface"], ()) if output is not None else (None, None, ())
    if out is None:
        return {"world_color": np.zeros(3, np.float32)}
    node = out.node
    if node.bl_idname != "ShaderNodeBackground":
        warnings.add(f"Candela: world '{world.name}': node '{node.name}' ({node.bl_idname}) is not supported yet; "
                     f"using the world's viewport colour")
        return {"world_color": np.array(world.color[:3], np.float32)}
    tables = tables if tables is not None else ShaderTables(warnings)
    nodes = NodeCompiler(tables, f"world '{world.name}'", warnings, world=True)
    radiance = nodes.program.mul(nodes.input(node.inputs["Color"], ctx), nodes.input(node.inputs["Strength"], ctx))
    if is_const(radiance):
        return {"world_color": np.array(const3(radiance), np.float32)}
    program = tables.add_program(nodes.program)
    tables.bind("WORLD", 0, 0, 3, program, radiance)
    return {}


def world_color(world, warnings):
    """Background colour × strength feeding the Cycles World Output; `world.color` without nodes; black if None.
    (A varying world has no single colour: its program's value at one direction is not meaningful here, so this
    returns black for it; export_scene uses world_arrays.)"""
    return world_arrays(world, warnings).get("world_color", np.zeros(3, np.float32))
