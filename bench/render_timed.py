"""Blender-side helper of bench/bench.py: time renders of one .blend with one engine at several sample counts.

    bin/candela-blender -b --factory-startup --python-exit-code 1 --python bench/render_timed.py -- \
        --blend X.blend --engine CANDELA|CYCLES --samples 64,320 --out DIR \
        [--threads N] [--repeats 2] [--dump DUMP_DIR] [--json RESULT.json]

For each repeat and each sample count S the helper sets the engine's sample count, then times
`bpy.ops.render.render(write_still=True)` with time.perf_counter() (EXR, float, RGBA, written to
DIR/<engine>_<S>.exr).  Setup costs (scene export, BVH build, kernel load, file write) are the same for every
sample count, so bench.py takes samples/s = W*H*(S2 - S1) / (t2 - t1) from the best time of each count.

It also reports the mean linear RGB of every EXR written (read back with bpy.data.images.load), the number of
rays Candela traced (the add-on keeps the last render's native stats in render_loop.last_render_stats), and, with
--dump, writes a scene dump with bpy.ops.candela.export_dump (tolerating its absence).

The result is printed as one line `RENDER_TIMED_JSON {...}` (and written to --json if given).
"""

import argparse
import json
import os
import resource
import sys
import time
import traceback

import bpy

try:
    import numpy as np
except ImportError:                    # Blender normally sees the system numpy; fall back to pure Python
    np = None

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "examples"))


def _args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="render_timed.py")
    ap.add_argument("--blend", default=None, help=".blend to open (default: build the Cornell box in memory)")
    ap.add_argument("--engine", required=True)
    ap.add_argument("--samples", required=True, help="comma-separated sample counts, e.g. 64,320")
    ap.add_argument("--out", required=True, help="directory for the EXRs")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0 = all cores)")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--size", type=int, default=0, help="override the square resolution (0 = keep)")
    ap.add_argument("--dump", default=None, help="write a Candela scene dump here first (candela.export_dump)")
    ap.add_argument("--json", default=None, help="also write the result to this file")
    ap.add_argument("--candela-set", action="append", default=[], metavar="KEY=VALUE",
                    help="set a Candela render setting (scene.candela.KEY) before rendering; repeatable")
    ap.add_argument("--tag", default="", help="suffix for the EXR names (several runs of one engine)")
    return ap.parse_args(argv)


def image_mean_rgb(path):
    """Mean linear RGB of an image file, read with Blender (EXR stays linear)."""
    img = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = img.size
        c = img.channels
        n = w * h * c
        if np is not None:
            buf = np.empty(n, dtype=np.float32)
            img.pixels.foreach_get(buf)
            px = buf.reshape(-1, c).astype(np.float64)
            rgb = px[:, :3].mean(axis=0)
            finite = bool(np.isfinite(px).all())
            return {"mean_rgb": [float(v) for v in rgb], "mean": float(rgb.mean()), "width": w, "height": h,
                    "finite": finite}
        px = list(img.pixels)
        sums = [sum(px[i::c]) / (w * h) for i in range(3)]
        return {"mean_rgb": sums, "mean": sum(sums) / 3.0, "width": w, "height": h, "finite": True}
    finally:
        bpy.data.images.remove(img)


def set_samples(scene, engine, samples):
    if engine == "CYCLES":
        scene.cycles.samples = samples
    elif engine == "CANDELA":
        scene.candela.samples = samples
    elif engine.startswith("BLENDER_EEVEE"):
        scene.eevee.taa_render_samples = samples
    else:
        raise ValueError(f"don't know how to set the sample count of engine {engine}")


def addon_stats():
    """The native stats of the last Candela render, as the add-on keeps them (render_loop.last_render_stats)."""
    mod = sys.modules.get("candela.render_loop")
    stats = getattr(mod, "last_render_stats", None) if mod is not None else None
    return dict(stats) if stats else None


def _cpu_seconds():
    """User + system CPU time of this process, all threads (render threads included). On a virtual machine it
    leaves out the time the host gives to other guests, which wall time does not."""
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def render_once(scene, engine, samples, path):
    set_samples(scene, engine, samples)
    scene.render.filepath = path
    if os.path.exists(path):
        os.remove(path)
    c0 = _cpu_seconds()
    t0 = time.perf_counter()
    res = bpy.ops.render.render(write_still=True)
    t1 = time.perf_counter()
    c1 = _cpu_seconds()
    if "FINISHED" not in res:
        raise RuntimeError(f"render.render returned {res}")
    if not os.path.exists(path):
        raise RuntimeError(f"render produced no file {path}")
    entry = {"samples": samples, "seconds": t1 - t0, "cpu_seconds": c1 - c0}
    stats = addon_stats() if engine == "CANDELA" else None
    if stats:
        entry["native_stats"] = {k: v for k, v in stats.items() if isinstance(v, (int, float, str))}
        if "rays" in stats:
            entry["rays"] = float(stats["rays"])
        if "render_seconds" in stats:
            entry["native_render_seconds"] = float(stats["render_seconds"])
    return entry


