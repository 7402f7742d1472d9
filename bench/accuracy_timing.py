"""Blender side of `make accuracy`'s timing phase: the cost per sample of every configuration of one scene,
measured interleaved in ONE Blender process so that all configurations see the same load.

    bin/candela-blender -b --factory-startup --python-exit-code 1 --python bench/accuracy_timing.py -- \
        --scene cornell_box --size 96 --threads 2 --counts 4,32 --repeats 3 --out DIR \
        --config "Cycles|CYCLES|" --config "Candela PATH SOBOL|CANDELA|integrator=PATH,sampler=SOBOL"

For each repeat, for each configuration in turn, it renders at the two counts n1 < n2 and records each render's
process CPU time (all threads). bench/accuracy.py takes, per configuration, the least CPU time at each count
over the repeats (the render least disturbed by other jobs on this shared machine) and the cost per sample
(min t(n2) − min t(n1)) / (n2 − n1), in which the per-render set-up (export, BVH, Cycles' sync) cancels.
Round-robin order: a load that comes and goes hits every configuration alike instead of whichever ran then.
Prints one line "ACCURACY_TIMING_JSON {...}".
"""

import argparse
import json
import os
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "examples"))

import scenes  # noqa: E402
from accuracy_render import parse_value, render  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="accuracy_timing.py")
    ap.add_argument("--scene", required=True)
    ap.add_argument("--size", type=int, default=96)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--counts", default="4,32", help="the two sample counts n1,n2")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--out", required=True)
    ap.add_argument("--config", action="append", default=[], help="LABEL|ENGINE|key=value,... (repeatable)")
    return ap.parse_args(argv)


def main():
    a = parse_args()
    scene = scenes.build(a.scene, bpy.context.scene, size=a.size, threads=a.threads)
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    configs = []
    for text in a.config:
        label, engine, rest = text.split("|", 2)
        configs.append((label, engine, [(k, parse_value(v)) for k, v in (kv.split("=", 1) for kv in rest.split(",") if kv)]))
    baseline = {k: getattr(scene.candela, k) for _, _, pairs in configs for k, _ in pairs}
    counts = [int(c) for c in a.counts.split(",")]
    os.makedirs(a.out, exist_ok=True)
    path = os.path.join(a.out, "timing.exr")
    for label, engine, _ in configs:   # warm-up: the first render of an engine loads its kernels
        scene.render.engine = engine
        render(scene, engine, 1, path)
    runs = []
    for rep in range(a.repeats):
        for label, engine, pairs in configs:
            scene.render.engine = engine
            for key, value in baseline.items():
                setattr(scene.candela, key, value)
            for key, value in pairs:
                setattr(scene.candela, key, value)
            for n in counts:
                wall, cpu, _ = render(scene, engine, n, path)
                runs.append({"configuration": label, "repeat": rep, "samples": n, "cpu_seconds": cpu,
                             "wall_seconds": wall})
    print("ACCURACY_TIMING_JSON " + json.dumps({"scene": a.scene, "runs": runs}), flush=True)


if __name__ == "__main__":
    main()
