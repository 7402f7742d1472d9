"""`make accuracy`: what accuracy costs in time, per scene, per technique, against Cycles.

    /usr/bin/python3.11 bench/accuracy.py [--quick] [--out DIR] [--docs docs] [--size 128] [--max-samples 256]

For every scene (examples/scenes.py) and every configuration — Cycles, and Candela with each integrator and
each sampler the native module offers — it renders at 1, 2, 4, … samples per pixel, measures the render time
(set-up excluded, see bench/accuracy_render.py) and the error against a high-sample reference of the SAME
engine (rendered once and cached in OUT/cache, keyed by scene, size, engine and the renderer's build), and
writes:
  DOCS/accuracy.md          a table per scene: time to reach 5 % / 2 % / 1 % relative error, the fitted
                            convergence slope, and the ratio to Cycles' time for the same error
  DOCS/accuracy/SCENE.png   log-log error-vs-time plots, one line per configuration, Cycles included
  DOCS/accuracy/measurements.csv   every measurement
Error: relative RMSE = √(mean over pixels of (L − L_ref)²) / mean(L_ref) on luminance, with the reference's own
estimated noise (a 16× longer render) subtracted; relative MSE = mean((L − L_ref)² / (L_ref² + 0.01)).
All times come from one run on one machine; the report says which and when. --quick (for `make test`) renders
small images at few samples into OUT only, to check the pipeline, not the numbers.
"""

import argparse
import csv
import datetime
import hashlib
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
TARGETS = (0.05, 0.02, 0.01)


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="pipeline check: tiny images, few samples, no docs")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--out", default=None, help="work directory (default BUILD/accuracy or BUILD/accuracy-quick)")
    ap.add_argument("--docs", default=str(ROOT / "docs"), help="where accuracy.md and the plots go")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--max-samples", type=int, default=256)
    ap.add_argument("--ref-factor", type=int, default=16, help="reference samples = factor × max samples")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--scenes", default=None, help="comma-separated subset of the scenes")
    a = ap.parse_args()
    if a.quick:
        a.size, a.max_samples, a.ref_factor = 32, 8, 8
        a.scenes = a.scenes or "cornell_box,soft_shadow"
    a.out = Path(a.out or Path(a.build) / ("accuracy-quick" if a.quick else "accuracy"))
    return a


def run_blender(args, log):
    cmd = [str(ROOT / "bin" / "candela-blender"), "-b", "--factory-startup", "-noaudio", "--python-exit-code", "1",
           "--python", str(ROOT / "bench" / "accuracy_render.py"), "--", *args]
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env["CANDELA_SCRIPTS_DIR"] = str(Path(ARGS.build) / "scripts")
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    log.write_text(proc.stdout + proc.stderr)
    if proc.returncode != 0:
        raise RuntimeError(f"Blender failed ({proc.returncode}); see {log}")
    for line in proc.stdout.splitlines():
        if line.startswith("ACCURACY_JSON "):
            return json.loads(line[len("ACCURACY_JSON "):])
    raise RuntimeError(f"no result from Blender; see {log}")


def native_module():
    sys.path.insert(0, str(Path(ARGS.build) / "scripts" / "addons" / "candela"))
    import _native
    return _native


def luminance(rgba):
    return 0.2126 * rgba[..., 0] + 0.7152 * rgba[..., 1] + 0.0722 * rgba[..., 2]


def configurations(native):
    """(label, engine, candela settings) for every configuration the build offers."""
    caps = native.capabilities()
    out = [("Cycles", "CYCLES", [])]
    for name, _ in caps["integrators"]:
        samplers = caps.get("samplers", ["RANDOM"]) if name == "PATH" else [None]
        for sampler in samplers:
            settings = [f"integrator={name}"] + ([f"sampler={sampler}"] if sampler and len(samplers) > 1 else [])
            label = f"Candela {name}" + (f" {sampler}" if sampler and len(samplers) > 1 else "")
            out.append((label, "CANDELA", settings))
    return out


