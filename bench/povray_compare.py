"""`make povray-compare`: Candela's irradiance cache beside POV-Ray 3.7's radiosity (also an irradiance cache) on the
Cornell box: the CPU time each needs to reach 2 % relative RMSE against its own converged image.

    /usr/bin/python3.11 bench/povray_compare.py [--build build] [--docs docs] [--size 96] [--threads 2] [--quick]

POV-Ray renders the box written in its scene language (bench/povray/cornell_box.pov.in: the official geometry of
examples/cornell_box.py, Lambertian materials of the same reflectances, the light an area light with physical
inverse-square falloff and a visible emitting quad). Its lights do not follow the same units as Candela's, so
brightness is not compared: each renderer's error is against its own converged image — POV-Ray's the step after
the top of the ladder below (`reference`), Candela's the converged PATH reference of `make accuracy` (two
independent halves, whose own noise is subtracted; the irradiance cache's bias is in its error). POV-Ray's error is therefore its distance to its own limit, not to the truth: that favours it.

POV-Ray quality ladder (each step doubles the radiosity gather rays, tightens error_bound, pretrace_end and the
adaptive anti-aliasing threshold by √2, and grows nearest_count and the area light's samples; the reference is the
next step): its times and errors give the time to 2 % by log-log interpolation between the two steps around it. Candela: the irradiance cache at its defaults at 1, 2, 4 … samples per
pixel, with PATH (Sobol) for the set-up estimate and as a baseline, rendered round-robin in one Blender process
(bench/accuracy_sequences.py). All CPU times (both render threads summed); POV-Ray's whole process, Candela's
render less the export and BVH set-up (bench/accuracy.py's rule).

Writes DOCS/povray.md and DOCS/povray/cornell_box.png (both converged images and the error-vs-time curves).
--steps N shortens POV-Ray's ladder to steps 0 … N−1 with step N as its reference (the default, 6, takes about 25
minutes in all). --quick checks the pipeline at 32 px with short ladders into BUILD/povray-quick.
"""

import argparse
import ast
import datetime
import math
import os
import resource
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
import accuracy  # noqa: E402  (reference, sequences, native_module, machine: the same machinery as make accuracy)
import accuracy_stats as stats  # noqa: E402

TARGET = 0.02
# (count, error_bound, nearest_count, pretrace_end, antialias threshold, area light samples per side)
def pov_step(k):
    return (50 * 2 ** k, 1.0 / 2 ** (k / 2), min(5 + 2 * k, 20), 0.02 / 2 ** (k / 2), 0.3 / 2 ** (k / 2), 4 + 2 * k)


# Each step costs 3–5× the one before (96 px, 2 threads: 0.4, 1.2, 6, 25, 72 s for steps 0–4); the reference is the
# step after the last (about 10 minutes).
POV_LADDER = [pov_step(k) for k in range(6)]
POV_REFERENCE = pov_step(6)


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--docs", default=str(ROOT / "docs"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--size", type=int, default=96)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--max-samples", type=int, default=1024)
    ap.add_argument("--steps", type=int, default=len(POV_LADDER),
                    help="POV-Ray ladder steps 0 … steps−1, the reference being step `steps` (default 6: about 10 "
                         "minutes for the reference alone at 96 px on an idle machine)")
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    if a.quick:
        a.size, a.max_samples = 32, 4
    a.out = Path(a.out or Path(a.build) / ("povray-quick" if a.quick else "povray"))
    return a


def cornell_geometry():
    """SURFACES of examples/cornell_box.py (official mm coordinates, y up), read without Blender."""
    src = (ROOT / "examples" / "cornell_box.py").read_text()
    tree = ast.parse(src)
    env = {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Name):
            name = node.targets[0].id
            if name in ("RED", "GREEN", "WHITE", "LIGHT_RADIANCE", "CEILING_Y_MM", "LIGHT_DROP_MM", "SURFACES"):
                env[name] = eval(compile(ast.Expression(node.value), "cornell_box.py", "eval"), {}, dict(env))
    return env


