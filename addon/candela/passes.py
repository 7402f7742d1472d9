"""The render passes Candela writes, in one table: what `update_render_passes` registers, what the native side is
asked to accumulate (the `passes` param) and what the View Layer > Passes panel draws.

Names, channels and channel ids are Blender's (and Cycles') for the standard passes, so the compositor's Render Layers
node and multilayer EXRs (`ViewLayer.Depth.Z`, `ViewLayer.Normal.X`, `ViewLayer.IndexOB.X`) see what they expect.
"""

from collections import namedtuple

RenderPass = namedtuple("RenderPass", "name channels chan_id pass_type owner prop")

# owner: where the toggle lives — "view_layer" (Blender's own settings, as Cycles uses them) or "candela"
# (view_layer.candela, Candela's properties).
PASSES = (
    RenderPass("Depth", 1, "Z", 'VALUE', "view_layer", "use_pass_z"),
    RenderPass("Normal", 3, "XYZ", 'VECTOR', "view_layer", "use_pass_normal"),
    RenderPass("Albedo", 3, "RGB", 'COLOR', "candela", "use_pass_albedo"),
    RenderPass("IndexOB", 1, "X", 'VALUE', "view_layer", "use_pass_object_index"),
    RenderPass("Noise", 1, "X", 'VALUE', "candela", "use_pass_noise"),
)


def _settings(view_layer, render_pass):
    return view_layer if render_pass.owner == "view_layer" else getattr(view_layer, "candela", None)


def enabled_passes(view_layer):
    """The passes `view_layer` asks for, beyond Combined (always written)."""
    if view_layer is None:
        return []
    result = []
    for render_pass in PASSES:
        settings = _settings(view_layer, render_pass)
        if settings is not None and getattr(settings, render_pass.prop, False):
            result.append(render_pass)
    return result


def strategy_passes(scene):
    """BDPT's strategy images (one RGB pass per (depth, s, t), weighted and unweighted) when the scene renders with
    BDPT and its Strategy Images setting is on: the setting is their toggle, so they need no entry in the panel."""
    settings = getattr(scene, "candela", None) if scene is not None else None
    if settings is None or getattr(settings, "integrator", "") != "BDPT" or \
            not getattr(settings, "bdpt_strategy_images", False):
        return []
    from . import schema
    depth = min(int(settings.bdpt_strategy_depth), int(settings.max_bounces) + 1)
    return [RenderPass(name, 3, "RGB", 'COLOR', None, None) for name in schema.bdpt_strategy_passes(depth)]


def native_pass_list(view_layer, scene=None):
    """The `passes` param: comma-separated pass names."""
    return ",".join(p.name for p in enabled_passes(view_layer) + strategy_passes(scene))