def build_fingerprint():
    """Changes whenever the renderer or the scenes change: references are re-rendered then."""
    h = hashlib.sha256()
    for p in [ROOT / "examples" / "scenes.py", ROOT / "examples" / "cornell_box.py"]:
        h.update(p.read_bytes())
    for so in (Path(ARGS.build) / "scripts" / "addons" / "candela").glob("_native*.so"):
        h.update(so.read_bytes())
    return h.hexdigest()[:16]


def reference(scene, engine, ref_samples):
    """A cached high-sample reference (luminance) and its estimated per-pixel noise variance."""
    key = f"{scene}_{engine}_{ARGS.size}_{ref_samples}_{build_fingerprint() if engine == 'CANDELA' else 'cycles34'}"
    cache = ARGS.out / "cache"
    cache.mkdir(parents=True, exist_ok=True)
    files = [cache / f"{key}_{i}.exr" for i in (0, 1)]
    if not all(f.exists() for f in files):
        # Two independent halves: their difference estimates the reference's own noise.
        for i, f in enumerate(files):
            res = run_blender(["--scene", scene, "--engine", engine, "--counts", str(ref_samples // 2),
                               "--size", str(ARGS.size), "--threads", str(ARGS.threads), "--seed", str(1000 + i),
                               "--out", str(cache), "--tag", f"{key}_part{i}"], cache / f"{key}_{i}.log")
            os.replace(res["runs"][0]["exr"], f)
    native = native_module()
    a, b = (luminance(native.read_exr(str(f))) for f in files)
    ref = 0.5 * (a + b)
    noise_var = float(np.mean((a - b) ** 2) / 4.0)   # Var(mean of halves) = Var(a − b)/4 per pixel
    return ref, noise_var


def errors(image, ref, ref_noise_var):
    d2 = (image - ref) ** 2
    rmse = math.sqrt(max(float(np.mean(d2)) - ref_noise_var, 0.0)) / max(float(np.mean(ref)), 1e-12)
    rel_mse = float(np.mean(d2 / (ref ** 2 + 1e-2)))
    return rmse, rel_mse


def fit(points):
    """Least-squares line through log(error) vs log(time) for the points with samples ≥ 4: (slope, intercept)."""
    pts = [(t, e) for n, t, e in points if n >= 4 and t > 0 and e > 0]
    if len(pts) < 2:
        return None
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    slope, intercept = np.polyfit(x, y, 1)
    return float(slope), float(intercept)


def time_to(target, points, line):
    """Seconds to reach `target` relative RMSE: interpolated between measurements, else extrapolated from the
    fit (marked by the caller)."""
    for (n0, t0, e0), (n1, t1, e1) in zip(points, points[1:]):
        if e0 >= target >= e1 and e0 > 0 and e1 > 0 and t0 > 0:
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0))), False
    if points and points[0][2] <= target:
        return points[0][1], False
    if line is None or line[0] >= 0:
        return None, True
    slope, intercept = line
    return math.exp((math.log(target) - intercept) / slope), True


def machine():
    cpu = "unknown CPU"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}"


