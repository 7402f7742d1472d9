"""Blender-side helper of bench/bench.py: time renders of one .blend with one or more engines at several sample
counts.

    bin/candela-blender -b --factory-startup --python-exit-code 1 --python bench/render_timed.py -- \
        --blend X.blend --config NAME=ENGINE[:KEY=VALUE,...] [--config ...] --samples 64,320 --out DIR \
        [--threads N] [--repeats 2] [--dump DUMP_DIR] [--json RESULT.json]

A configuration is an engine (CYCLES, CANDELA, ...) under a name, with Candela settings (scene.candela.KEY) to
apply on top of the scene's own, e.g. `--config CANDELA_POWER=CANDELA:light_selection=POWER`.  For each repeat
and each sample count S the helper sets the engine's sample count, then times
`bpy.ops.render.render(write_still=True)` with time.perf_counter() (EXR, float, RGBA, written to
DIR/<name>_<S>.exr).  Setup costs (scene export, BVH build, kernel load, file write) are the same for every
sample count, so bench.py takes samples/s = W*H*(S2 - S1) / (t2 - t1) from the best time of each count.

With several configurations the run is *paired*: each repeat is a round in which every configuration renders
every sample count, in alternating order (A B C, then C B A, ...), all in this one process on one scene.
Configurations measured seconds apart see the same machine load, so the per-round ratio of their samples/s is far
steadier on a shared machine than a ratio of runs taken minutes apart; `rounds` lists each round's order, and each
run carries its round as `repeat` (bench.py takes each round's samples/s from its own S1/S2 pair).

It also reports the mean linear RGB of every EXR written (read back with bpy.data.images.load), the number of
rays Candela traced (the add-on keeps the last render's native stats in render_loop.last_render_stats), and, with
--dump, writes a scene dump with bpy.ops.candela.export_dump (tolerating its absence).

The result is printed as one line `RENDER_TIMED_JSON {...}` (and written to --json if given):
{"configs": {NAME: result, ...}, "rounds": [...], "samples": [...], "width": W, "height": H}.
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
    ap.add_argument("--scene", default=None,
                    help="build this scene of examples/scenes.py in memory instead (--size: its width)")
    ap.add_argument("--config", action="append", required=True, metavar="NAME=ENGINE[:KEY=VALUE,...]",
                    help="a configuration to time; repeatable (several configurations alternate round by round)")
    ap.add_argument("--samples", required=True, help="comma-separated sample counts, e.g. 64,320")
    ap.add_argument("--out", required=True, help="directory for the EXRs")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0 = all cores)")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--size", type=int, default=0, help="override the square resolution (0 = keep)")
    ap.add_argument("--dump", default=None, help="write a Candela scene dump here first (candela.export_dump)")
    ap.add_argument("--json", default=None, help="also write the result to this file")
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


def parse_config(spec):
    """NAME=ENGINE[:KEY=VALUE,...] -> {"name", "engine", "candela": {KEY: VALUE}}."""
    name, sep, rest = spec.partition("=")
    if not sep or not name or not rest:
        raise SystemExit(f"render_timed: --config {spec!r}: expected NAME=ENGINE[:KEY=VALUE,...]")
    engine, _, settings = rest.partition(":")
    candela = {}
    for item in filter(None, settings.split(",")):
        key, sep, value = item.partition("=")
        if not sep:
            raise SystemExit(f"render_timed: --config {spec!r}: setting {item!r} is not KEY=VALUE")
        candela[key] = value
    if candela and engine.upper() != "CANDELA":
        raise SystemExit(f"render_timed: --config {spec!r}: settings are only for CANDELA")
    return {"name": name.upper(), "engine": engine.upper(), "candela": candela}


def select_engine(scene, engine):
    try:
        scene.render.engine = engine
    except TypeError:
        raise SystemExit(f"render_timed: engine {engine} is not available (add-on not enabled?)")
    if scene.render.engine != engine:
        raise SystemExit(f"render_timed: could not select engine {engine}")


def candela_settings(scene):
    """scene.candela's plain settings, {identifier: value}."""
    props = getattr(scene, "candela", None)
    settings = {}
    if props is not None:
        for prop in props.bl_rna.properties:
            if prop.identifier == "rna_type" or prop.type in ("POINTER", "COLLECTION"):
                continue
            val = getattr(props, prop.identifier, None)
            if isinstance(val, (int, float, str, bool)):
                settings[prop.identifier] = val
    return settings