def povray_scene(quality):
    """The Cornell box in POV-Ray's scene language at one quality step."""
    count, error_bound, nearest, pretrace_end, _, light_n = quality
    g = cornell_geometry()
    colours = {"White": g["WHITE"], "Red": g["RED"], "Green": g["GREEN"]}
    lines = ["#version 3.7;",
             "global_settings { assumed_gamma 1.0 max_trace_level 10",
             f"  radiosity {{ pretrace_start 0.08 pretrace_end {pretrace_end:.5f} count {count} "
             f"error_bound {error_bound:.4f} nearest_count {nearest} recursion_limit 4 low_error_factor 0.5 "
             "minimum_reuse 0.005 brightness 1 } }",
             # The official camera (looking +z from z = −800): POV-Ray is left-handed, `right -x` mirrors it back.
             "camera { perspective location <278, 273, -800> look_at <278, 273, 0> right -x up y angle 39.3076 }"]
    for name, rgb in colours.items():
        lines.append(f"#declare {name} = texture {{ pigment {{ rgb <{rgb[0]}, {rgb[1]}, {rgb[2]}> }} "
                     "finish { ambient 0 emission 0 diffuse 1 } }")
    for surface, (material, quads) in g["SURFACES"].items():
        if material == "Light":
            continue
        for q in quads:
            a, b, c, d = (f"<{p[0]}, {p[1]}, {p[2]}>" for p in q)
            lines.append(f"triangle {{ {a}, {b}, {c} texture {{ {material} }} }}")
            lines.append(f"triangle {{ {a}, {c}, {d} texture {{ {material} }} }}")
    y = g["CEILING_Y_MM"] - g["LIGHT_DROP_MM"]
    le = g["LIGHT_RADIANCE"]
    lines.append(
        f"light_source {{ <278, {y}, 279.5> color rgb <{le[0]}, {le[1]}, {le[2]}> * 0.25 "
        f"area_light <130, 0, 0>, <0, 0, 105>, {light_n}, {light_n} adaptive 1 circular orient "
        "fade_distance 200 fade_power 2 "
        "looks_like { box { <-65, -0.1, -52.5>, <65, 0.1, 52.5> "
        f"texture {{ pigment {{ rgb <{le[0]}, {le[1]}, {le[2]}> }} finish {{ ambient 0 diffuse 0 emission 1 }} }} "
        "no_shadow no_radiosity } } }")
    return "\n".join(lines) + "\n"


