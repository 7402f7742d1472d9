"""`make sampling-docs`: docs/sampling.md, what each sampling technique of the path tracer buys.

    /usr/bin/python3.11 examples/sampling_gallery.py [--quick] [--build build] [--out DIR] [--docs docs]
                                                     [--size 128] [--threads 2]

For every technique (pixel samplers, hemisphere sampling, BSDF/light/MIS direct lighting with both heuristics,
light pdfs, light selection on a many-light scene, branching factor, Russian roulette) it renders one scene of
examples/scenes.py at the SAME sample count with only that setting changed (everything else at Candela's
defaults), and reports the picture, its relative RMSE against a converged reference of the same scene, the
render time, and the efficiency 1/(RMSE²·time) relative to the default setting (how much faster the technique
reaches a given error; Monte Carlo error² falls as 1/time, so this ratio does not depend on the sample count).

The error is that of what the picture shows: luminance clipped to the display range [0, 1] (Blender's Standard
view), so that the directly visible lights of Veach's scene (radiance up to 8000) do not drown the noise of the
plates; the reference's own noise (from its two independent halves) is subtracted. The time is the fastest of three
identical renders (the machine may be shared).

The renders go through Blender with the add-on (bench/accuracy_render.py, one Blender process per scene); the
cached two-half references and the Blender runner are bench/accuracy.py's.
Writes DOCS/sampling.md and DOCS/sampling/*.png. --quick (a ctest) renders tiny images of two sections into OUT
only, to check the pipeline, not the numbers.
"""

import argparse
import datetime
import math
import re
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "bench"))
import accuracy  # noqa: E402  (run_blender, reference, native_module, build_fingerprint, machine)
import accuracy_stats  # noqa: E402  (luminance)

# Each section: one setting swept over its values on one scene at one sample count; `default` is Candela's
# default value (the efficiency baseline). Values may be (label, {setting: value, ...}) for combined settings.
SECTIONS = [
    {"id": "sampler", "title": "Pixel samplers", "scene": "soft_shadow", "samples": 16, "default": "SOBOL",
     "values": ["RANDOM", "STRATIFIED", "NROOKS", "HALTON", "HAMMERSLEY", "SOBOL"],
     "text": "Where the sample values come from. Independent random numbers (RANDOM) clump and leave gaps; "
             "jittered strata (STRATIFIED), Latin hypercubes (NROOKS) and the low-discrepancy Halton, Hammersley and "
             "Owen-scrambled Sobol sequences spread them evenly, which pays off most in the penumbra (a 2-D light "
             "integral) and on edges (the pixel area)."},
    {"id": "hemisphere_sampling", "title": "Hemisphere sampling (continuation directions)", "scene": "cornell_box",
     "samples": 16, "default": "BSDF", "values": ["UNIFORM", "COSINE", "BSDF"],
     "text": "How the next direction of a path is drawn at a diffuse or glossy surface: uniformly over the "
             "hemisphere, proportional to cos θ, or proportional to the BSDF times cos θ (the same as cosine on "
             "the Cornell box's Lambertian walls). Importance sampling the cosine removes a factor from the "
             "estimator's variance for free."},
    {"id": "light_sampling", "title": "Direct light: BSDF sampling, light sampling and MIS (Veach's scene)",
     "scene": "veach_mis", "samples": 16, "default": "MIS (power)",
     "values": [("BSDF only", {"light_sampling": "BSDF_ONLY"}), ("light only", {"light_sampling": "LIGHT_ONLY"}),
                ("MIS (balance)", {"light_sampling": "MIS", "mis_heuristic": "BALANCE"}),
                ("MIS (power)", {"light_sampling": "MIS", "mis_heuristic": "POWER"})],
     "text": "Veach's four plates (smooth at the back, rough at the front) under four lights of equal power. "
             "Sampling the BSDF finds the small lights in the smooth plates' narrow reflections but rarely hits "
             "them from the rough plates; sampling the lights (next-event estimation) is the opposite. Multiple "
             "importance sampling weights both estimates by their densities and keeps the better one everywhere "
             "(tests/native/veach_mis_test.cpp measures it: MIS has the least variance on every plate)."},
    {"id": "light_pdf", "title": "Light pdf: area or solid angle", "scene": "soft_shadow", "samples": 16,
     "default": "SOLID_ANGLE", "values": ["AREA", "SOLID_ANGLE"],
     "text": "How a point on an area light is drawn: uniformly over its area (a density in solid angle of "
             "d²/(A cos θ), poor for large lights seen up close or at grazing angles) or uniformly over the solid "
             "angle it subtends (spherical rectangles and triangles)."},
    {"id": "light_selection", "title": "Light selection (64 lights)", "scene": "many_lights", "samples": 16,
     "default": "TREE", "values": ["ALL", "UNIFORM", "AREA", "POWER", "TREE", "WARD"],
     "text": "Which light a shadow ray goes to when there are many: every light (ALL, one shadow ray each: exact "
             "but costly), one chosen uniformly, by area, by power, by a light tree that bounds each cluster's "
             "contribution at the shading point (position, orientation, power), or Ward's method (sort the lights "
             "by their largest possible contribution and shadow-test only until the untested rest is negligible). "
             "The lights here are points of equal radius, so AREA picks them uniformly too."},
    {"id": "branching_factor", "title": "Branching factor (stochastic ray tracing)", "scene": "cornell_box",
     "samples": 16, "default": 1, "values": [1, 2, 4],
     "text": "Continuation rays at the first surface: 1 is path tracing; more rays per camera ray spend more time "
             "on indirect light and less on the pixel area and the first bounce."},
    {"id": "rr_mode", "title": "Russian roulette", "scene": "cornell_box", "samples": 16, "default": "THROUGHPUT",
     "values": ["OFF", "THROUGHPUT", "ALBEDO", "SQRT_THROUGHPUT"],
     "text": "Ending paths early without bias: OFF traces every path to the bounce limit; THROUGHPUT continues "
             "with the probability of the path's throughput; ALBEDO with the surface's reflectance; "
             "SQRT_THROUGHPUT (Cycles' rule) decides on arrival at a vertex, before its shadow rays, with "
             "the square root of the throughput."},
]