def apply_config(scene, config, baseline):
    """Selects the configuration's engine; for Candela restores the scene's own settings (`baseline`) and applies
    the configuration's on top, so one configuration's settings never leak into the next."""
    select_engine(scene, config["engine"])
    if config["engine"] != "CANDELA":
        return
    props = scene.candela
    for key, value in baseline.items():
        if getattr(props, key) != value:
            setattr(props, key, value)
    for key, value in config["candela"].items():
        current = getattr(props, key)  # AttributeError names an unknown setting
        setattr(props, key, value in ("1", "True", "true") if isinstance(current, bool) else type(current)(value))


def engine_settings(scene, engine):
    """The settings the engine renders with (Candela's after apply_config)."""
    if engine == "CYCLES":
        c = scene.cycles
        return {k: getattr(c, k) for k in (
            "device", "use_denoising", "use_adaptive_sampling", "sample_clamp_direct", "sample_clamp_indirect",
            "pixel_filter_type", "filter_width", "max_bounces", "diffuse_bounces", "glossy_bounces",
            "transmission_bounces", "min_light_bounces", "seed")}
    if engine == "CANDELA":
        return candela_settings(scene)
    return {}


def summarise(result, counts):
    """Best (least) wall and CPU time per sample count, and the mean RGB of each count's best image."""
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


def main():
    a = _args()
    configs = [parse_config(c) for c in a.config]
    names = [c["name"] for c in configs]
    if len(set(names)) != len(names):
        raise SystemExit(f"render_timed: configuration names repeat: {names}")
    counts = [int(s) for s in a.samples.split(",") if s.strip()]
    os.makedirs(a.out, exist_ok=True)

    if a.blend:
        bpy.ops.wm.open_mainfile(filepath=os.path.abspath(a.blend))
        scene = bpy.context.scene
    elif a.scene:
        import scenes
        scene = scenes.build(a.scene, bpy.context.scene, size=a.size or 128, samples=counts[0], threads=a.threads)
        a.size = 0   # keep the scene's own aspect (configure_render below would make it square)
    else:
        import cornell_box
        scene = cornell_box.build_cornell_box(size=a.size or 256)

    for config in configs:
        select_engine(scene, config["engine"])

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
    width = r.resolution_x * r.resolution_percentage // 100
    height = r.resolution_y * r.resolution_percentage // 100
    baseline = candela_settings(scene)

    results = {}
    for config in configs:
        apply_config(scene, config, baseline)
        results[config["name"]] = {
            "engine": config["engine"],
            "blend": a.blend,
            "width": width,
            "height": height,
            "threads": r.threads,             # what Blender resolves (FIXED: the value set; AUTO: all cores)
            "threads_mode": r.threads_mode,
            "blender": bpy.app.version_string,
            "samples": counts,
            "settings": engine_settings(scene, config["engine"]),
            "runs": [],
        }
    if a.dump:
        dump_config = next((c for c in configs if c["engine"] == "CANDELA"), configs[0])
        apply_config(scene, dump_config, baseline)
        results[dump_config["name"]]["dump"] = write_dump(os.path.abspath(a.dump))

    # One untimed 1-sample render per configuration first: one-time costs of a process's first render with an
    # engine (module import, kernel load, thread pools) would otherwise land in round 0's S1 time only.
    for config in configs:
        apply_config(scene, config, baseline)
        warmup = os.path.join(os.path.abspath(a.out), f"warmup_{config['name'].lower()}.exr")
        render_once(scene, config["engine"], 1, warmup)
        os.remove(warmup)

    rounds = []
    for rep in range(max(1, a.repeats)):
        # Alternate the order round by round (A B C, C B A, ...) so no configuration always runs first.
        order = configs if rep % 2 == 0 else configs[::-1]
        rounds.append({"round": rep, "order": [c["name"] for c in order]})
        for config in order:
            name = config["name"]
            apply_config(scene, config, baseline)
            for s in counts:
                path = os.path.join(os.path.abspath(a.out), f"{name.lower()}_{s}.exr")
                entry = render_once(scene, config["engine"], s, path)
                entry["repeat"] = rep
                entry["exr"] = path
                results[name]["runs"].append(entry)
                print(f"render_timed: round {rep} {name} {s} spp: {entry['seconds']:.3f} s", flush=True)

    for name in names:
        summarise(results[name], counts)

    out = {"configs": results, "rounds": rounds, "samples": counts, "width": width, "height": height}
    line = json.dumps(out)
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
