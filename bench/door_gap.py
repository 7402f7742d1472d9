"""Who is right on the door ajar (issue 22, item 4): the mean brightness of door-gap scene variants rendered by Cycles
and by Candela's PATH and BDPT, each as R independent seeds, with the standard error from the replicates and the z of
every difference.

    /usr/bin/python3.11 bench/door_gap.py [--build build] [--variants slit_thin,door,...] [--size 64] [--seeds 8]
                                          [--seed-base 1] [--engines CYCLES:2048,PATH:2048,BDPT:512] [--out DIR]
                                          [--reuse] [--docs docs]

`make door-gap` runs the default variants and writes docs/door_gap.md (about 20 minutes idle). Each variant
renders in one Blender process (bench/door_gap_render.py); each render's luminance image mean is one replicate.
Per engine: mean m, standard error s = sd/√R (R − 1 degrees of freedom); per pair, z = (m₁ − m₂)/√(s₁² + s₂²);
against the exact value, z = (m − exact)/s. Image means of ≥ 10⁵ samples are close to normal, but with R = 8 a |z|
of 3 still has a false-alarm probability near 1–2 % (Student t, 7–14 degrees of freedom), not 0.3 %: the report
prints the two-sided Student (Welch) p-value beside z.
"""

import argparse
import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT / "tests" / "parity"))
import parity_stats as ps  # noqa: E402  (luminance, Student-t quantiles)


DEFAULT_VARIANTS = ["slit_thin", "slit_thin_far100", "slit_thin_far1000", "slit_slab", "slit_boxes", "slit_rug", "door",
                    "ajar8_trim", "ajar8_sunk"]
# Per kind of variant: image width and samples per render per engine, for standard errors near 0.1–0.2 % on the slit
# and 0.3–1.4 % on the door (PATH and Cycles need ~16× BDPT's samples there for equal noise).
SLIT_RUN = (48, "CYCLES:512,PATH:1024,BDPT:512")
DOOR_RUN = (64, "CYCLES:2048,PATH:2048,BDPT:512")


def run_settings(a, variant):
    size, engines = SLIT_RUN if variant.startswith("slit_") else DOOR_RUN
    return a.size or size, a.engines or engines


def run_variant(a, variant, out):
    seeds = ",".join(str(a.seed_base + i) for i in range(a.seeds))
    size, engines = run_settings(a, variant)
    cmd = [str(ROOT / "bin" / "candela-blender"), "-b", "--factory-startup", "-noaudio", "--python-exit-code", "1",
           "--python", str(HERE / "door_gap_render.py"), "--", "--variant", variant, "--size", str(size),
           "--seeds", seeds, "--engines", engines, "--threads", str(a.threads),
           "--out", str(out)]
    for kv in a.set:
        cmd += ["--set", kv]
    env = dict(os.environ, CANDELA_SCRIPTS_DIR=str(Path(a.build).resolve() / "scripts"))
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    for line in proc.stdout.splitlines():
        if line.startswith("DOOR_GAP_JSON "):
            result = json.loads(line[len("DOOR_GAP_JSON "):])
            (out / "run.json").write_text(json.dumps(result))
            return result
    raise RuntimeError(f"door_gap_render failed for {variant}:\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}")


def welch_p(m1, s1, n1, m2, s2, n2):
    """Two-sided p-value of m1 − m2 under Welch's t with Satterthwaite's degrees of freedom."""
    v = s1 ** 2 + s2 ** 2
    if not v > 0:
        return float("nan")
    nu = v ** 2 / (s1 ** 4 / (n1 - 1) + s2 ** 4 / (n2 - 1))
    return 2.0 * ps._t_tail(abs(m1 - m2) / math.sqrt(v), nu)


# Variants compared seed by seed with a base variant (paired_differences).
PAIRS = {"slit_thin_far100": "slit_thin", "slit_thin_far1000": "slit_thin", "slit_rug": "slit_slab",
         "slit_boxes": "slit_slab", "slit_overlap": "slit_slab", "ajar8_trim": "door",
         "ajar8_sunk": "door", "ajar8": "door"}


def exact_mean(variant):
    """The closed-form image mean of the slit variants (bench/door_gap_analytic.py), None for the door scenes."""
    if not variant.startswith("slit_"):
        return None
    import door_gap_analytic as an
    return an.mean(slab=0.0 if variant.split("_")[1] == "thin" else an.SLAB)


