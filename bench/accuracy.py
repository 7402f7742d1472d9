"""`make accuracy`: what accuracy costs in time, per scene, per technique, against Cycles.

    /usr/bin/python3.11 bench/accuracy.py [--quick] [--out DIR] [--docs docs] [--size 96] [--max-samples 256] [--scenes A,B] [--configs 'Cycles,Candela PATH SOBOL'] [--reference-integrator door=BDPT]

For every scene (examples/scenes.py) and every configuration — Cycles, and Candela with each integrator and
each sampler the native module offers — it renders at 1, 2, 4, … samples per pixel, measures the CPU time of
every render (all configurations of a scene round-robin in one Blender process: bench/accuracy_sequences.py)
and the error against a high-sample reference of the SAME engine
(rendered once as two independent halves and cached in OUT/cache, keyed by scene, size, engine and the
renderer's build), and writes:
  DOCS/accuracy.md          a table per scene: time to reach 5 % / 2 % / 1 % relative RMSE (measured, or
                            extrapolated within a stated bound), the fitted slope ± its standard error, the ratio
                            to Cycles' time, time and MSE at equal samples against Cycles, relative
                            MSE and a trimmed relative RMSE; the method is written into the report
  DOCS/accuracy/SCENE.png   log-log error-vs-time plots (relative RMSE, trimmed dotted; relative MSE), one line
                            per configuration, Cycles included
  DOCS/accuracy/measurements.csv   every measurement (CPU and wall times, all metrics)
The statistics (metrics, set-up, fits, the extrapolation bound) are in bench/accuracy_stats.py.
All times come from one run on one machine; the report says which and when. The defaults (96 px, up to 256
samples, references of 2048) take about 10 minutes on an idle 2-core machine and stay under 30 under load.
--quick (for `make test`) renders 32 px images at up to 8 samples into OUT only, to check the pipeline (about
half a minute), not the numbers.
--auto (`make accuracy-auto`, issue 19's acceptance of AUTO) measures the accuracy scenes and the held-out ones
(examples/scenes.py HELD_OUT) with AUTO_CONFIGS only and writes DOCS/accuracy_auto.md (the table "AUTO at equal time"
first, with a verdict per scene against the targets) and DOCS/accuracy_auto/. --reuse reads back the sequences an
earlier run saved in OUT for the same arguments (whatever build measured them; --rerun A,B renders those scenes
afresh), for a run split into batches or repeated after a change that leaves the other configurations' images alike.
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


sys.path.insert(0, str(Path(__file__).resolve().parent))
import accuracy_stats as stats  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
TARGETS = (0.05, 0.02, 0.01)
# Integrators measured on some scenes only (the others on all): the irradiance cache on the scenes its issue names,
# the Cornell box and a diffuse interior.
INTEGRATOR_SCENES = {"IRRADIANCE_CACHE": ("cornell_box", "room_window")}
# Configurations measured on some scenes only: PATH with POWER light selection beside the default TREE where the
# light tree has thousands of emissive triangles to choose from (issue 22: TREE must not cost more than POWER).
CONFIG_SCENES = {"Candela PATH POWER": ("veach_mis",)}
DEFAULT_SCENES = ["cornell_box", "soft_shadow", "veach_mis", "glossy", "room_window", "caustic", "door"]
# `--auto` (make accuracy-auto, issue 19's acceptance of AUTO): the accuracy scenes and the held-out ones
# (examples/scenes.py HELD_OUT, which the policy was not tuned on), with the configurations AUTO is compared with:
# Cycles, PATH with the default sampler, AUTO, and BDPT (the other integrator the policy can choose in this build:
# SPPM comes after BDPT in the table); MMLT on the door ajar, the one scene where a Metropolis sampler may be best;
# the irradiance cache on its two scenes (INTEGRATOR_SCENES). Not measured for want of time on this shared machine:
# LIGHT, MLT, PHOTON, SPPM and PATH's other samplers (docs/accuracy.md has them on the accuracy scenes).
AUTO_CONFIGS = ("Cycles", "Candela PATH SOBOL", "Candela AUTO", "Candela BDPT", "Candela MMLT",
                "Candela IRRADIANCE_CACHE")
AUTO_CONFIG_SCENES = {"Candela MMLT": ("door",)}


def held_out_scenes(name=None):
    """examples/scenes.py's HELD_OUT (or the list `name`; default HELD_OUT + HELD_OUT_2, the second held-out set),
    read without importing it (it needs Blender's bpy)."""
    import ast
    if name is None:
        return held_out_scenes("HELD_OUT") + held_out_scenes("HELD_OUT_2")
    tree = ast.parse((ROOT / "examples" / "scenes.py").read_text())
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == name for t in node.targets):
            return list(ast.literal_eval(node.value))
    return []


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="pipeline check: tiny images, few samples, no docs")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--out", default=None, help="work directory (default BUILD/accuracy or BUILD/accuracy-quick)")
    ap.add_argument("--docs", default=str(ROOT / "docs"), help="where accuracy.md and the plots go")
    ap.add_argument("--size", type=int, default=96)
    ap.add_argument("--max-samples", type=int, default=256)
    ap.add_argument("--ref-factor", type=int, default=8, help="reference samples = factor × max samples")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--scenes", default=None, help="comma-separated subset of the scenes")
    ap.add_argument("--configs", default=None, help="comma-separated subset of the configuration labels")
    ap.add_argument("--repeats", type=int, default=1, help="renders per configuration and count (least CPU kept)")
    ap.add_argument("--reference-integrator", default="",
                    help="SCENE=INTEGRATOR,…: the Candela integrator rendering a scene's reference (default PATH); "
                         "an unbiased one with less noise per second there (BDPT on the door scenes) makes the "
                         "reference's own noise a smaller part of every error")
    ap.add_argument("--path-reference", action="store_true",
                    help="every Candela reference by PATH (but --reference-integrator's), not the integrator the "
                         "scene analysis calls for (default: BDPT where a light no ray hits has caustic paths)")
    ap.add_argument("--reuse", action="store_true",
                    help="read back the sequences an earlier run with the same arguments and build saved in OUT")
    ap.add_argument("--rerun", default="", help="with --reuse: comma-separated scenes to render afresh")
    ap.add_argument("--auto", action="store_true",
                    help="AUTO's acceptance: accuracy + held-out scenes, AUTO_CONFIGS, DOCS/accuracy_auto.md")
    ap.add_argument("--report", default=None,
                    help="the report's name: DOCS/REPORT.md and DOCS/REPORT/ (default accuracy or accuracy_auto)")
    a = ap.parse_args()
    if a.quick:
        a.size, a.max_samples, a.ref_factor = 32, 8, 8
        a.scenes = a.scenes or "cornell_box,soft_shadow"
    a.out = Path(a.out or Path(a.build) / ("accuracy-quick" if a.quick else "accuracy-auto" if a.auto else "accuracy"))
    a.report = a.report or ("accuracy_auto" if a.auto else "accuracy")
    a.rerun = [x for x in a.rerun.split(",") if x]
    a.reference_integrator = dict(kv.split("=", 1) for kv in a.reference_integrator.split(",") if kv)
    a.default_reference = not a.path_reference
    return a