def main():
    global ARGS
    ARGS = parse_args()
    native = native_module()
    started = time.time()
    counts = [2 ** k for k in range(int(math.log2(ARGS.max_samples)) + 1)]
    scene_names = ARGS.scenes.split(",") if ARGS.scenes else ["cornell_box", "soft_shadow", "veach_mis", "glossy"]
    configs = configurations(native)
    if ARGS.quick:
        configs = configs[:2] + configs[-1:] if len(configs) > 3 else configs
    ARGS.out.mkdir(parents=True, exist_ok=True)
    rows, results = [], {}
    for scene in scene_names:
        refs = {}
        for label, engine, settings in configs:
            if engine not in refs:
                refs[engine] = reference(scene, engine, ARGS.ref_factor * ARGS.max_samples)
            ref, ref_noise = refs[engine]
            tag = f"{scene}_{label.replace(' ', '_')}"
            args = ["--scene", scene, "--engine", engine, "--counts", ",".join(map(str, counts)), "--size",
                    str(ARGS.size), "--threads", str(ARGS.threads), "--out", str(ARGS.out / "renders"), "--tag", tag]
            for s in settings:
                args += ["--set", s]
            res = run_blender(args, ARGS.out / f"{tag}.log")
            points = []
            for run in res["runs"]:
                rmse, rel_mse = errors(luminance(native.read_exr(run["exr"])), ref, ref_noise)
                points.append((run["samples"], run["seconds"], rmse))
                rows.append({"scene": scene, "configuration": label, "samples": run["samples"],
                             "seconds": f"{run['seconds']:.6f}", "relative_rmse": f"{rmse:.6f}",
                             "relative_mse": f"{rel_mse:.6g}"})
            results[(scene, label)] = points
            print(f"{scene:12s} {label:28s} " + "  ".join(f"{n}:{e:.3f}@{t:.2f}s" for n, t, e in points), flush=True)
    write_outputs(scene_names, configs, results, rows, started)
    print(f"accuracy: done in {time.time() - started:.0f} s; results in {ARGS.out}" +
          ("" if ARGS.quick else f" and {ARGS.docs}/accuracy.md"))


def write_outputs(scene_names, configs, results, rows, started):
    docs = ARGS.out if ARGS.quick else Path(ARGS.docs)
    plots = docs / "accuracy"
    plots.mkdir(parents=True, exist_ok=True)
    with open(plots / "measurements.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    when = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    md = ["# What accuracy costs in time", "",
          "Generated by `make accuracy` (`bench/accuracy.py`); do not edit by hand.", "",
          f"Measured on {machine()}, {ARGS.threads} render threads, {when}, in one run: every number below comes "
          "from the same machine and session. Headline figures are ratios, not seconds.", "",
          f"Images {ARGS.size} px wide; 1 to {ARGS.max_samples} samples per pixel; error = relative RMSE of "
          f"luminance against a {ARGS.ref_factor * ARGS.max_samples}-sample reference of the same engine. "
          "Times exclude scene export and BVH build. *Slope* is the fitted exponent of error ∝ time^slope "
          "(−0.5 for plain Monte Carlo). A `~` marks a time extrapolated from that fit; `—` means not reached.",
          ""]
    for scene in scene_names:
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        cyc_points = results.get((scene, "Cycles"))
        cyc_line = fit(cyc_points) if cyc_points else None
        md += [f"## {scene.replace('_', ' ').title()}", "", f"![{scene}](accuracy/{scene}.png)", "",
               "| configuration | 5 % | 2 % | 1 % | slope | vs Cycles at 2 % |", "|---|---|---|---|---|---|"]
        for label, _, _ in configs:
            points = results[(scene, label)]
            line = fit(points)
            ax.loglog([p[1] for p in points], [p[2] for p in points], marker="o", ms=3, label=label,
                      color="black" if label == "Cycles" else None)
            cells = []
            for target in TARGETS:
                t, extrapolated = time_to(target, points, line)
                cells.append("—" if t is None else f"{'~' if extrapolated else ''}{t:.3g} s")
            t2, _ = time_to(0.02, points, line)
            tc, _ = time_to(0.02, cyc_points, cyc_line) if cyc_points else (None, True)
            ratio = "—" if not t2 or not tc else f"{t2 / tc:.2f}×"
            md.append(f"| {label} | {' | '.join(cells)} | {line[0]:.2f} |" if line else
                      f"| {label} | {' | '.join(cells)} | — |")
            md[-1] += f" {ratio} |"
        ax.set_xlabel("render time [s]")
        ax.set_ylabel("relative RMSE")
        ax.set_title(scene.replace("_", " "))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(plots / f"{scene}.png", dpi=110)
        plt.close(fig)
        md.append("")
    md += ["Raw measurements: [accuracy/measurements.csv](accuracy/measurements.csv). "
           f"The run took {time.time() - started:.0f} s.", ""]
    (docs / "accuracy.md").write_text("\n".join(md))


if __name__ == "__main__":
    main()
