"""Blender side of `make door-gap` (bench/door_gap.py): build one variant of the door-gap scene and render it with
Cycles and with Candela's integrators, several independent seeds each, in ONE Blender process; print the EXR paths
as one JSON line.

    bin/candela-blender -b --factory-startup -noaudio --python-exit-code 1 --python bench/door_gap_render.py -- \
        --variant door --size 64 --seeds 1,2,3,4 --engines CYCLES:2048,PATH:2048,BDPT:512 --out DIR

Variants (build_variant): the door ajar of examples/scenes.py (`door`); the same rooms with the door at another
angle, its slabs touching the floor, ceiling and lintel with hidden faces (as in scenes.py), sunk 1 cm into them
instead (`_sunk`: no coplanar faces but a sliver of the door's top under the lintel), or with a casing and a threshold lying on visible faces (`_trim`);
and the slit of bench/door_gap_analytic.py, whose image mean has a closed form (`slit_*`). Settings are
those of the parity suite (tests/parity/render_pair.py: box filter 1 px, 12 bounces of every kind, no clamping, no
light threshold, Candela's lights chosen by area for PATH), so a difference is the estimators', not a setting's.
"""

import argparse
import json
import math
import os
import sys
import time

import bpy
from mathutils import Matrix

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path[:0] = [os.path.join(ROOT, "examples"), os.path.join(ROOT, "tests", "parity"), HERE]

import cornell_box as cb  # noqa: E402
import door_gap_analytic as an  # noqa: E402
import parity_scenes as pscenes  # noqa: E402


def _example_scenes():
    """examples/scenes.py, loaded by path: the in-Blender tests have a `scenes` module of their own."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("candela_example_scenes", os.path.join(ROOT, "examples", "scenes.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


scenes = _example_scenes()
from accuracy_render import render  # noqa: E402
from render_pair import mirror_settings  # noqa: E402


def build_rooms(scene, angle_deg=8.0, sink=0.0, trim=False, door_rgb=(0.5, 0.4, 0.3)):
    """examples/scenes.py's build_door with the door angle and the contact as parameters. sink 0: the wall slabs'
    and the door's faces lie in the floor's, the ceiling's and the lintel's planes (coplanar contact, hidden: the
    touching faces face each other). sink > 0: every slab reaches `sink` past the surfaces it meets instead, but for the door's top, which
    stays in the lintel's plane (raised, it would block the light passing over it: 1 cm took 11 % of the image), so
    the only coplanar faces left are the door's top and the lintel's bottom over the few millimetres by the hinge
    where the door is under the lintel. trim: a door casing (10 cm strips around the doorway, quads lying on both faces of the
    wall) and a threshold (a quad on the floor across the doorway, 30 cm into each room), all of the wall's or the
    floor's material: visible faces with a coplanar twin, as modellers leave them."""
    white = scenes.diffuse("White", (0.7, 0.7, 0.7))
    floor = scenes.diffuse("Floor", (0.6, 0.5, 0.4))
    for name, mat, matrix in (
            ("Floor", floor, Matrix.Diagonal((6, 2, 1, 1))),
            ("Ceiling", white, Matrix.Translation((0, 0, 2.5)) @ Matrix.Rotation(math.pi, 4, "X")
             @ Matrix.Diagonal((6, 2, 1, 1))),
            ("Back", white, Matrix.Translation((0, 2, 1.25)) @ Matrix.Rotation(math.radians(90), 4, "X")
             @ Matrix.Diagonal((6, 1.25, 1, 1))),
            ("Front", white, Matrix.Translation((0, -2, 1.25)) @ Matrix.Rotation(math.radians(-90), 4, "X")
             @ Matrix.Diagonal((6, 1.25, 1, 1))),
            ("Left", white, Matrix.Translation((-6, 0, 1.25)) @ Matrix.Rotation(math.radians(90), 4, "Y")
             @ Matrix.Diagonal((1.25, 2, 1, 1))),
            ("Right", white, Matrix.Translation((6, 0, 1.25)) @ Matrix.Rotation(math.radians(-90), 4, "Y")
             @ Matrix.Diagonal((1.25, 2, 1, 1)))):
        scenes.rectangle(scene, name, mat, matrix)
    s = sink
    # The dividing wall at x = 0, doorway y ∈ [0.2, 1.2], z ∈ [0, 2]; with sink, slabs reach past floor, ceiling
    # and front/back walls by s.
    scenes.cube(scene, "WallA", white, Matrix.Translation((0, -0.9 - s / 2, 1.25))
                @ Matrix.Diagonal((0.05, 1.1 + s / 2, 1.25 + s, 1)))
    scenes.cube(scene, "WallB", white, Matrix.Translation((0, 1.6 + s / 2, 1.25))
                @ Matrix.Diagonal((0.05, 0.4 + s / 2, 1.25 + s, 1)))
    scenes.cube(scene, "Lintel", white, Matrix.Translation((0, 0.7, 2.25 + s / 2))
                @ Matrix.Diagonal((0.05, 0.5, 0.25 + s / 2, 1)))
    hinge = Matrix.Translation((0, 1.2, 0)) @ Matrix.Rotation(math.radians(angle_deg), 4, "Z") \
        @ Matrix.Translation((0, -1.2, 0))
    scenes.cube(scene, "Door", scenes.diffuse("Door", door_rgb),
                hinge @ Matrix.Translation((0.06, 0.7, 1.0 - s / 2)) @ Matrix.Diagonal((0.02, 0.49, 1.0 + s / 2, 1)))
    if trim:
        for side in (-1, 1):
            x = side * 0.05
            turn = Matrix.Rotation(math.radians(90 * side), 4, "Y")   # the quad's normal to ±x, out of the wall
            for name, (y0, y1, z0, z1) in (("JambA", (0.1, 0.2, 0.0, 2.1)), ("JambB", (1.2, 1.3, 0.0, 2.1)),
                                           ("Head", (0.1, 1.3, 2.0, 2.1))):
                scenes.rectangle(scene, f"Casing{name}{side:+d}", white,
                                 Matrix.Translation((x, (y0 + y1) / 2, (z0 + z1) / 2)) @ turn
                                 @ Matrix.Diagonal(((z1 - z0) / 2, (y1 - y0) / 2, 1, 1)))
        scenes.rectangle(scene, "Threshold", floor, Matrix.Translation((0, 0.7, 0)) @ Matrix.Diagonal((0.3, 0.5, 1, 1)))
    scenes.area_light(scene, "Lamp", (3.5, 0.8, 2.2), 0.6, 400.0, rotation_deg=(0.0, -120.0, 0.0))
    scenes.camera(scene, (-5.4, -1.5, 1.3), (88.0, 0.0, -65.0), lens=24.0)
    scenes.world(scene, (0, 0, 0), 0.0)
    return 4 / 3