def render_povray(quality, path, size, threads):
    """Renders one step; returns its CPU seconds (the POV-Ray process, all threads)."""
    path = path.resolve()
    pov = path.with_suffix(".pov")
    pov.write_text(povray_scene(quality))
    aa = quality[4]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run(["povray", f"+I{pov}", f"+O{path}", "+FE", f"+W{size}", f"+H{size}", f"+WT{threads}", "-D",
                           f"+A{aa:.4f}", "+R4", "Display_Gamma=1.0", "File_Gamma=1.0"],
                          capture_output=True, text=True, cwd=path.parent)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode != 0 or not path.exists():
        raise RuntimeError(f"povray failed ({proc.returncode}):\n{proc.stderr[-2000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def relative_rmse(image, reference):
    return math.sqrt(float(np.mean((image - reference) ** 2))) / float(np.mean(reference))


def time_to(target, times, errors):
    """Log-log interpolation of the time at which the error first falls to `target` (None if it never does)."""
    for (t0, e0), (t1, e1) in zip(zip(times, errors), zip(times[1:], errors[1:])):
        if e0 > target >= e1:
            f = math.log(e0 / target) / math.log(e0 / e1)
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    if errors and errors[0] <= target:
        return times[0]
    return None


def main():
    a = parse_args()
    if shutil.which("povray") is None:
        raise SystemExit("povray is not installed (Debian's `povray`: make deps)")
    accuracy.ARGS = argparse.Namespace(build=a.build, out=a.out, size=a.size, threads=a.threads, repeats=1,
                                       max_samples=a.max_samples, ref_factor=8, reference_integrator={},
                                       reuse=False, rerun=[])
    native = accuracy.native_module()
    a.out.mkdir(parents=True, exist_ok=True)
    started = time.time()
    steps = 2 if a.quick else a.steps
    ladder = [pov_step(k) for k in range(steps)]
    ref_quality = pov_step(steps)

    # POV-Ray: the reference once, then the ladder.
    ref_path = a.out / f"povray_reference_{a.size}.exr"
    ref_cpu = render_povray(ref_quality, ref_path, a.size, a.threads)
    pov_ref = stats.luminance(native.read_exr(str(ref_path)))
    pov = []
    for k, q in enumerate(ladder):
        path = a.out / f"povray_{a.size}_{k}.exr"
        cpu = render_povray(q, path, a.size, a.threads)
        err = relative_rmse(stats.luminance(native.read_exr(str(path))), pov_ref)
        pov.append({"step": k, "quality": q, "cpu": cpu, "rrmse": err})
        print(f"povray step {k} count {q[0]} error_bound {q[1]:.3f}: {cpu:.2f} s CPU, rel. RMSE {err:.4f}", flush=True)

    # Candela: the irradiance cache and PATH, round-robin in one Blender process, against PATH's reference.
    counts = [2 ** k for k in range(int(math.log2(a.max_samples)) + 1)]
    configs = [("Candela PATH SOBOL", "CANDELA", ["integrator=PATH", "sampler=SOBOL"]),
               ("Candela IRRADIANCE_CACHE", "CANDELA", ["integrator=IRRADIANCE_CACHE"])]
    ref = accuracy.reference("cornell_box", "CANDELA", 2048 if not a.quick else 32)
    runs = accuracy.sequences("cornell_box", configs, counts)
    rows = []
    path_p = accuracy.measure("cornell_box", configs[0][0], runs[configs[0][0]], ref, rows)
    ic_p = accuracy.measure("cornell_box", configs[1][0], runs[configs[1][0]], ref, rows, path_p["setup"])

    t_pov = time_to(TARGET, [p["cpu"] for p in pov], [p["rrmse"] for p in pov])
    t_ic = time_to(TARGET, ic_p["time"], ic_p["rrmse"])
    t_path = time_to(TARGET, path_p["time"], path_p["rrmse"])
    write_docs(a, pov, ref_cpu, ref_quality, ic_p, path_p, t_pov, t_ic, t_path, native, ref_path,
               runs[configs[1][0]][-1]["exr"], started)


def write_docs(a, pov, ref_cpu, ref_quality, ic_p, path_p, t_pov, t_ic, t_path, native, ref_path, ic_exr, started):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    docs = a.out if a.quick else Path(a.docs)
    pics = docs / "povray"
    pics.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.4))
    pov_img = native.read_exr(str(ref_path))[::-1, :, :3]
    axes[0].imshow(np.clip(pov_img / max(float(np.percentile(pov_img, 99)), 1e-6), 0, 1) ** (1 / 2.2))
    axes[0].set_title("POV-Ray 3.7 radiosity, its reference (exposure normalised)")
    ic_img = native.read_exr(ic_exr)[::-1, :, :3]
    axes[1].imshow(np.clip(ic_img, 0, 1) ** (1 / 2.2))
    axes[1].set_title(f"Candela IRRADIANCE_CACHE, {ic_p['samples'][-1]} samples per pixel")
    for ax in axes[:2]:
        ax.set_axis_off()
    axes[2].loglog([p["cpu"] for p in pov], [p["rrmse"] for p in pov], "o-", ms=3, label="POV-Ray radiosity")
    axes[2].loglog(ic_p["time"], ic_p["rrmse"], "o-", ms=3, label="Candela IRRADIANCE_CACHE")
    axes[2].loglog(path_p["time"], path_p["rrmse"], "o-", ms=3, label="Candela PATH (Sobol)")
    axes[2].axhline(TARGET, color="grey", lw=0.8, ls=":")
    axes[2].set_xlabel("CPU time [s]")
    axes[2].set_ylabel("relative RMSE against its own converged image")
    axes[2].grid(True, which="both", alpha=0.3)
    axes[2].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(pics / "cornell_box.png", dpi=100)
    plt.close(fig)
    when = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    md = ["# Candela's irradiance cache beside POV-Ray's radiosity", "",
          "Generated by `make povray-compare` (`bench/povray_compare.py`); do not edit by hand.", "",
          f"Measured on {accuracy.machine()}, {a.threads} render threads, {when}, in one run. Cornell box at "
          f"{a.size} × {a.size} px. The method is in the script's docstring: each renderer against its own converged "
          "image (POV-Ray: its own highest quality, so its error is its distance to its own limit, biases "
          "included in that limit; Candela: PATH's converged reference, so the irradiance cache's bias counts), "
          "CPU time of both threads, Candela's export/BVH set-up excluded, POV-Ray's whole process included "
          "(its parse and bounding take well under 1 % here).", "",
          "![Cornell box](povray/cornell_box.png)", "",
          f"| renderer | time to {100 * TARGET:g} % | ratio to POV-Ray |", "|---|---|---|",
          f"| POV-Ray 3.7 radiosity | {fmt(t_pov)} | 1.00× |",
          f"| Candela IRRADIANCE_CACHE (defaults) | {fmt(t_ic)} | {ratio(t_ic, t_pov)} |",
          f"| Candela PATH (Sobol) | {fmt(t_path)} | {ratio(t_path, t_pov)} |", "",
          "POV-Ray's ladder (radiosity count, error_bound, nearest_count, pretrace_end, anti-aliasing threshold, "
          "area-light samples per side):", "",
          "| step | settings | CPU s | rel. RMSE |", "|---|---|---|---|"]
    for p in pov:
        md.append(f"| {p['step']} | {', '.join(f'{v:g}' for v in p['quality'])} | {p['cpu']:.3g} | {p['rrmse']:.4f} |")
    md.append(f"| reference (step {len(pov)}) | {', '.join(f'{v:g}' for v in ref_quality)} | {ref_cpu:.3g} | — |")
    md += ["", "Candela (samples per pixel: CPU s, rel. RMSE against PATH's reference):", ""]
    for label, p in (("IRRADIANCE_CACHE", ic_p), ("PATH", path_p)):
        md.append(f"- {label}: " + ", ".join(f"{n}: {t:.3g} s {e:.4f}" for n, t, e in zip(p["samples"], p["time"],
                                                                                               p["rrmse"])))
    md += ["", f"The run took {time.time() - started:.0f} s.", ""]
    (docs / "povray.md").write_text("\n".join(md))
    print(f"povray-compare: time to 2 %: POV-Ray {fmt(t_pov)}, IRRADIANCE_CACHE {fmt(t_ic)}, PATH {fmt(t_path)}")


def fmt(t):
    return "not reached" if t is None else f"{t:.3g} s"


def ratio(t, base):
    return "—" if t is None or base is None else f"{t / base:.2f}×"


if __name__ == "__main__":
    main()
