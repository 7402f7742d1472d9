"""`make bdpt-strategies`: the picture of docs/bdpt.md — which BDPT strategy carries which light.

    bin/candela-blender -b --factory-startup --python examples/bdpt_strategies_picture.py -- \
        [--scene caustic] [--size 128] [--samples 256] [--depth 2] [--out docs/bdpt]

Renders a scene of examples/scenes.py with BDPT and Strategy Images on (a one-pixel box filter, so the weighted
images add up to the render exactly) into a multilayer EXR through Blender, then lays the passes out in two grids
(rows: path depth d = 0, 1, 2, …, that is bounces; columns: s, the light subpath's vertices, with t = d + 2 − s):
`strategies_weighted.png` (w·C, what each strategy contributes; a row sums to that depth's light) and
`strategies_unweighted.png` (C alone, what the strategy would estimate by itself). All images share one exposure.
"""
import argparse
import os
import subprocess
import sys

import bpy
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import scenes  # noqa: E402


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser()
    p.add_argument("--scene", default="caustic")
    p.add_argument("--size", type=int, default=128)
    p.add_argument("--samples", type=int, default=256)
    p.add_argument("--depth", type=int, default=3)
    p.add_argument("--out", default=os.path.join(os.path.dirname(HERE), "docs", "bdpt"))
    return p.parse_args(argv)


def srgb(rgb):
    rgb = np.clip(rgb, 0.0, 1.0)
    return np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * np.power(rgb, 1 / 2.4) - 0.055)


def grid(images, depth, unweighted, path, title):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cols = depth + 2
    fig, axes = plt.subplots(depth + 1, cols, figsize=(2.0 * cols, 2.0 * (depth + 1) + 0.4), squeeze=False)
    for d in range(depth + 1):
        for s in range(cols):
            ax = axes[d][s]
            ax.set_xticks([])
            ax.set_yticks([])
            t = d + 2 - s
            name = f"BDPT d{d} s{s} t{t}" + (" unweighted" if unweighted else "")
            if s > d + 1 or name not in images:
                ax.axis("off")
                continue
            ax.imshow(srgb(images[name][::-1]), interpolation="nearest")
            ax.set_title(f"d={d}  s={s}  t={t}", fontsize=8)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    scene = scenes.build(args.scene, size=args.size, samples=args.samples)
    c = scene.candela
    c.integrator = 'BDPT'
    c.samples = args.samples
    c.bdpt_strategy_images = True
    c.bdpt_strategy_depth = args.depth
    c.max_bounces = max(int(c.max_bounces), args.depth)
    c.pixel_filter = 'BOX'
    c.filter_width = 1.0
    # Rendered from the saved file by a second Blender (`-b file -f 1`), as a farm would: the passes an engine
    # registers are set up when the file's view layers are loaded.
    blend = os.path.join(args.out, "strategies.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend, check_existing=False)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    cmd = [os.path.join(os.path.dirname(HERE), "bin", "candela-blender"), "-b", blend, "-E", "CANDELA",
           "-o", os.path.join(args.out, "strategies_#"), "-F", "OPEN_EXR_MULTILAYER", "-f", "1"]
    proc = subprocess.run(cmd, env=env, capture_output=True, text=True)
    os.remove(blend)
    if proc.returncode != 0:
        raise SystemExit(proc.stdout + proc.stderr)
    exr = os.path.join(args.out, "strategies_1.exr")
    from candela import native
    channels = native.require().read_exr_channels(exr)
    layer = bpy.context.view_layer.name
    images = {}
    for key in channels:
        if key.startswith(layer + ".BDPT ") and key.endswith(".R"):
            name = key[len(layer) + 1:-2]
            images[name] = np.stack([channels[f"{layer}.{name}.{ch}"] for ch in "RGB"], axis=-1)
    if not images:
        raise SystemExit(f"no strategy passes in {exr}: {sorted(channels)[:12]}")
    os.remove(exr)
    grid(images, args.depth, False, os.path.join(args.out, "strategies_weighted.png"),
         f"BDPT strategies, MIS-weighted ({args.scene}, {args.samples} spp): each row sums to that depth's light")
    grid(images, args.depth, True, os.path.join(args.out, "strategies_unweighted.png"),
         f"BDPT strategies, unweighted ({args.scene}, {args.samples} spp): each alone estimates its depth")
    print("BDPT_STRATEGIES", len(images), "images written to", args.out)


main()