def write_dump(directory):
    op = getattr(getattr(bpy.ops, "candela", None), "export_dump", None)
    if op is None:
        return {"ok": False, "error": "bpy.ops.candela.export_dump not available"}
    try:
        os.makedirs(directory, exist_ok=True)
        res = bpy.ops.candela.export_dump(directory=directory)
        ok = "FINISHED" in res and os.path.exists(os.path.join(directory, "params.json"))
        return {"ok": ok, "result": sorted(res), "directory": directory}
    except Exception as exc:                 # tolerate a missing/unfinished operator
        return {"ok": False, "error": f"{type(exc).__name__}: {exc}"}


def main():
    a = _args()
    engine = a.engine.upper()
    counts = [int(s) for s in a.samples.split(",") if s.strip()]
    os.makedirs(a.out, exist_ok=True)

    if a.blend:
        bpy.ops.wm.open_mainfile(filepath=os.path.abspath(a.blend))
        scene = bpy.context.scene
    else:
        import cornell_box
        scene = cornell_box.build_cornell_box(size=a.size or 256)

    try:
        scene.render.engine = engine
    except TypeError:
        raise SystemExit(f"render_timed: engine {engine} is not available (add-on not enabled?)")
    if scene.render.engine != engine:
        raise SystemExit(f"render_timed: could not select engine {engine}")

    # Same conditions for every engine (the .blend from cornell_box.py already has them; enforce anyway).
    try:
        import cornell_box
        if a.size:
            cornell_box.configure_render(scene, size=a.size, threads=a.threads)
        cornell_box.configure_cycles(scene, samples=counts[0], threads=a.threads)
        cornell_box.configure_candela(scene, samples=counts[0], threads=a.threads)
    except ImportError:
        pass
    r = scene.render
    if a.threads > 0:
        r.threads_mode = "FIXED"
        r.threads = a.threads
    else:
        r.threads_mode = "AUTO"
    r.use_border = False
    r.resolution_percentage = 100
    r.use_file_extension = False
    r.use_overwrite = True
    isettings = r.image_settings
    isettings.file_format = "OPEN_EXR"
    isettings.color_mode = "RGBA"
    isettings.color_depth = "32"
    isettings.exr_codec = "ZIP"

    result = {
        "engine": engine,
        "blend": a.blend,
        "width": r.resolution_x * r.resolution_percentage // 100,
        "height": r.resolution_y * r.resolution_percentage // 100,
        "threads": r.threads,                 # what Blender resolves (FIXED: the value set; AUTO: all cores)
        "threads_mode": r.threads_mode,
        "blender": bpy.app.version_string,
        "samples": counts,
        "runs": [],
    }
    if engine == "CYCLES":
        c = scene.cycles
        result["settings"] = {k: getattr(c, k) for k in (
            "device", "use_denoising", "use_adaptive_sampling", "sample_clamp_direct", "sample_clamp_indirect",
            "pixel_filter_type", "filter_width", "max_bounces", "diffuse_bounces", "glossy_bounces",
            "transmission_bounces", "seed")}
    elif engine == "CANDELA":
        props = getattr(scene, "candela", None)
        for item in a.candela_set:
            key, _, value = item.partition("=")
            current = getattr(props, key)  # AttributeError names an unknown setting
            setattr(props, key, type(current)(value) if not isinstance(current, bool) else value in ("1", "True"))
        settings = {}
        if props is not None:
            for prop in props.bl_rna.properties:
                if prop.identifier == "rna_type" or prop.type in ("POINTER", "COLLECTION"):
                    continue
                val = getattr(props, prop.identifier, None)
                if isinstance(val, (int, float, str, bool)):
                    settings[prop.identifier] = val
        result["settings"] = settings

    if a.dump:
        result["dump"] = write_dump(os.path.abspath(a.dump))

    for rep in range(max(1, a.repeats)):
        for s in counts:
            path = os.path.join(os.path.abspath(a.out), f"{engine.lower()}{a.tag}_{s}.exr")
            entry = render_once(scene, engine, s, path)
            entry["repeat"] = rep
            entry["exr"] = path
            result["runs"].append(entry)
            print(f"render_timed: {engine} {s} spp: {entry['seconds']:.3f} s", flush=True)

    best = {}
    for e in result["runs"]:
        s = e["samples"]
        if s not in best or e["seconds"] < best[s]["seconds"]:
            best[s] = e
    result["best_seconds"] = {str(s): best[s]["seconds"] for s in counts}
    result["best_cpu_seconds"] = {str(s): min(e["cpu_seconds"] for e in result["runs"] if e["samples"] == s)
                                  for s in counts}
    result["images"] = {str(s): image_mean_rgb(best[s]["exr"]) for s in counts}
    rays = {str(s): best[s]["rays"] for s in counts if "rays" in best[s]}
    if rays:
        result["rays"] = rays

    line = json.dumps(result)
    if a.json:
        with open(a.json, "w") as f:
            f.write(line + "\n")
    print("RENDER_TIMED_JSON " + line, flush=True)


if __name__ == "__main__":
    try:
        main()
    except SystemExit:
        raise
    except Exception:
        traceback.print_exc()
        sys.exit(1)