def box(scene, name, material, lo, hi):
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    half = [(b - a) / 2 for a, b in zip(lo, hi)]
    return scenes.cube(scene, name, material, Matrix.Translation(centre) @ Matrix.Diagonal((*half, 1)))


def build_slit(scene, slab, boxes=False, rug=False):
    """bench/door_gap_analytic.py's room: a black room with a floor of reflectance ρ, its ceiling two quads
    (slab 0) or two slabs leaving a slit under a uniform sky. boxes: each slab is two overlapping boxes (their top,
    bottom and side faces coplanar where they overlap). rug: a quad of the floor's material lies in the floor's
    plane under the slit, x, y ∈ [−0.5, 0.5] (a coplanar overlap on the receiver)."""
    R, H, W = an.ROOM_HALF, an.HEIGHT, an.SLIT_WIDTH
    black = scenes.diffuse("Black", (0.0, 0.0, 0.0))
    rho = (an.FLOOR_RHO,) * 3
    scenes.rectangle(scene, "Floor", scenes.diffuse("Floor", rho), Matrix.Diagonal((R, R, 1, 1)))
    top = H + slab
    for name, matrix in (
            ("WallXn", Matrix.Translation((-R, 0, top / 2)) @ Matrix.Rotation(math.radians(90), 4, "Y")
             @ Matrix.Diagonal((top / 2, R, 1, 1))),
            ("WallXp", Matrix.Translation((R, 0, top / 2)) @ Matrix.Rotation(math.radians(-90), 4, "Y")
             @ Matrix.Diagonal((top / 2, R, 1, 1))),
            ("WallYn", Matrix.Translation((0, -R, top / 2)) @ Matrix.Rotation(math.radians(-90), 4, "X")
             @ Matrix.Diagonal((R, top / 2, 1, 1))),
            ("WallYp", Matrix.Translation((0, R, top / 2)) @ Matrix.Rotation(math.radians(90), 4, "X")
             @ Matrix.Diagonal((R, top / 2, 1, 1)))):
        scenes.rectangle(scene, name, black, matrix)
    if slab == 0.0:
        for sign in (-1, 1):
            scenes.rectangle(scene, f"Ceiling{sign:+d}", black, Matrix.Translation((sign * (R + W / 2) / 2, 0, H))
                             @ Matrix.Rotation(math.pi, 4, "X") @ Matrix.Diagonal(((R - W / 2) / 2, R, 1, 1)))
    else:
        for sign in (-1, 1):
            spans = [(W / 2, 0.6), (0.4, R)] if boxes else [(W / 2, R)]
            for k, (a, b) in enumerate(spans):
                x0, x1 = sorted((sign * a, sign * b))
                box(scene, f"Slab{sign:+d}_{k}", black, (x0, -R, H), (x1, R, H + slab))
    if rug:
        scenes.rectangle(scene, "Rug", scenes.diffuse("Rug", rho), Matrix.Diagonal((0.5, 0.5, 1, 1)))
    cam = pscenes.ortho_camera(scene, (0.0, 0.0, H - 0.1), 2 * an.WINDOW_HALF)
    cam.data.clip_start = 0.01
    scenes.world(scene, (1.0, 1.0, 1.0), 1.0)
    return 1.0


