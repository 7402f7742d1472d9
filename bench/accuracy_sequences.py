"""Blender side of `make accuracy`: every configuration of one scene at every sample count, in ONE Blender
process, round-robin — for each count, each configuration in turn — so that a load coming and going on this
shared machine hits all configurations alike instead of whichever happened to run then.

    bin/candela-blender -b --factory-startup --python-exit-code 1 --python bench/accuracy_sequences.py -- \
        --scene cornell_box --size 96 --threads 2 --counts 1,2,4,8 --out DIR \
        --config "Cycles|CYCLES|" --config "Candela PATH SOBOL|CANDELA|integrator=PATH,sampler=SOBOL"

Each render writes DIR/SCENE_LABEL_N.exr and records its process CPU time (all threads) and wall time; with
--repeats R every render is repeated R times (same seed, same image) and bench/accuracy.py keeps the least CPU
time. Before the sequences, one warm-up render per configuration (an engine's first render loads kernels).
Prints one line "ACCURACY_SEQUENCES_JSON {...}".
"""

import argparse
import json
import os
import re
import sys

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "examples"))

import scenes  # noqa: E402
from accuracy_render import parse_value, render  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="accuracy_sequences.py")
    ap.add_argument("--scene", required=True)
    ap.add_argument("--size", type=int, default=96)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--counts", required=True, help="comma-separated sample counts")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--out", required=True)
    ap.add_argument("--config", action="append", default=[], help="LABEL|ENGINE|key=value,... (repeatable)")
    return ap.parse_args(argv)


def auto_decision(engine):
    """AUTO's choice and analysis time from the last render's status and log (empty for other integrators):
    {"method": "Auto: BDPT — …", "choice": "BDPT", "analysis_ms": 12.3}."""
    if engine != "CANDELA":
        return {}
    stats = sys.modules["candela.render_loop"].last_render_stats
    method = stats.get("method") or ""
    if not method.startswith("Auto: "):
        return {}
    out = {"method": method, "choice": method[len("Auto: "):].split(" ", 1)[0]}
    for line in stats.get("info", []):
        m = re.search(r"; analysis ([0-9.]+) ms", line)
        if line.startswith("Auto: chose ") and m:
            out["analysis_ms"] = float(m.group(1))
    return out


def main():
    a = parse_args()
    scene = scenes.build(a.scene, bpy.context.scene, size=a.size, threads=a.threads)
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    configs = []
    for text in a.config:
        label, engine, rest = text.split("|", 2)
        pairs = [(k, parse_value(v)) for k, v in (kv.split("=", 1) for kv in rest.split(",") if kv)]
        configs.append((label, engine, pairs))
    baseline = {k: getattr(scene.candela, k) for _, _, pairs in configs for k, _ in pairs}

    def select(engine, pairs):
        scene.render.engine = engine
        for key, value in baseline.items():
            setattr(scene.candela, key, value)
        for key, value in pairs:
            setattr(scene.candela, key, value)

    os.makedirs(a.out, exist_ok=True)
    for label, engine, pairs in configs:
        select(engine, pairs)
        render(scene, engine, 1, os.path.join(a.out, f"{a.scene}_warm.exr"))
    runs = []
    for n in [int(c) for c in a.counts.split(",")]:
        for rep in range(a.repeats):
            for label, engine, pairs in configs:
                select(engine, pairs)
                path = os.path.join(a.out, f"{a.scene}_{label.replace(' ', '_')}_{n}.exr")
                wall, cpu, _ = render(scene, engine, n, path)
                runs.append({"configuration": label, "repeat": rep, "samples": n, "cpu_seconds": cpu,
                             "wall_seconds": wall, "exr": path, **auto_decision(engine)})
    print("ACCURACY_SEQUENCES_JSON " + json.dumps({"scene": a.scene, "runs": runs}), flush=True)


if __name__ == "__main__":
    main()
