"""`make demo`: render the example Cornell box with Candela to out/cornell_box.exr and out/cornell_box.png.

    bin/candela-blender -b --factory-startup --python-exit-code 1 --python examples/demo.py -- \
        --out out [--blend build/examples/cornell_box.blend] [--size 512] [--samples 64] [--engine CANDELA]

With --blend the file is opened (and created first with examples/cornell_box.py's builder if it does not exist);
without it the scene is built afresh and saved to --save-blend (default build/examples/cornell_box.blend).  The scene is rendered ONCE; the render result is then saved twice:
  OUT/cornell_box.exr  scene-linear OpenEXR, float, RGBA (no view transform)
  OUT/cornell_box.png  8-bit PNG through the scene's view transform (Standard in the example scene)
and a line `Candela: WxH, N spp, T s -> X samples/s` is printed (wall time of the render call, so it includes
scene export and BVH build; `make bench` measures the steady-state rate).
"""

import argparse
import os
import sys
import time

import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import cornell_box  # noqa: E402


def _args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="demo.py")
    ap.add_argument("--out", default="out", help="output directory (default: out)")
    ap.add_argument("--name", default="cornell_box", help="output file stem (default: cornell_box)")
    ap.add_argument("--blend", default=None, help=".blend to render (created if missing); default: build the scene "
                                                   "afresh and save it to --save-blend")
    ap.add_argument("--save-blend", default=os.path.join(os.path.dirname(HERE), "build", "examples",
                                                         "cornell_box.blend"),
                    help="where the freshly built scene is saved when --blend is not given "
                         "(default: build/examples/cornell_box.blend; '' = do not save)")
    ap.add_argument("--size", type=int, default=0, help="square resolution (default: the scene's, 512)")
    ap.add_argument("--samples", type=int, default=0, help="samples per pixel (default: the scene's, 64)")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0 = all cores)")
    ap.add_argument("--engine", default="CANDELA", help="render engine (default CANDELA)")
    return ap.parse_args(argv)


def main():
    a = _args()
    engine = a.engine.upper()
    if not cornell_box.engine_available(engine):
        raise SystemExit(f"demo: render engine {engine} is not available "
                         f"(run through bin/candela-blender after 'make build')")

    if a.blend:
        blend = os.path.abspath(a.blend)
        if not os.path.exists(blend):
            cornell_box.build_cornell_box(engine=engine)
            os.makedirs(os.path.dirname(blend), exist_ok=True)
            bpy.ops.wm.save_as_mainfile(filepath=blend, check_existing=False)
            print(f"demo: created {blend}")
        bpy.ops.wm.open_mainfile(filepath=blend)
        scene = bpy.context.scene
    else:
        scene = cornell_box.build_cornell_box(engine=engine)
        if a.save_blend:
            blend = os.path.abspath(a.save_blend)
            os.makedirs(os.path.dirname(blend), exist_ok=True)
            bpy.ops.wm.save_as_mainfile(filepath=blend, check_existing=False)
            print(f"demo: saved the scene to {blend}")
            scene = bpy.context.scene

    scene.render.engine = engine
    if a.size:
        cornell_box.configure_render(scene, size=a.size, threads=a.threads)
    elif a.threads:
        scene.render.threads_mode = "FIXED"
        scene.render.threads = a.threads
    if a.samples:
        cornell_box.configure_cycles(scene, samples=a.samples, threads=a.threads or None)
        cornell_box.configure_candela(scene, samples=a.samples, threads=a.threads or None)
    if engine == "CANDELA":
        samples = scene.candela.samples
    elif engine == "CYCLES":
        samples = scene.cycles.samples
    else:
        samples = None

    r = scene.render
    w = r.resolution_x * r.resolution_percentage // 100
    h = r.resolution_y * r.resolution_percentage // 100

    t0 = time.perf_counter()
    res = bpy.ops.render.render()
    seconds = time.perf_counter() - t0
    if "FINISHED" not in res:
        raise SystemExit(f"demo: render failed ({res})")
    result = bpy.data.images.get("Render Result")
    if result is None:
        raise SystemExit("demo: no Render Result")

    out = os.path.abspath(a.out)
    os.makedirs(out, exist_ok=True)
    isettings = r.image_settings

    exr = os.path.join(out, a.name + ".exr")
    isettings.file_format = "OPEN_EXR"
    isettings.color_mode = "RGBA"
    isettings.color_depth = "32"
    isettings.exr_codec = "ZIP"
    result.save_render(exr, scene=scene)

    png = os.path.join(out, a.name + ".png")
    isettings.file_format = "PNG"
    isettings.color_mode = "RGBA"
    isettings.color_depth = "8"
    isettings.compression = 15
    result.save_render(png, scene=scene)

    label = {"CANDELA": "Candela", "CYCLES": "Cycles"}.get(engine, engine)
    print(f"demo: wrote {exr} (scene-linear) and {png} (view transform {scene.view_settings.view_transform})")
    if samples:
        sps = w * h * samples / seconds
        print(f"{label}: {w}x{h}, {samples} spp, {seconds:.2f} s -> {sps / 1e6:.3f} M samples/s "
              f"({sps:.0f} samples/s, render call wall time incl. setup)")
    else:
        print(f"{label}: {w}x{h}, {seconds:.2f} s")
    render_loop = sys.modules.get("candela.render_loop")
    stats = dict(getattr(render_loop, "last_render_stats", {}) or {}) if engine == "CANDELA" else {}
    if stats:
        shown = {k: v for k, v in stats.items() if isinstance(v, (int, float, str))}
        print(f"{label} native stats: {shown}")
        if stats.get("samples_per_second"):
            print(f"{label}: {float(stats['samples_per_second']):.0f} samples/s (native render time)")


if __name__ == "__main__":
    main()
