"""Blender side of `make accuracy`: build one scene, render it with one engine configuration at several sample
counts in ONE Blender process, write an EXR per count and print the times as one JSON line.

    bin/candela-blender -b --factory-startup --python-exit-code 1 --python bench/accuracy_render.py -- \
        --scene veach_mis --engine CANDELA --set sampler=SOBOL --counts 1,2,4,8 --size 128 --threads 2 \
        --out DIR --tag NAME

With `--variant TAG:key=value,key=value` (repeatable; Candela only) it renders several settings variants of
the scene in the same process, each at every count, into TAG_N.exr; each variant starts from the scene's
settings (and --set), so variants do not leak into each other (examples/sampling_gallery.py uses this).

Each run reports three times:
  seconds:     set-up excluded, so that it measures the sampling itself. Candela: the native render time
               (session.stats()["render_seconds"]: no export, no BVH build); Cycles: the wall time minus a
               set-up estimate, 2·t(1) − t(2) from two extra warm-up renders at 1 and 2 samples (Cycles syncs
               and builds its BVH again for every render).
  wall_seconds: the wall time of bpy.ops.render.render.
  cpu_seconds:  the process CPU time (all threads) of bpy.ops.render.render. On a shared machine this is the
               stable one: wall time depends on what else runs (bench/accuracy.py fits its cost per sample).
"""

import argparse
import json
import os
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "examples"))

import scenes  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="accuracy_render.py")
    ap.add_argument("--scene", required=True)
    ap.add_argument("--engine", required=True, choices=["CANDELA", "CYCLES"])
    ap.add_argument("--set", action="append", default=[], help="scene.candela property override key=value")
    ap.add_argument("--counts", required=True, help="comma-separated sample counts")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", required=True)
    ap.add_argument("--tag", required=True)
    ap.add_argument("--variant", action="append", default=[],
                    help="TAG:key=value,... a settings variant rendered in this process (repeatable)")
    return ap.parse_args(argv)


def parse_variant(text):
    """'TAG:key=value,key=value' -> (TAG, [(key, value), ...])."""
    tag, _, rest = text.partition(":")
    pairs = [kv.split("=", 1) for kv in rest.split(",") if kv]
    return tag, [(k, parse_value(v)) for k, v in pairs]


def parse_value(text):
    for cast in (int, float):
        try:
            return cast(text)
        except ValueError:
            pass
    return text


def render(scene, engine, samples, path):
    if engine == "CANDELA":
        scene.candela.samples = samples
    else:
        scene.cycles.samples = samples
    scene.render.filepath = path
    t0, c0 = time.perf_counter(), time.process_time()
    result = bpy.ops.render.render(write_still=True)
    wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    if "FINISHED" not in result or not os.path.exists(path):
        raise RuntimeError(f"{engine} render of {samples} samples failed")
    if engine == "CANDELA":
        stats = sys.modules["candela.render_loop"].last_render_stats
        return wall, cpu, float(stats["render_seconds"])
    return wall, cpu, None


def main():
    a = parse_args()
    scene = scenes.build(a.scene, bpy.context.scene, size=a.size, threads=a.threads)
    scene.render.engine = a.engine
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    if a.engine == "CANDELA":
        scene.candela.seed = a.seed
        for kv in a.set:
            key, value = kv.split("=", 1)
            setattr(scene.candela, key, parse_value(value))
    else:
        scene.cycles.seed = a.seed
    os.makedirs(a.out, exist_ok=True)
    counts = [int(c) for c in a.counts.split(",")]
    variants = [parse_variant(v) for v in a.variant] or [(a.tag, [])]
    if a.variant and a.engine != "CANDELA":
        raise SystemExit("--variant is for Candela settings only")
    baseline = {k: getattr(scene.candela, k) for _, pairs in variants for k, _ in pairs}
    setup = 0.0
    if a.engine == "CYCLES":
        t1 = min(render(scene, a.engine, 1, os.path.join(a.out, f"{a.tag}_warm1.exr"))[0] for _ in range(2))
        t2 = min(render(scene, a.engine, 2, os.path.join(a.out, f"{a.tag}_warm2.exr"))[0] for _ in range(2))
        setup = max(0.0, 2.0 * t1 - t2)
    runs = []
    for tag, pairs in variants:
        for key, value in baseline.items():
            setattr(scene.candela, key, value)
        for key, value in pairs:
            setattr(scene.candela, key, value)
        for n in counts:
            path = os.path.join(a.out, f"{tag}_{n}.exr")
            wall, cpu, native = render(scene, a.engine, n, path)
            seconds = native if native is not None else max(wall - setup, 1e-6)
            runs.append({"samples": n, "seconds": seconds, "wall_seconds": wall, "cpu_seconds": cpu, "exr": path,
                         "variant": tag})
    # The last Candela render's Info log lines (AUTO's scene features: accuracy.py's choice of reference integrator).
    info = sys.modules["candela.render_loop"].last_render_stats.get("info", []) if a.engine == "CANDELA" else []
    print("ACCURACY_JSON " + json.dumps({"scene": a.scene, "engine": a.engine, "settings": a.set,
                                         "size": [scene.render.resolution_x, scene.render.resolution_y],
                                         "setup_seconds": setup, "runs": runs, "info": info}), flush=True)


if __name__ == "__main__":
    main()
