"""Motion blur export: the camera's and every object's transform sampled over the shutter, as Cycles 3.4 syncs
them (intern/cycles/blender/sync.cpp sync_motion, object.cpp object_motion_steps), into `instance_motion`
(instances × steps × 4 × 4) and `camera_motion` (steps × 4 × 4).

Cycles' semantics: Render Properties > Motion Blur > Shutter is the shutter interval in frames (0.5 by default) and
Position (scene.cycles.motion_blur_position) places it START (the frame opens it), CENTER (the frame is its middle)
or END (the frame closes it). An object's Motion Steps s (Object Properties > Motion Blur, default 1) gives
2^s + 1 samples evenly spaced over the interval; objects with Motion Blur unticked, and everything without
Render Properties > Motion Blur, stay still. One step count serves the whole scene here: the largest any moving
object (or the camera) asks for, so an object with fewer steps is sampled more finely than Cycles samples it
(identical for motion that is linear between Cycles' samples). Only transforms move: a deforming mesh
(Cycles' Deformation) is exported at the frame's time, and the shutter curve and rolling shutter are ignored
(unsupported.py reports them).
"""

import math

import numpy as np

from .camera import camera_to_world

MAX_STEPS = 129   # the native schema's limit (2^7 + 1: Cycles' largest Motion Steps)


def object_steps(ob):
    """Cycles' motion samples of object `ob` (2^s + 1 for Motion Steps s; 0 with its Motion Blur unticked)."""
    # The original's settings: an evaluated copy is not refreshed when only a property group changes.
    cycles = getattr(getattr(ob, "original", ob), "cycles", None)
    if cycles is None or not getattr(cycles, "use_motion_blur", True):
        return 0
    return min((2 << (max(1, int(getattr(cycles, "motion_steps", 1))) - 1)) + 1, MAX_STEPS)


def shutter_offsets(scene, steps):
    """The frame offsets (from the current frame) of `steps` samples evenly spaced over the shutter interval."""
    shutter = float(scene.render.motion_blur_shutter)
    position = getattr(getattr(scene, "cycles", None), "motion_blur_position", "CENTER")
    centre = {"START": 0.5 * shutter, "END": -0.5 * shutter}.get(position, 0.0)
    return [centre + shutter * (k / (steps - 1) - 0.5) for k in range(steps)]


def instance_key(inst):
    """What identifies an object instance across the depsgraph walks of different subframes."""
    ob = inst.object
    if inst.is_instance:
        parent = inst.parent.name if inst.parent is not None else ""
        return (ob.name, parent, tuple(inst.persistent_id))
    return (ob.name,)


def motion_arrays(engine, depsgraph, camera, keys, instance_steps, still):
    """`instance_motion` and `camera_motion` for the instances whose keys are `keys` (export order) and the render
    camera (`camera`, an original object, or None): each transform sampled at the shutter's times by moving
    Blender's frame (engine.frame_set) and restoring it after. `instance_steps`: each instance's object_steps; `still`: the exported instance_transform, which instances that do not move repeat. Returns {}
    when nothing moves."""
    scene = depsgraph.scene
    if not scene.render.use_motion_blur or scene.render.motion_blur_shutter <= 0.0:
        return {}
    steps = max(list(instance_steps) + [object_steps(camera) if camera else 0])
    if steps < 2:
        return {}
    moving = {key[0] for key, n in zip(keys, instance_steps) if n >= 2}
    frame, subframe = scene.frame_current, scene.frame_subframe
    samples = []          # per step: {key: matrix}
    cameras = []
    try:
        for offset in shutter_offsets(scene, steps):
            time = frame + subframe + offset
            whole = math.floor(time)
            engine.frame_set(int(whole), time - whole)
            matrices = {}
            for inst in depsgraph.object_instances:
                if inst.object.name in moving:
                    matrices[instance_key(inst)] = np.array(inst.matrix_world, np.float32)
            samples.append(matrices)
            if camera is not None:
                cameras.append(camera_to_world(camera.evaluated_get(depsgraph).matrix_world))
    finally:
        engine.frame_set(frame, subframe)
    out = {}
    if keys:
        motion = np.zeros((len(keys), steps, 4, 4), np.float32)
        any_moves = False
        for i, key in enumerate(keys):
            mats = [s.get(key) for s in samples] if instance_steps[i] >= 2 else [None]
            if any(m is None for m in mats):   # not there at every time (or not moving): it stays still
                motion[i] = still[i]
                continue
            motion[i] = np.stack(mats)
            any_moves |= any(not np.array_equal(m, mats[0]) for m in mats)
        if any_moves:
            out["instance_motion"] = motion
    if cameras and object_steps(camera) >= 2 and any(not np.array_equal(c, cameras[0]) for c in cameras):
        out["camera_motion"] = np.stack(cameras).astype(np.float32)
    return out
