"""Blender side of the parity suite: build each scene and render it with Cycles and with Candela, each twice
with independent seeds, in ONE Blender process, and print the EXR paths as one JSON line.

    bin/candela-blender -b --factory-startup -noaudio --python-exit-code 1 --python tests/parity/render_pair.py -- \
        --scenes point,area_rect --size 128 --samples 256 --threads 2 --out DIR

Both engines get the same settings (mirrored on both sides): CPU, --samples samples per pixel in total (split
into two renders of half as many with seeds 1 and 2, whose difference gives the noise estimate), box pixel filter
of width 1 px (every sample lands in exactly one pixel, so pixels are independent), 12 bounces for every ray type,
caustics on, no denoising, no adaptive sampling, no clamping, no light tree (Cycles 3.4 has none: Candela picks
lights by emitting area, as Cycles 3.4's light distribution does for emissive triangles), Standard view transform.
"""

import argparse
import json
import os
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path[:0] = [os.path.join(ROOT, "examples"), os.path.join(ROOT, "bench"), HERE]

import parity_scenes  # noqa: E402
from accuracy_render import render  # noqa: E402  (sets the sample count, renders, writes the EXR, times it)

SEEDS = (1, 2)
FILTER = "BOX"
FILTER_WIDTH = 1.0
CANDELA_LIGHT_SELECTION = "AREA"


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="render_pair.py")
    ap.add_argument("--scenes", required=True, help="comma-separated parity scene names")
    ap.add_argument("--size", type=int, default=128, help="image width in pixels")
    ap.add_argument("--samples", type=int, default=256, help="total samples per pixel per engine (two halves)")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", required=True)
    ap.add_argument("--engines", default="CYCLES,CANDELA")
    ap.add_argument("--integrator", default="PATH", help="Candela's integrator (a registry name)")
    return ap.parse_args(argv)


def unbiased_light_paths(scene):
    """Cycles' Light Paths without the limits and clamps (every bounce type up to Max Bounces, no clamp, no Filter
    Glossy), on both engines: the reference for an integrator that does not apply those settings (it does not
    publish them: its image is the full solution, and the add-on warns when they are set)."""
    c, p = scene.cycles, scene.candela
    for key in ("diffuse_bounces", "glossy_bounces", "transmission_bounces"):
        setattr(c, key, c.max_bounces)
        setattr(p, key, 1024)
    c.sample_clamp_direct = c.sample_clamp_indirect = c.blur_glossy = 0.0
    p.clamp_direct = p.clamp_indirect = p.filter_glossy = 0.0


def applies_light_paths(integrator):
    from candela import schema
    return "clamp_indirect" in {spec["key"] for spec in schema.integrator_params().get(integrator, [])}


def mirror_settings(scene, seed, integrator="PATH"):
    """The settings both engines must share beyond examples/cornell_box.configure_* (which set bounces etc.)."""
    c = scene.cycles
    c.pixel_filter_type = FILTER
    c.filter_width = FILTER_WIDTH
    c.seed = seed
    c.use_animated_seed = False
    c.light_sampling_threshold = 0.0     # 3.4: no light culling by contribution (unbiased)
    p = scene.candela
    p.pixel_filter = FILTER
    p.filter_width = FILTER_WIDTH
    p.seed = seed
    p.use_animated_seed = False
    p.integrator = integrator
    if not applies_light_paths(integrator):
        unbiased_light_paths(scene)
    if integrator == "PATH":  # the other integrators choose lights their own way (or publish the same setting)
        p.light_selection = CANDELA_LIGHT_SELECTION
    p.clamp_indirect = c.sample_clamp_indirect   # 0 but in the *_cycles_defaults scenes (parity_scenes.py)
    p.noise_threshold = 0.0
    p.time_limit = 0.0
    r = scene.render.image_settings
    r.file_format = "OPEN_EXR"
    r.color_depth = "32"
    r.color_mode = "RGBA"


def main():
    a = parse_args()
    os.makedirs(a.out, exist_ok=True)
    engines = [e.strip().upper() for e in a.engines.split(",") if e.strip()]
    half = max(1, a.samples // 2)
    results = []
    for name in a.scenes.split(","):
        scene = parity_scenes.build(name, bpy.context.scene, size=a.size, threads=a.threads, out_dir=a.out)
        entry = {"scene": name, "size": [scene.render.resolution_x, scene.render.resolution_y],
                 "samples_per_render": half, "renders": {}}
        for engine in engines:
            scene.render.engine = engine
            files, seconds = [], []
            for seed in SEEDS:
                mirror_settings(scene, seed, a.integrator)
                path = os.path.join(a.out, f"{name}_{engine.lower()}_seed{seed}.exr")
                t0 = time.perf_counter()
                render(scene, engine, half, path)
                seconds.append(time.perf_counter() - t0)
                files.append(path)
            entry["renders"][engine] = {"exr": files, "seconds": seconds}
            print(f"parity: {name} {engine} {len(SEEDS)} x {half} spp in {sum(seconds):.1f} s", flush=True)
        results.append(entry)
    print("PARITY_JSON " + json.dumps({"blender": bpy.app.version_string, "known_scenes": list(parity_scenes.SCENES),
                                       "settings": {
        "filter": FILTER, "filter_width": FILTER_WIDTH, "seeds": SEEDS, "max_bounces": parity_scenes.cb.MAX_BOUNCES,
        "candela_light_selection": CANDELA_LIGHT_SELECTION}, "scenes": results}), flush=True)


if __name__ == "__main__":
    main()
