"""The world → a constant background radiance (`world_color`)."""

import numpy as np


def world_color(world, warnings):
    """Background colour × strength feeding the Cycles World Output; `world.color` without nodes; black if None."""
    if world is None:
        return np.zeros(3, np.float32)
    if not world.use_nodes or world.node_tree is None:
        return np.array(world.color[:3], np.float32)
    output = world.node_tree.get_output_node('CYCLES')
    if output is None or not output.inputs["Surface"].is_linked:
        return np.zeros(3, np.float32)
    node = output.inputs["Surface"].links[0].from_node
    if node.bl_idname != "ShaderNodeBackground":
        warnings.add(f"Candela: world '{world.name}': node '{node.name}' ({node.bl_idname}) is not supported yet; "
                     f"using the world's viewport colour")
        return np.array(world.color[:3], np.float32)
    color, strength = node.inputs["Color"], node.inputs["Strength"]
    for socket in (color, strength):
        if socket.is_linked:
            warnings.add(f"Candela: world '{world.name}': input '{socket.name}' of '{node.name}' is driven by "
                         f"another node, which is not supported yet; using the input's own value")
    return (np.array(color.default_value[:3]) * strength.default_value).astype(np.float32)