QUICK_SECTIONS = ["sampler", "light_sampling"]


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="pipeline check: tiny images, two sections, no docs")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--out", default=None, help="work directory and reference cache (default BUILD/sampling)")
    ap.add_argument("--docs", default=str(ROOT / "docs"))
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--ref-samples", type=int, default=512, help="samples per pixel of each scene's reference")
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    if a.quick:
        a.size, a.ref_samples = 24, 16
    a.out = Path(a.out or Path(a.build) / ("sampling-quick" if a.quick else "sampling"))
    return a


def variants(section):
    """[(label, tag, [(key, value), ...])] of a section."""
    out = []
    for v in section["values"]:
        label, settings = v if isinstance(v, tuple) else (str(v), {section["id"]: v})
        tag = f"{section['id']}_{label}".replace(" ", "_").replace("(", "").replace(")", "")
        out.append((label, tag, list(settings.items())))
    return out


def srgb8(rgba):
    """Linear RGB → 8-bit sRGB (Blender's Standard view), top row first (the EXR's row 0 is the bottom)."""
    rgb = np.clip(rgba[::-1, :, :3], 0.0, 1.0)
    srgb = np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * np.power(rgb, 1 / 2.4) - 0.055)
    return (srgb * 255 + 0.5).astype(np.uint8)


def to_png(rgba, path, zoom=2):
    """The picture with each pixel drawn zoom × zoom times (nearest neighbour), so the noise stays visible."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    plt.imsave(path, np.repeat(np.repeat(srgb8(rgba), zoom, axis=0), zoom, axis=1))


def veach_triple(images, labels, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(images), figsize=(4.0 * len(images), 4.0 * images[0].shape[0] / images[0].shape[1] + 0.5))
    for ax, img, label in zip(axes, images, labels):
        ax.imshow(img, interpolation="nearest")
        ax.set_title(label, fontsize=11)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def display_error(rgba, halves):
    """Relative RMSE of the display-clipped luminance against the mean of the reference halves, minus the
    reference's own noise: Var(mean of halves) = E[(a − b)²]/4 per pixel."""
    def shown(img):
        return np.clip(accuracy_stats.luminance(img), 0.0, 1.0)
    a, b = shown(halves[0]), shown(halves[1])
    ref = 0.5 * (a + b)
    mse = float(np.mean((shown(rgba) - ref) ** 2)) - float(np.mean((a - b) ** 2)) / 4.0
    return math.sqrt(max(mse, 0.0)) / max(float(np.mean(ref)), 1e-12)