def build_variant(scene, name, size):
    """name: `door` (examples/scenes.py as it is), `ajar<deg>`, `ajar<deg>_sunk`, `ajar<deg>_trim` (build_rooms),
    or `slit_thin`, `slit_slab`, `slit_boxes`, `slit_rug`, `slit_overlap` (boxes and rug; build_slit), each also
    as `slit_<mode>_far<D>` (the camera D m away)."""
    cb.clear_scene(scene)
    if name == "door":
        aspect = scenes.BUILDERS["door"](scene)
    elif name.startswith("slit_"):
        mode, _, far = name[5:].partition("_far")
        if mode not in ("thin", "slab", "boxes", "rug", "overlap"):
            raise SystemExit(f"unknown variant {name!r}")
        aspect = build_slit(scene, 0.0 if mode == "thin" else an.SLAB, boxes=mode in ("boxes", "overlap"),
                            rug=mode in ("rug", "overlap"))
        if far:
            # `_far<D>`: the orthographic camera D metres higher, its rays starting where they did (clip start D):
            # the same image, with camera-world coordinates ~D at the floor, so the scale-relative ray offsets
            # there grow with D (256 ulps of D: 2 mm at D = 100, 16 mm at D = 1000).
            cam = scene.camera
            cam.location.z += float(far)
            cam.data.clip_start, cam.data.clip_end = float(far), float(far) + 100.0
    else:
        base, _, mode = name.partition("_")
        if not base.startswith("ajar") or mode not in ("", "sunk", "trim"):
            raise SystemExit(f"unknown variant {name!r}")
        aspect = build_rooms(scene, angle_deg=float(base[4:]), sink=0.01 if mode == "sunk" else 0.0,
                             trim=mode == "trim")
    cb.configure_render(scene, size=size, threads=2)
    scene.render.resolution_y = max(1, round(size / aspect))
    cb.configure_cycles(scene, samples=16, threads=2)
    cb.configure_candela(scene, samples=16, threads=2)
    return scene


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="door_gap_render.py")
    ap.add_argument("--variant", required=True)
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--samples", type=int, default=256, help="samples per pixel of each render")
    ap.add_argument("--seeds", default="1,2,3,4")
    ap.add_argument("--engines", default="CYCLES,PATH,BDPT",
                    help="CYCLES and Candela integrator names, each NAME or NAME:SAMPLES")
    ap.add_argument("--set", action="append", default=[], help="Candela property key=value (all its renders)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", required=True)
    return ap.parse_args(argv)


def main():
    a = parse_args()
    os.makedirs(a.out, exist_ok=True)
    scene = build_variant(bpy.context.scene, a.variant, a.size)
    scene.render.threads_mode = "FIXED"
    scene.render.threads = a.threads
    renders = {}
    for spec in [e.strip().upper() for e in a.engines.split(",") if e.strip()]:
        engine, _, spp = spec.partition(":")
        samples = int(spp) if spp else a.samples
        blender_engine = "CYCLES" if engine == "CYCLES" else "CANDELA"
        scene.render.engine = blender_engine
        files, seconds = [], []
        for seed in [int(s) for s in a.seeds.split(",")]:
            mirror_settings(scene, seed, "PATH" if engine == "CYCLES" else engine)
            for kv in a.set:
                key, value = kv.split("=", 1)
                setattr(scene.candela, key, type(getattr(scene.candela, key))(value))
            path = os.path.join(a.out, f"{a.variant}_{engine.lower()}_seed{seed}.exr")
            t0 = time.perf_counter()
            render(scene, blender_engine, samples, path)
            seconds.append(time.perf_counter() - t0)
            files.append(path)
        renders[engine] = {"exr": files, "seconds": seconds, "samples": samples}
        print(f"door_gap: {a.variant} {engine} {len(files)} x {samples} spp in {sum(seconds):.1f} s", flush=True)
    print("DOOR_GAP_JSON " + json.dumps({"variant": a.variant, "size": [scene.render.resolution_x,
                                         scene.render.resolution_y], "samples": a.samples, "renders": renders}),
          flush=True)


if __name__ == "__main__":
    main()