def summarise(result, native, vout):
    rows = {}
    for engine, r in result["renders"].items():
        files = [vout / Path(f).name for f in r["exr"]]   # the run folder may have moved
        means = np.array([float(ps.luminance(native.read_exr(str(f))).mean()) for f in files])
        seeds = [int(f.stem.rsplit("seed", 1)[1]) for f in files]
        rows[engine] = {"means": means.tolist(), "mean": float(means.mean()), "seeds": [min(seeds), max(seeds)],
                        "se": float(means.std(ddof=1) / math.sqrt(len(means))), "n": len(means),
                        "seconds": float(sum(r["seconds"])), "samples": r.get("samples", result["samples"])}
    return rows


def comparisons(variant, rows):
    """(label, ratio − 1, z, p) of every engine pair and of every engine against the exact value."""
    out = []
    engines = list(rows)
    exact = exact_mean(variant)
    if exact is not None:
        for e in engines:
            r = rows[e]
            z = (r["mean"] - exact) / r["se"]
            out.append((f"{e} / exact", r["mean"] / exact - 1, z, 2.0 * ps._t_tail(abs(z), r["n"] - 1)))
    for i, e1 in enumerate(engines):
        for e2 in engines[i + 1:]:
            r1, r2 = rows[e1], rows[e2]
            z = (r1["mean"] - r2["mean"]) / math.hypot(r1["se"], r2["se"])
            out.append((f"{e1} / {e2}", r1["mean"] / r2["mean"] - 1, z,
                        welch_p(r1["mean"], r1["se"], r1["n"], r2["mean"], r2["se"], r2["n"])))
    return out


def paired_differences(report):
    """(variant, base, engine, relative difference, its standard error, z) for PAIRS present with equal seeds: the
    same seeds trace the same paths wherever the two variants' geometry agrees, so the per-seed differences have
    far less noise than either mean."""
    out = []
    for v, b in PAIRS.items():
        if v not in report or b not in report:
            continue
        for e, r in report[v].items():
            base = report[b].get(e)
            if base is None or base["n"] != r["n"]:
                continue
            d = np.array(r["means"]) - np.array(base["means"])
            se = float(d.std(ddof=1) / math.sqrt(len(d)))
            z = float(d.mean()) / se if se > 0 else (0.0 if d.mean() == 0 else math.inf)
            out.append((v, b, e, float(d.mean()) / base["mean"], se / base["mean"], z))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--variants", default=",".join(DEFAULT_VARIANTS))
    ap.add_argument("--size", type=int, default=None, help="image width (default: 48 for the slit, 64 the door)")
    ap.add_argument("--seeds", type=int, default=8, help="independent renders per engine")
    ap.add_argument("--seed-base", type=int, default=1, help="the seeds are SEED_BASE, SEED_BASE + 1, ...")
    ap.add_argument("--engines", default=None,
                    help=f"NAME:SAMPLES, comma-separated (default {SLIT_RUN[1]} for the slit, {DOOR_RUN[1]} the door)")
    ap.add_argument("--set", action="append", default=[], help="Candela property key=value")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default=None)
    ap.add_argument("--reuse", action="store_true", help="re-analyse the renders of a previous run in OUT")
    ap.add_argument("--docs", default=None, help="also write DOCS/door_gap.md")
    a = ap.parse_args(argv)
    out = Path(a.out or Path(a.build) / "door_gap")
    sys.path.insert(0, str(Path(a.build) / "scripts" / "addons" / "candela"))
    import _native  # noqa: E402
    report, sizes = {}, {}
    for variant in a.variants.split(","):
        vout = out / variant
        vout.mkdir(parents=True, exist_ok=True)
        result = json.loads((vout / "run.json").read_text()) if a.reuse else run_variant(a, variant, vout)
        rows = summarise(result, _native, vout)
        report[variant], sizes[variant] = rows, result["size"]
        print(f"{variant}: {result['size'][0]}x{result['size'][1]} px"
              + (f", exact {exact_mean(variant):.6f}" if exact_mean(variant) is not None else ""))
        for e, r in rows.items():
            print(f"  {e:8s} {r['n']:2d} x {r['samples']:5d} spp  mean {r['mean']:.6f} ± {r['se']:.6f} "
                  f"({100 * r['se'] / r['mean']:.2f} %), {r['seconds']:.0f} s")
        for label, rel, z, p in comparisons(variant, rows):
            print(f"  {label:18s} - 1 = {100 * rel:+.2f} %  z = {z:+.2f}  p = {p:.3g}")
    for v, b, e, rel, se, z in paired_differences(report):
        print(f"paired {v} - {b}, {e}: {100 * rel:+.3f} % ± {100 * se:.3f} %  z = {z:+.2f}")
    (out / "summary.json").write_text(json.dumps(report, indent=1))
    if a.docs:
        import door_gap_docs
        door_gap_docs.write(Path(a.docs), report, sizes, comparisons, paired_differences(report), exact_mean)


if __name__ == "__main__":
    main()