def main():
    args = parse_args()
    # bench/accuracy.py's helpers read their settings from its module-level ARGS.
    accuracy.ARGS = argparse.Namespace(build=args.build, out=args.out, size=args.size, threads=args.threads,
                                       reference_integrator={}, reuse=False, default_reference=False)
    native = accuracy.native_module()
    started = time.time()
    sections = [s for s in SECTIONS if not args.quick or s["id"] in QUICK_SECTIONS]
    if args.quick:
        for s in sections:
            s["samples"] = 2
            s["values"] = s["values"][:2]
    docs = args.out if args.quick else Path(args.docs)
    pictures = docs / "sampling"
    pictures.mkdir(parents=True, exist_ok=True)
    renders = args.out / "renders"

    results = {}   # tag -> (rgba, seconds, relative error)
    for scene in dict.fromkeys(s["scene"] for s in sections):   # scenes in order, each once
        accuracy.reference(scene, "CANDELA", args.ref_samples)   # renders and caches the two halves
        key = f"{scene}_CANDELA_{args.size}_{args.ref_samples}_{accuracy.build_fingerprint()}"
        halves = [native.read_exr(str(args.out / "cache" / f"{key}_{i}.exr")) for i in (0, 1)]
        to_png(0.5 * (halves[0] + halves[1]), pictures / f"{scene}_reference.png")
        mine = [s for s in sections if s["scene"] == scene]
        counts = sorted({s["samples"] for s in mine})
        assert len(counts) == 1, "one sample count per scene (one Blender process renders them all)"
        # Each variant three times (the same image): the fastest time counts.
        cli = ["--scene", scene, "--engine", "CANDELA", "--counts", ",".join([str(counts[0])] * 3), "--size",
               str(args.size), "--threads", str(args.threads), "--out", str(renders), "--tag", scene]
        for s in mine:
            for _, tag, settings in variants(s):
                cli += ["--variant", tag + ":" + ",".join(f"{k}={v}" for k, v in settings)]
        res = accuracy.run_blender(cli, args.out / f"{scene}.log")
        for run in res["runs"]:
            if run["variant"] in results:
                rgba, seconds, err = results[run["variant"]]
                results[run["variant"]] = (rgba, min(seconds, run["seconds"]), err)
                continue
            rgba = native.read_exr(run["exr"])
            results[run["variant"]] = (rgba, run["seconds"], display_error(rgba, halves))
        print(f"sampling-docs: {scene} done ({time.time() - started:.0f} s)", flush=True)

    md = ["# What each sampling technique buys", "",
          "Generated by `make sampling-docs` (`examples/sampling_gallery.py`); do not edit by hand.", "",
          f"Measured on {accuracy.machine()}, {args.threads} render threads, "
          f"{datetime.datetime.now().strftime('%Y-%m-%d %H:%M')}. Images {args.size} px wide, rendered through "
          "Blender with the add-on. In each section one setting changes and everything else stays at Candela's "
          "defaults (Sobol sampler, BSDF hemisphere sampling, MIS with the power heuristic, solid-angle light pdf, "
          "light tree, branching factor 1, throughput roulette, 12 bounces).", "",
          "*Error* is the relative RMSE of what the picture shows (luminance clipped to the display range, so "
          "that directly visible lights do not dominate) against a converged reference of the same scene "
          f"({args.ref_samples} samples per pixel, its own noise subtracted); *time* is the render time without "
          "scene export, the fastest of three identical renders; *efficiency* is 1/(error²·time) relative to the "
          "default setting: 2× means the technique "
          "reaches any given error in half the default's time. Monte Carlo error² falls as 1/time, so the "
          "efficiency does not depend on the sample count (low-discrepancy samplers converge faster than that, "
          "so theirs grows with it). The errors come from one image each (about 1 % uncertainty); the times vary by "
          "10–20 % between runs on a shared machine, and so does the efficiency. The pictures show the noise a "
          "student should learn to recognise.", ""]
    for s in sections:
        md += [f"## {s['title']}", "", s["text"], "",
               f"Scene `{s['scene']}`, {s['samples']} samples per pixel. "
               f"Reference: [{s['scene']}](sampling/{s['scene']}_reference.png).", "",
               "| setting | picture | error | time | efficiency |", "|---|---|---|---|---|"]
        base = next((results[tag] for label, tag, _ in variants(s) if label == str(s["default"])), None)
        for label, tag, _ in variants(s):
            rgba, seconds, rmse = results[tag]
            png = f"{tag}.png"
            to_png(rgba, pictures / png)
            eff = "—"
            if base and rmse > 0 and seconds > 0:
                eff = f"{(base[2] ** 2 * base[1]) / (rmse ** 2 * seconds):.2f}×"
            name = f"**{label}**" if label == str(s["default"]) else label
            md.append(f"| {name} | ![{label}](sampling/{png}) | {100 * rmse:.1f} % | {seconds:.2f} s | {eff} |")
        md.append("")
        if s["id"] == "light_sampling":
            triple = [v for v in variants(s) if v[0] in ("BSDF only", "light only", "MIS (power)")]
            if len(triple) == 3:
                images = [srgb8(results[tag][0]) for _, tag, _ in triple]
                veach_triple(images, [f"{label}: {100 * results[tag][2]:.0f} % error" for label, tag, _ in triple],
                             pictures / "veach_triple.png")
                md += ["Veach's triple at the same sample count: BSDF sampling only, light sampling only, MIS.", "",
                       "![Veach: BSDF only, light only, MIS](sampling/veach_triple.png)", ""]
    md += [f"The whole run took {time.time() - started:.0f} s.", ""]
    (docs / "sampling.md").write_text("\n".join(md))
    missing = [p for p in re.findall(r"\((sampling/[^)]+\.png)\)", "\n".join(md)) if not (docs / p).exists()]
    if missing:
        raise RuntimeError(f"sampling.md links pictures that were not written: {missing}")
    print(f"sampling-docs: wrote {docs / 'sampling.md'} in {time.time() - started:.0f} s")


if __name__ == "__main__":
    main()
