"""docs/irradiance_cache/*.png: where the irradiance cache puts its records (the "IC Records" pass).

    /usr/bin/python3.11 examples/ic_records_picture.py [--build build] [--docs docs] [--size 192] [--samples 64]

For the Cornell box and the room lit through a window (examples/scenes.py) it renders the Irradiance Cache
integrator at its default settings through Blender and the add-on, with the IC Records pass on (a multilayer EXR),
and draws the image beside the same image dimmed with a dot on every record (at the pixel whose path made it; a
pixel holding several gets a larger dot). Prints the record count and the render time of each.

The same file runs inside Blender (called by itself with --inside) to do the render.
"""

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCENES = ("cornell_box", "room_window")


def parse_args(argv):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--docs", default=str(ROOT / "docs"))
    ap.add_argument("--size", type=int, default=192)
    ap.add_argument("--samples", type=int, default=64)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--inside", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--scene", default=None, help=argparse.SUPPRESS)
    ap.add_argument("--exr", default=None, help=argparse.SUPPRESS)
    return ap.parse_args(argv)


def render_inside(a):
    """Inside Blender: render a.scene with the irradiance cache into the multilayer EXR a.exr."""
    import time
    import bpy
    sys.path.insert(0, str(ROOT / "examples"))
    import scenes
    scene = scenes.build(a.scene, bpy.context.scene, size=a.size, samples=a.samples, threads=a.threads)
    scene.render.engine = "CANDELA"
    scene.candela.integrator = "IRRADIANCE_CACHE"
    scene.candela.samples = a.samples
    bpy.context.view_layer.candela.use_pass_ic_records = True
    scene.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = a.exr
    t0 = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    stats = sys.modules["candela.render_loop"].last_render_stats
    print("IC_PICTURE_JSON " + json.dumps({"seconds": time.perf_counter() - t0,
                                           "render_seconds": stats.get("render_seconds"),
                                           "warnings": stats.get("warnings", [])}), flush=True)


def main(a):
    sys.path.insert(0, str(Path(a.build) / "scripts" / "addons" / "candela"))
    import _native
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(a.docs) / "irradiance_cache"
    out.mkdir(parents=True, exist_ok=True)
    work = Path(a.build) / "ic_records"
    work.mkdir(parents=True, exist_ok=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env["CANDELA_SCRIPTS_DIR"] = str(Path(a.build) / "scripts")
    for name in SCENES:
        exr = work / f"{name}.exr"
        cmd = [str(ROOT / "bin" / "candela-blender"), "-b", "--factory-startup", "-noaudio", "--python-exit-code", "1",
               "--python", str(Path(__file__).resolve()), "--", "--inside", "--scene", name, "--exr", str(exr),
               "--size", str(a.size), "--samples", str(a.samples), "--threads", str(a.threads)]
        proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
        if proc.returncode != 0:
            raise SystemExit(f"Blender failed on {name}:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}")
        info = next(json.loads(line.split(" ", 1)[1]) for line in proc.stdout.splitlines()
                    if line.startswith("IC_PICTURE_JSON "))
        channels = _native.read_exr_channels(str(exr))
        rgb_keys = [next(k for k in channels if k.endswith(f"Combined.{c}")) for c in "RGB"]
        rgb = np.stack([channels[k] for k in rgb_keys], axis=-1)[::-1]   # row 0 = bottom in the EXR reader
        records = channels[next(k for k in channels if "IC Records" in k)][::-1]
        shown = np.clip(rgb, 0.0, 1.0) ** (1 / 2.2)                        # a display encoding, for the picture only
        ys, xs = np.nonzero(records)
        fig, axes = plt.subplots(1, 2, figsize=(10, 5.4 * rgb.shape[0] / rgb.shape[1] + 0.6))
        axes[0].imshow(shown, interpolation="nearest")
        axes[0].set_title(f"Irradiance Cache, {a.samples} samples per pixel")
        axes[1].imshow(shown * 0.35, interpolation="nearest")
        axes[1].scatter(xs, ys, s=2.0 * records[ys, xs], c="#ff3020", marker="o", linewidths=0)
        axes[1].set_title(f"{int(records.sum())} records (IC Records pass)")
        for ax in axes:
            ax.set_axis_off()
        fig.tight_layout()
        fig.savefig(out / f"{name}_records.png", dpi=100)
        plt.close(fig)
        print(f"{name}: {int(records.sum())} records, render {info['render_seconds']:.1f} s "
              f"({a.size} px, {a.samples} samples per pixel, {a.threads} threads)")


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else sys.argv[1:]
    args = parse_args(argv)
    if args.inside:
        render_inside(args)
    else:
        main(args)