def run_blender(args, log, script="accuracy_render.py", marker="ACCURACY_JSON "):
    cmd = [str(ROOT / "bin" / "candela-blender"), "-b", "--factory-startup", "-noaudio", "--python-exit-code", "1",
           "--python", str(ROOT / "bench" / script), "--", *args]
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env["CANDELA_SCRIPTS_DIR"] = str(Path(ARGS.build) / "scripts")
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    log.write_text(proc.stdout + proc.stderr)
    if proc.returncode != 0:
        raise RuntimeError(f"Blender failed ({proc.returncode}); see {log}")
    for line in proc.stdout.splitlines():
        if line.startswith(marker):
            return json.loads(line[len(marker):])
    raise RuntimeError(f"no result from Blender; see {log}")


def native_module():
    sys.path.insert(0, str(Path(ARGS.build) / "scripts" / "addons" / "candela"))
    import _native
    return _native


def configurations(native):
    """(label, engine, candela settings) for every configuration the build offers."""
    caps = native.capabilities()
    out = [("Cycles", "CYCLES", [])]
    for name, *_ in caps["integrators"]:
        samplers = caps.get("samplers", ["RANDOM"]) if name == "PATH" else [None]
        for sampler in samplers:
            settings = [f"integrator={name}"] + ([f"sampler={sampler}"] if sampler and len(samplers) > 1 else [])
            # Every count renders afresh: a bootstrap for the image size, not 10⁵ paths. The default 1000 chains: on the
            # door scene at 96 px MMLT's MSE at 256 mutations per pixel was 1.7× lower with 1000 chains than with 100
            # (3 seeds each, docs/metropolis.md) — a depth then has tens of chains, not a handful.
            if name in ("MLT", "MMLT"):
                settings += [f"mlt_bootstrap={1000 if ARGS.quick else 20000}", "mlt_chains=1000"]
            label = f"Candela {name}" + (f" {sampler}" if sampler and len(samplers) > 1 else "")
            out.append((label, "CANDELA", settings))
        if name == "PATH":
            out.append(("Candela PATH POWER", "CANDELA", [f"integrator={name}", "light_selection=POWER"]))
    return out


def integrator_of(config):
    """The Candela integrator of a configuration (None for Cycles)."""
    for kv in config[2]:
        if kv.startswith("integrator="):
            return kv.split("=", 1)[1]
    return None


def build_fingerprint():
    """Changes whenever the renderer or the scenes change: references are re-rendered then."""
    h = hashlib.sha256()
    for p in [ROOT / "examples" / "scenes.py", ROOT / "examples" / "cornell_box.py"]:
        h.update(p.read_bytes())
    for so in (Path(ARGS.build) / "scripts" / "addons" / "candela").glob("_native*.so"):
        h.update(so.read_bytes())
    return h.hexdigest()[:16]


REFERENCE_WHY = {}  # scene → why its Candela reference is rendered by the integrator it is (report, log)


def features_line(scene):
    """AUTO's scene-features log line for the scene (one AUTO render of 1 sample at the run's size), cached."""
    cache = ARGS.out / "cache"
    cache.mkdir(parents=True, exist_ok=True)
    saved = cache / f"{scene}_features_{ARGS.size}_{build_fingerprint()}.txt"
    if not saved.exists():
        res = run_blender(["--scene", scene, "--engine", "CANDELA", "--counts", "1", "--size", str(ARGS.size),
                           "--threads", str(ARGS.threads), "--out", str(cache), "--tag", f"{scene}_features",
                           "--set", "integrator=AUTO"], cache / f"{scene}_features.log")
        lines = [l for l in res.get("info", []) if "Auto: scene features:" in l]
        saved.write_text(lines[0] if lines else "")
    return saved.read_text()


def default_reference_integrator(scene):
    """The Candela integrator for the scene's reference, from AUTO's scene analysis (stats.reference_integrator_for)."""
    return stats.reference_integrator_for(features_line(scene))


def reference(scene, engine, ref_samples):
    """A cached high-sample reference: the luminance of two independent half renders (accuracy_stats.errors
    averages them and uses their difference as the reference's own noise)."""
    integrator = None
    if engine == "CANDELA":
        if scene in ARGS.reference_integrator:
            integrator = ARGS.reference_integrator[scene]
            REFERENCE_WHY[scene] = (integrator, "--reference-integrator")
        elif ARGS.default_reference:
            integrator, why = default_reference_integrator(scene)
            REFERENCE_WHY[scene] = (integrator or "PATH", why)
            print(f"accuracy: {scene}: Candela reference by {integrator or 'PATH'} ({why})", flush=True)
    key = (f"{scene}_{engine}{'_' + integrator if integrator else ''}_{ARGS.size}_{ref_samples}_"
           f"{build_fingerprint() if engine == 'CANDELA' else 'cycles34'}")
    cache = ARGS.out / "cache"
    cache.mkdir(parents=True, exist_ok=True)
    files = [cache / f"{key}_{i}.exr" for i in (0, 1)]
    if ARGS.reuse and engine == "CANDELA" and not all(f.exists() for f in files):
        # --reuse: a reference another build rendered (PATH's image: valid while PATH's estimator is unchanged)
        older = sorted(cache.glob(f"{scene}_{engine}{'_' + integrator if integrator else ''}_{ARGS.size}_"
                                  f"{ref_samples}_*_0.exr"))
        if older:
            files = [older[-1], Path(str(older[-1])[:-len("_0.exr")] + "_1.exr")]
    if not all(f.exists() for f in files):
        for i, f in enumerate(files):
            res = run_blender(["--scene", scene, "--engine", engine, "--counts", str(ref_samples // 2),
                               "--size", str(ARGS.size), "--threads", str(ARGS.threads), "--seed", str(1000 + i),
                               "--out", str(cache), "--tag", f"{key}_part{i}",
                               *(["--set", f"integrator={integrator}"] if integrator else [])], cache / f"{key}_{i}.log")
            os.replace(res["runs"][0]["exr"], f)
    native = native_module()
    return tuple(stats.luminance(native.read_exr(str(f))) for f in files)


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


MEASURED = {}  # --reuse: scene → (when its saved sequences were measured, by which build)


def sequences_args(scene, configs, counts):
    """bench/accuracy_sequences.py's arguments for one scene (also the key of its saved result)."""
    args = ["--scene", scene, "--size", str(ARGS.size), "--threads", str(ARGS.threads), "--counts",
            ",".join(map(str, counts)), "--repeats", str(ARGS.repeats), "--out", str(ARGS.out / "renders")]
    for label, engine, settings in configs:
        args += ["--config", f"{label}|{engine}|{','.join(settings)}"]
    return args


def sequences(scene, configs, counts):
    """Render every configuration at every count, round-robin in one Blender process
    (bench/accuracy_sequences.py): {label: [run, …]} with the least CPU time over the repeats."""
    args = sequences_args(scene, configs, counts)
    # --reuse: a scene's sequences measured by an earlier run with the same arguments are read back instead of
    # rendered again (a long run split into batches, the report rewritten), whatever build measured them: for
    # changes that leave the images of the configurations measured alike (AUTO's policy: then --rerun the scenes
    # whose choice changed). The build that measured them is recorded in the file.
    key = hashlib.sha256(json.dumps(args).encode()).hexdigest()[:16]
    saved = ARGS.out / f"{scene}_sequences_{key}.json"
    if ARGS.reuse and saved.exists() and scene not in ARGS.rerun:
        res = json.loads(saved.read_text())
        MEASURED[scene] = (datetime.datetime.fromtimestamp(saved.stat().st_mtime).strftime("%Y-%m-%d %H:%M"),
                           res.get("build", "an earlier build (not recorded)"))
    else:
        res = run_blender(args, ARGS.out / f"{scene}_sequences.log", "accuracy_sequences.py",
                          "ACCURACY_SEQUENCES_JSON ")
        res["build"] = build_fingerprint()
        saved.write_text(json.dumps(res))
    best = {}
    for run in res["runs"]:
        key = (run["configuration"], run["samples"])
        if key not in best or run["cpu_seconds"] < best[key]["cpu_seconds"]:
            best[key] = run
    return {label: [best[(label, n)] for n in counts] for label, _, _ in configs}


def measure(scene, label, runs, ref, rows, setup=None):
    """One configuration's points as a dict of lists (samples, cpu, time, the metrics …). `setup`: the per-render
    set-up to subtract instead of the one estimated from the configuration's own 1- and 2-sample renders (an
    integrator whose pre-pass does not grow with the samples — the irradiance cache — would have it counted as
    set-up: it takes the PATH configuration's, the same export and BVH)."""
    native = native_module()
    metrics = ("rrmse", "relmse", "robust", "ref_noise_fraction", "robust_ref_noise_fraction", "top_share")
    p = {k: [] for k in ("samples", "cpu", "wall", "rrmse_sigma", *metrics)}
    for run in runs:
        image = stats.luminance(native.read_exr(run["exr"]))
        err = stats.errors(image, *ref)
        p["rrmse_sigma"].append(stats.rrmse_log_sigma(image, *ref))
        p["samples"].append(run["samples"])
        p["cpu"].append(run["cpu_seconds"])
        p["wall"].append(run["wall_seconds"])
        for k in metrics:
            p[k].append(err[k])
    p["setup"], p["time"] = stats.render_times(p["samples"], p["cpu"])
    if setup is not None:
        p["setup"], p["time"] = setup, [max(c - setup, 1e-9) for c in p["cpu"]]
    p["cost_sequence"] = stats.cost_per_sample(p["samples"], p["cpu"])
    for i, n in enumerate(p["samples"]):
        rows.append({"scene": scene, "configuration": label, "samples": n,
                     "cpu_seconds": f"{p['cpu'][i]:.6f}", "wall_seconds": f"{p['wall'][i]:.6f}",
                     "setup_cpu_seconds": f"{p['setup']:.6f}", "time_seconds": f"{p['time'][i]:.6f}",
                     "relative_rmse": f"{p['rrmse'][i]:.6g}", "relative_mse": f"{p['relmse'][i]:.6g}",
                     "trimmed_relative_rmse": f"{p['robust'][i]:.6g}",
                     "worst_pixels_error_share": f"{p['top_share'][i]:.4g}",
                     "reference_noise_fraction": f"{p['ref_noise_fraction'][i]:.4g}"})
    print(f"{scene:12s} {label:28s} {1e3 * p['time'][-1] / p['samples'][-1]:.2f} ms/spp at {p['samples'][-1]} "
          f"(Theil-Sen {1e3 * p['cost_sequence']:.2f})  " +
          "  ".join(f"{n}:{e:.3f}/{r:.3f}" for n, e, r in zip(p["samples"], p["rrmse"], p["robust"])), flush=True)
    return p


def main():
    global ARGS
    ARGS = parse_args()
    native = native_module()
    started = time.time()
    counts = [2 ** k for k in range(int(math.log2(ARGS.max_samples)) + 1)]
    scene_names = ARGS.scenes.split(",") if ARGS.scenes else DEFAULT_SCENES + (held_out_scenes() if ARGS.auto else [])
    configs = configurations(native)
    if ARGS.auto:
        configs = [c for c in configs if c[0] in AUTO_CONFIGS]
    if ARGS.quick:
        configs = configs[:2] + configs[-1:] if len(configs) > 3 else configs
    if ARGS.configs:
        wanted = ARGS.configs.split(",")
        configs = [c for c in configs if c[0] in wanted]
    ARGS.out.mkdir(parents=True, exist_ok=True)
    rows, results = [], {}
    scene_configs = {}
    for scene in scene_names:
        config_scenes = {**CONFIG_SCENES, **AUTO_CONFIG_SCENES} if ARGS.auto else CONFIG_SCENES
        here = [c for c in configs
                if scene in config_scenes.get(c[0], INTEGRATOR_SCENES.get(integrator_of(c), (scene,)))]
        scene_configs[scene] = here
        refs = {engine: reference(scene, engine, ARGS.ref_factor * ARGS.max_samples)
                for engine in dict.fromkeys(engine for _, engine, _ in here)}
        runs = sequences(scene, here, counts)
        path_setup = None
        for label, engine, settings in here:
            integrator = integrator_of((label, engine, settings))
            setup = path_setup if engine == "CANDELA" and integrator not in (None, "PATH") else None
            results[(scene, label)] = measure(scene, label, runs[label], refs[engine], rows, setup)
            results[(scene, label)]["runs"] = runs[label]
            if integrator == "PATH" and path_setup is None:
                path_setup = results[(scene, label)]["setup"]
    write_outputs(scene_names, scene_configs, results, rows, started)
    print(f"accuracy: done in {time.time() - started:.0f} s; results in {ARGS.out}" +
          ("" if ARGS.quick else f" and {ARGS.docs}/{ARGS.report}.md"))


def cell(t, how):
    if t is None:
        return "—"
    return {"measured": f"{t:.3g} s", "extrapolated": f"~{t:.3g} s", "beyond": f"> {t:.3g} s"}[how]


def ratio(a, b):
    return "—" if a is None or b is None or b <= 0 else f"{a / b:.2f}×"


def target_cells(p, metric, cyc, cyc_line):
    """Time to each target, the slope, and the time ratio to Cycles at 2 % for one metric."""
    noise = p["ref_noise_fraction" if metric == "rrmse" else "robust_ref_noise_fraction"]
    line = stats.fit(p["samples"], p[metric], noise)
    cells = [cell(*stats.time_to(x, p["samples"], p["time"], p[metric], line)) for x in TARGETS]
    slope = "—" if line is None else (f"{line['slope']:.2f} ± {line['sigma']:.2f}" +
                                      ("" if stats.fit_is_usable(line) else " (not used)"))
    t2, how2 = stats.time_to(0.02, p["samples"], p["time"], p[metric], line)
    how_text, log_sigma = stats.crossing(0.02, p["samples"], p["time"], p[metric], line,
                                         p["rrmse_sigma"] if metric == "rrmse" else None)
    if log_sigma is not None:   # the error figure's noise and the load's scatter of the render times
        how_text += f" (×/÷ {math.exp(math.hypot(log_sigma, time_line_log_sigma(p))):.2f})"
    time_ratio = "—"
    if cyc:
        t_cyc, how_cyc = stats.time_to(0.02, cyc["samples"], cyc["time"], cyc[metric], cyc_line)
        if how2 != "beyond" and how_cyc != "beyond":   # both measured or inside the extrapolation bound
            time_ratio = ratio(t2, t_cyc)
    return cells, slope, time_ratio, how_text


def scene_tables(scene, configs, results, n_max):
    """Two markdown tables for one scene: relative RMSE (the targets, ratios to Cycles, the other metrics at
    the largest count) and the trimmed relative RMSE (the same targets on the robust figure)."""
    cyc = results.get((scene, "Cycles"))
    fits = {m: stats.fit(cyc["samples"], cyc[m], cyc[f]) if cyc else None
            for m, f in (("rrmse", "ref_noise_fraction"), ("robust", "robust_ref_noise_fraction"))}
    main = [f"| configuration | 5 % | 2 % | 1 % | 2 % reached how | slope ± σ | time vs Cycles at 2 % "
            f"| time vs Cycles at {n_max} spp "
            f"| rel. RMSE at {n_max} spp | MSE vs Cycles at {n_max} spp | rel. MSE at {n_max} spp "
            f"| worst {100 * stats.TRIM:g} % of pixels' share of the squared error |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    robust = [f"Trimmed relative RMSE ({100 * stats.TRIM:g} % of pixels with the largest errors dropped):", "",
              "| configuration | 5 % | 2 % | 1 % | 2 % reached how | slope ± σ | time vs Cycles at 2 % "
              f"| trimmed rel. RMSE at {n_max} spp | its MSE vs Cycles |", "|---|---|---|---|---|---|---|---|---|"]
    for label, _, _ in configs:
        p = results[(scene, label)]
        cells, slope, time_ratio, how = target_cells(p, "rrmse", cyc, fits["rrmse"])
        mse_ratio = ratio(p["rrmse"][-1] ** 2, cyc["rrmse"][-1] ** 2) if cyc else "—"
        main.append(f"| {label} | {' | '.join(cells)} | {how} | {slope} | {time_ratio} | "
                    f"{ratio(p['time'][-1], cyc['time'][-1]) if cyc else '—'} | {p['rrmse'][-1]:.3g} | {mse_ratio} | "
                    f"{p['relmse'][-1]:.3g} | {100 * p['top_share'][-1]:.0f} % |")
        cells, slope, time_ratio, how = target_cells(p, "robust", cyc, fits["robust"])
        mse_ratio = ratio(p["robust"][-1] ** 2, cyc["robust"][-1] ** 2) if cyc else "—"
        robust.append(f"| {label} | {' | '.join(cells)} | {how} | {slope} | {time_ratio} | {p['robust'][-1]:.3g} | "
                      f"{mse_ratio} |")
    return main + [""] + robust


def plot(scene, configs, results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    for label, _, _ in configs:
        p = results[(scene, label)]
        colour = "black" if label == "Cycles" else None
        (h,) = axes[0].loglog(p["time"], p["rrmse"], marker="o", ms=3, label=label, color=colour)
        axes[0].loglog(p["time"], p["robust"], ls=":", lw=1, color=h.get_color())
        axes[1].loglog(p["time"], p["relmse"], marker="o", ms=3, label=label, color=h.get_color())
    axes[0].set_ylabel(f"relative RMSE (dotted: trimmed, {100 * stats.TRIM:g} % largest errors dropped)")
    axes[1].set_ylabel("relative MSE")
    for ax in axes:
        ax.set_xlabel("CPU time [s], set-up excluded")
        ax.grid(True, which="both", alpha=0.3)
    axes[1].legend(fontsize=7)
    fig.suptitle(scene.replace("_", " "))
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def write_outputs(scene_names, configs, results, rows, started):
    docs = ARGS.out if ARGS.quick else Path(ARGS.docs)
    plots = docs / ARGS.report
    plots.mkdir(parents=True, exist_ok=True)
    with open(plots / "measurements.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    when = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    n_max = ARGS.max_samples
    md = ["# What accuracy costs in time", "",
          "Generated by `make accuracy` (`bench/accuracy.py`, statistics in `bench/accuracy_stats.py`); do not "
          "edit by hand.", "",
          f"Measured on {machine()}, {ARGS.threads} render threads, {when}, in one run: every number below comes "
          "from the same machine and session. Headline figures are ratios, not seconds.", "",
          "## Method", "",
          f"Images {ARGS.size} px wide, rendered at 1, 2, 4 … {n_max} samples per pixel (one progressive "
          f"sequence per configuration: fixed seed, so the counts share their first samples); references of "
          f"{ARGS.ref_factor * n_max} samples, rendered once per engine as two independent halves.", "",
          "- **Error** is on luminance against the reference of the same engine, with the reference's own noise "
          "(estimated from the difference of its halves) subtracted. *rel. RMSE* = √mean((L − L_ref)²) / "
          "mean(L_ref) is the error the targets 5 / 2 / 1 % refer to; *rel. MSE* = mean((L − L_ref)² / "
          f"(L_ref² + {stats.EPS:g})) weighs every pixel by its own brightness. Where a few pixels carry most "
          "of the squared error (emitters seen directly or in mirrors: their edges, and fireflies), one "
          "image's rel. RMSE jumps up and down between sample counts and says little about the rest of the "
          f"image; the column *worst {100 * stats.TRIM:g} % of pixels' share* says how much that is the case. "
          f"The second table per scene is the *trimmed rel. RMSE*, without the {100 * stats.TRIM:g} % of "
          "pixels with the largest errors: a robust figure for heavy-tailed scenes, not an error bound (it "
          "leaves out the fireflies by construction).",
          "- **Time** is CPU time (both render threads summed; on an idle machine the wall time is about half), "
          "less the per-render set-up (export, BVH, Cycles' sync) estimated as 2·t(1) − t(2). Wall time on "
          "this shared 2-core machine follows the other jobs' load: it made the previous report show Candela "
          "at 2.4× Cycles' time per sample on the Cornell box, where CPU time put it at 0.7–1.1× in three later runs. CPU time "
          "moves less, but still by up to ~30 % (the cores are shared), so all configurations of a scene "
          "render in one Blender process, round-robin — each count in turn for every configuration — and a "
          "load that comes and goes hits them alike"
          + (f"; each render is repeated {ARGS.repeats}× and the least CPU time kept" if ARGS.repeats > 1 else "")
          + ". The CSV also has every render's wall time.",
          f"- **Slope** is the least-squares exponent of rel. RMSE ∝ samples^s (= time^s), fitted on the counts "
          f"≥ {stats.MIN_SAMPLES_FIT} where the reference's noise is under {100 * stats.REF_NOISE_MAX:g} % of "
          "the raw squared error, with its standard error σ (a lower bound: the points are nested). −0.5 is "
          "plain Monte Carlo. A fit with fewer than 3 such points, a slope outside −1.5 … −0.2 or σ > 0.15 is "
          "marked *not used* and never extrapolated.",
          "- **Extrapolation** past the last measurement follows the fitted line for at most a factor F_max "
          "in time. A slope error Δs changes an extrapolated time by F^(Δs/|s|); asking for at most "
          f"{stats.TIME_TOLERANCE:g}× both for the fit's σ and for a change of regime of Δs = "
          f"{stats.REGIME_DS:g} at s = −0.5 gives F_max = min({stats.F_CAP:.1f}, "
          f"{stats.TIME_TOLERANCE:g}^(|s|/σ)). `~` marks such a time; `> t` means not reached within it "
          "(t = the last measured time); `—` no usable value. A time without a mark is measured: interpolated "
          "(log-log) between the two measured counts whose errors bracket the target.",
          "- **2 % reached how** says which for the 2 % target: *interpolated N–2N spp* (the counts bracketing "
          "it), *extrapolated ×F past N spp* (F = that time over the last measured one), *not reached by N spp*, "
          "*first at N spp* (reached, then lost again by noise). For an interpolated crossing ×/÷ f is its "
          "time's noise, f = e^σ, σ² = (σ_e/|s|)² + τ²: σ_e the larger standard error of log(rel. RMSE) of the "
          "two bracketing images (from the scatter of the squared error over 2 × 2-pixel tiles; it understates "
          "an error made of smooth blotches, such as an irradiance cache's records'), s the local slope "
          "between them, τ the scatter of log(CPU time) about a straight line t₀ + c·samples over the counts ≥ "
          f"{TIME_NOISE_MIN_SAMPLES} (the load; c the Theil–Sen cost per sample).",
          "- **Integrators other than PATH** are measured against the same Candela reference, which PATH renders "
          "except where the scene has caustic paths from a light no ray can hit (AUTO's scene analysis: a point, "
          "spot or sun light and a delta surface): PATH cannot sample those caustics and its reference would lack "
          "them, so BDPT renders it (--path-reference: PATH everywhere); the references not PATH's here:"
          + ("".join(f" {s.replace('_', ' ')}: {i} ({why});" for s, (i, why) in REFERENCE_WHY.items()
                     if s in scene_names and i != "PATH") or " none;") + " their error includes their bias (the irradiance cache's interpolation and record noise, which do not "
          "fall with the samples per pixel). The irradiance cache's pre-pass is part of its time: its set-up is "
          "taken to be PATH's on the same scene (the same export and BVH) rather than 2·t(1) − t(2), which would "
          "count the pre-pass as set-up. It is measured on the scenes its issue names (the Cornell box and the "
          "room lit through a window).",
          "- **Ratios to Cycles**: the time ratio at 2 % only where both times are measured or within the "
          f"bound; the *time* and the *MSE* at {n_max} samples always (for slopes near −0.5, the time ratio "
          "at equal error is about their product).", ""]
    for scene in scene_names:
        md += [f"## {scene.replace('_', ' ').title()}", "", f"![{scene}]({ARGS.report}/{scene}.png)", ""]
        md += scene_tables(scene, configs[scene], results, n_max)
        md.append("")
        plot(scene, configs[scene], results, plots / f"{scene}.png")
    table = auto_table(scene_names, configs, results)
    md += ["Raw measurements: [{0}/measurements.csv]({0}/measurements.csv). ".format(ARGS.report) +
           f"The run took {time.time() - started:.0f} s.", ""]
    if ARGS.auto:   # the acceptance table first: it is what this report is for
        head = md.index("## Method")
        md = md[:head] + table + md[head:]
        md[0] = "# AUTO at equal time: issue 19's acceptance measurement"
        md[2] = md[2].replace("`make accuracy`", "`make accuracy-auto`")
    else:
        md += table
    (docs / f"{ARGS.report}.md").write_text("\n".join(md))


def error_at(p, t):
    """A configuration's rel. RMSE at time t: log-log interpolation between its measured points, and beyond them
    the plain Monte Carlo slope −0.5 from the nearest end (an equal-time comparison needs every configuration at
    the same time, which the sample counts do not give)."""
    # Sorted by time: under load a small count can take longer than the next one (the points stay the same).
    pts = sorted((x, e) for x, e in zip(p["time"], p["rrmse"]) if x > 0 and e > 0)
    if not pts or t <= 0:
        return None
    if t <= pts[0][0]:
        return pts[0][1] * (t / pts[0][0]) ** -0.5
    if t >= pts[-1][0]:
        return pts[-1][1] * (t / pts[-1][0]) ** -0.5
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if t0 <= t <= t1:
            w = math.log(t / t0) / math.log(t1 / t0) if t1 > t0 else 0.0
            return math.exp(math.log(e0) + w * (math.log(e1) - math.log(e0)))
    return None


AUTO_TARGETS = (1.25, 1.05)  # AUTO's error at equal time: ≤ 1.25× the best single integrator's, ≤ 1.05× PATH's
NOISE_Z = 2.0                # a row fails only when its ratio exceeds the target by more than NOISE_Z σ
TIME_NOISE_MIN_SAMPLES = 16  # counts whose CPU time scatter estimates the timing noise (set-up negligible there)


def time_log_sigma(p):
    """σ of log(time) of one render: the scatter of log(time/samples) over the counts ≥ TIME_NOISE_MIN_SAMPLES
    (the cost per sample is constant there, so the scatter is the machine's load)."""
    x = [math.log(t / n) for n, t in zip(p["samples"], p["time"]) if n >= TIME_NOISE_MIN_SAMPLES and t > 0]
    if len(x) < 2:
        return 0.0
    m = sum(x) / len(x)
    return math.sqrt(sum((v - m) ** 2 for v in x) / (len(x) - 1))


def time_line_log_sigma(p):
    """σ of log(time) of one render about the straight line time ≈ t₀ + c·samples (c the Theil–Sen cost per sample,
    t₀ the median of time − c·samples), over the counts ≥ TIME_NOISE_MIN_SAMPLES: the load's scatter, also for an
    integrator with a fixed cost per render that time_log_sigma would count as scatter (the irradiance cache's
    pre-pass)."""
    c = p["cost_sequence"]
    pts = [(n, t) for n, t in zip(p["samples"], p["time"]) if n >= TIME_NOISE_MIN_SAMPLES and t > 0]
    if len(pts) < 3:
        return 0.0
    t0 = sorted(t - c * n for n, t in pts)[len(pts) // 2]
    x = [math.log(t / max(t0 + c * n, 1e-12)) for n, t in pts]
    m = sum(x) / len(x)
    return math.sqrt(sum((v - m) ** 2 for v in x) / (len(x) - 1))


def sigma_at(p, t):
    """σ of log(rel. RMSE) of a configuration at time t: the larger image noise of the two measured points t lies
    between (or of the nearest end)."""
    pts = [(x, s) for x, s in zip(p["time"], p["rrmse_sigma"]) if x > 0]
    for (t0, s0), (t1, s1) in zip(pts, pts[1:]):
        if t0 <= t <= t1:
            return max(s0, s1)
    return pts[0][1] if t <= pts[0][0] else pts[-1][1]


def same_images(a, b):
    """AUTO rendered exactly the chosen integrator's images (same seed and settings): equal errors at every count."""
    return len(a["rrmse"]) == len(b["rrmse"]) and all(
        abs(x - y) <= 1e-9 * max(abs(x), 1e-30) for x, y in zip(a["rrmse"], b["rrmse"]))


def ratio_sigma(a, b, t):
    """σ of log(e_AUTO(t) / e_other(t)). Independent images: both images' error noise and both timings' noise
    (an error at equal time moves by half the log-time error, e ∝ t^−½). AUTO rendering the other's very images:
    the image noise cancels and what is left is the scatter of half the log time ratio over the counts."""
    if same_images(a, b):
        x = [0.5 * math.log(ta / tb) for n, ta, tb in zip(a["samples"], a["time"], b["time"])
             if n >= TIME_NOISE_MIN_SAMPLES and ta > 0 and tb > 0]
        if len(x) < 2:
            return 0.0
        m = sum(x) / len(x)
        return math.sqrt(sum((v - m) ** 2 for v in x) / (len(x) - 1))
    return math.sqrt(a["rrmse_sigma"][-1] ** 2 + sigma_at(b, t) ** 2 +
                     0.25 * (time_log_sigma(a) ** 2 + time_log_sigma(b) ** 2))


def verdict(r, sigma, target):
    """pass: r ≤ target; within noise: above it by less than NOISE_Z σ (not distinguishable from meeting it);
    FAIL: above it by more."""
    if r is None:
        return "—"
    if r <= target:
        return "pass"
    return "within noise" if math.log(r / target) <= NOISE_Z * sigma else "**FAIL**"


def auto_rows(scene_names, configs, results):
    """Per scene: (markdown row, reason line, verdicts) of the acceptance table."""
    out = []
    for scene in scene_names:
        labels = [c[0] for c in configs[scene]]
        if "Candela AUTO" not in labels:
            continue
        a = results[(scene, "Candela AUTO")]
        t, e_auto = a["time"][-1], a["rrmse"][-1]   # AUTO's largest count: its time sets the equal time
        singles = {label: error_at(results[(scene, label)], t) for label in labels
                   if label.startswith("Candela ") and label != "Candela AUTO"}
        singles = {k: v for k, v in singles.items() if v}
        best = min(singles, key=singles.get) if singles else None
        path = next((k for k in ("Candela PATH SOBOL", "Candela PATH") if k in singles), None)
        if path is None:
            path = next((k for k in singles if k.startswith("Candela PATH")), None)
        cycles = error_at(results[(scene, "Cycles")], t) if "Cycles" in labels else None
        last = a["runs"][-1] if a.get("runs") else {}
        share = (last["analysis_ms"] / 1e3 / last["wall_seconds"]
                 if last.get("analysis_ms") is not None and last.get("wall_seconds") else None)

        def judged(label, target):
            if not label or not e_auto:
                return "—", "—"
            r = e_auto / singles[label]
            sig = ratio_sigma(a, results[(scene, label)], t)
            if not math.isfinite(sig):   # an error figure not above the reference's own noise
                return f"{r:.2f} ×/÷ ∞ (reference noise)", verdict(r, sig, target)
            return f"{r:.2f} ×/÷ {math.exp(sig):.2f}", verdict(r, sig, target)
        r_best, v_best = judged(best, AUTO_TARGETS[0])
        r_path, v_path = judged(path, AUTO_TARGETS[1])
        r_cyc = f"{e_auto / cycles:.2f}" if e_auto and cycles else "—"
        others = ", ".join(f"{k[len('Candela '):]} {v:.3g}" for k, v in sorted(singles.items(), key=lambda kv: kv[1]))
        row = (f"| {scene} | {last.get('choice', '?')} | {e_auto:.3g} | {others} | {r_best} ({(best or '—')[8:]}) | "
               f"{v_best} | {r_path} | {v_path} | {r_cyc} | {'—' if share is None else f'{100 * share:.1f} %'} |")
        out.append((scene, row, f"- {scene}: {last.get('method', '?')}", (v_best, v_path)))
    return out


def auto_table(scene_names, configs, results):
    """The acceptance table of issue 19 (docs/auto.md): per scene, AUTO's choice, its rel. RMSE at equal time (its
    own time at its largest sample count) divided by the best single Candela integrator's, by PATH's (the default
    sampler's) and by Cycles', each against its target with a verdict, and the analysis (static features + pilot)
    as a share of that render's wall time. Accuracy scenes and held-out scenes in separate tables."""
    rows = auto_rows(scene_names, configs, results)
    if not rows:
        return []
    held, held_2 = set(held_out_scenes("HELD_OUT")), set(held_out_scenes("HELD_OUT_2"))
    head = ["| scene | AUTO's choice | AUTO rel. RMSE | each integrator's rel. RMSE at AUTO's time | ratio to best "
            f"(which) | ≤ {AUTO_TARGETS[0]}× best | ratio to PATH | ≤ {AUTO_TARGETS[1]}× PATH | ratio to Cycles "
            "| analysis share |", "|---|---|---|---|---|---|---|---|---|---|"]
    md = ["## AUTO at equal time", "",
          "Issue 19's acceptance table: AUTO's relative RMSE at its own time for the largest sample count, divided "
          "by each configuration's at the same time (log-log interpolation between its measured points, slope −0.5 "
          f"beyond them); targets ≤ {AUTO_TARGETS[0]}× the best single integrator's and ≤ {AUTO_TARGETS[1]}× "
          "PATH's (the default sampler). The analysis share is AUTO's logged analysis time (static features and "
          "pilot) over that render's wall time; the pilot's time is in AUTO's time (its set-up is PATH's, so "
          "nothing of the analysis is subtracted as set-up).", "",
          "**Noise.** Each ratio is given as r ×/÷ f, f = e^σ with σ the standard error of log r: for two "
          "independent images, σ² = σ_A² + σ_B² + ¼(τ_A² + τ_B²), where σ_X is the standard error of log(rel. RMSE) "
          "of X's image (from the scatter of the squared error over 2 × 2-pixel tiles, "
          "`accuracy_stats.rrmse_log_sigma`) and τ_X the scatter of X's log(time per sample) over its counts ≥ "
          f"{TIME_NOISE_MIN_SAMPLES} (the load; an error at equal time moves by half the log-time error). When AUTO "
          "rendered the very images of the integrator it is compared with (same seed, same integrator: equal errors "
          "at every count) the image noise cancels and σ is the scatter of ½ log(time ratio) over the counts ≥ "
          f"{TIME_NOISE_MIN_SAMPLES}. Verdict: *pass* if r ≤ target; *within noise* if r exceeds the target by "
          f"less than {NOISE_Z:g} σ (a false FAIL rate of about 2 % per row for an AUTO exactly on target); "
          f"**FAIL** beyond. The best single integrator is the minimum of noisy estimates, so the ratio to it is "
          "biased slightly high where two integrators are close.", ""]
    for title, names in (("Accuracy scenes (the policy's rules were written and tuned on these)",
                          [r for r in rows if r[0] not in held | held_2]),
                         ("Held-out scenes (examples/scenes.py HELD_OUT: used to tune the caustic rule since)",
                          [r for r in rows if r[0] in held]),
                         ("Second held-out set (examples/scenes.py HELD_OUT_2: not used for tuning)",
                          [r for r in rows if r[0] in held_2])):
        if not names:
            continue
        md += [f"### {title}", "", *head, *(r[1] for r in names), ""]
        met = sum(1 for r in names if "FAIL" not in r[3][0] and "FAIL" not in r[3][1])
        md += [f"Both targets met (pass or within noise) on {met} of {len(names)} scenes.", ""]
    md += ["AUTO's status line per scene:", "", *(r[2] for r in rows), ""]
    if MEASURED:
        md += ["Read back with --reuse (measured by an earlier invocation into the same work directory; every "
               "configuration of a scene always comes from one invocation, round-robin): " +
               "; ".join(f"{k} at {w} by build {b}" for k, (w, b) in MEASURED.items()) +
               f". Measured by this invocation (build {build_fingerprint()}): " +
               (", ".join(k for k in scene_names if k not in MEASURED) or "none") + ".", ""]
    return md

if __name__ == "__main__":
    main()
