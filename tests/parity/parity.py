"""The parity suite: Candela against Cycles 3.4 on scenes made by scripts (tests/parity/parity_scenes.py).

    /usr/bin/python3.11 tests/parity/parity.py [--quick] [--build build] [--out DIR] [--docs docs]
                                               [--size 160] [--samples 1024] [--scenes a,b] [--threads 2]

For every scene both engines render in one Blender process (tests/parity/render_pair.py: same settings mirrored
on both sides, each engine twice with independent seeds), then this script requires, per RGB channel, the image
mean within 2 % and each of the 4 × 4 block means within 5 % (dark blocks: an absolute tolerance), each widened
by the measured noise (tests/parity/parity_stats.py derives it). It writes to OUT:
  SCENE.png        Cycles | Candela | difference, side by side (same exposure for both renders)
  summary.md       one table row per scene
  summary.json     every number of every check
and with --docs DIR also DIR/parity.md plus DIR/parity/SCENE.png (what `make parity` commits as docs/parity.md).
Exit status 1 when a check fails or a render failed.

--quick (`make test`): small images, few samples, the scenes marked quick — a pipeline check and a coarse
brightness check whose tolerance is wider only by the larger measured noise.

--nodes: the per-node scenes instead (tests/parity/node_scenes.py: one texture or input node feeding an Emission
shader): image mean within 1 % and each of 8 × 8 block means within 3 %, widened by the measured noise as above;
with --docs, DOCS/parity_nodes.md and DOCS/parity/nodes/. `make test` runs `--nodes --quick` too.
"""

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))
sys.path.insert(1, str(ROOT / "bench"))

import parity_stats as ps  # noqa: E402
from accuracy import machine  # noqa: E402  (the machine line every generated report shows)

FULL_SIZE, FULL_SAMPLES = 144, 512
QUICK_SIZE, QUICK_SAMPLES = 48, 64
# The scenes of parity_scenes.SCENES, in order (a full run checks that the lists agree); QUICK_SCENES run in
# `make test`.
ALL_SCENES = ["point", "point_radius", "spot_blend", "sun_angle", "area_square", "area_rect", "area_disk",
              "area_ellipse", "emissive_quad", "cornell_area_light", "cornell_emissive_quad",
              "cornell_quad_near_ceiling", "principled_spheres", "environment", "glossy_cycles_defaults",
              "glass_cycles_defaults", "moving_cube", "camera_pan"]
# Scenes left out of the quick run (none: the two that waited for path tracer fixes, cornell_area_light and
# cornell_quad_near_ceiling, pass since camera rays skip camera-hidden lights and shadow rays aim from the offset
# origin at the light point).
PENDING = set()
QUICK_SCENES = [s for s in ALL_SCENES if s not in PENDING]
# The per-node suite (--nodes): tolerances of issue 21.
NODE_REL_IMAGE, NODE_REL_BLOCK, NODE_GRID = 0.01, 0.03, 8
NODE_QUICK_SIZE, NODE_QUICK_SAMPLES = 48, 32


def parse_args(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="small images, few samples, the quick scenes")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--out", default=None, help="output folder (default BUILD/parity or BUILD/parity-quick)")
    ap.add_argument("--docs", default=None, help="also write DOCS/parity.md and DOCS/parity/*.png")
    ap.add_argument("--size", type=int, default=None, help=f"image width (default {FULL_SIZE}, quick {QUICK_SIZE})")
    ap.add_argument("--samples", type=int, default=None,
                    help=f"samples per pixel per engine, over two seeds (default {FULL_SAMPLES}, quick {QUICK_SAMPLES})")
    ap.add_argument("--scenes", default=None, help="comma-separated scene names (default: all, or the quick ones)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--integrator", default="PATH",
                    help="Candela's integrator; other than PATH, the docs are DOCS/parity_<name>.md and parity/<name>/")
    ap.add_argument("--reuse", action="store_true", help="re-analyse the renders of a previous run in OUT")
    ap.add_argument("--nodes", action="store_true", help="the per-node scenes (tests/parity/node_scenes.py)")
    a = ap.parse_args(argv)
    if a.nodes:
        import node_scenes  # noqa: E402  (plain Python: the scene list, no bpy needed to read it)
        a.size = a.size or (NODE_QUICK_SIZE if a.quick else FULL_SIZE)
        a.samples = a.samples or (NODE_QUICK_SAMPLES if a.quick else 128)
        a.full_list = False
        a.scenes = a.scenes.split(",") if a.scenes else (
            node_scenes.QUICK_NODE_SCENES if a.quick else list(node_scenes.NODE_SCENES))
        a.out = Path(a.out or Path(a.build) / ("parity-nodes-quick" if a.quick else "parity-nodes"))
        a.rel_image, a.rel_block, a.grid = NODE_REL_IMAGE, NODE_REL_BLOCK, NODE_GRID
        return a
    a.size = a.size or (QUICK_SIZE if a.quick else FULL_SIZE)
    a.samples = a.samples or (QUICK_SAMPLES if a.quick else FULL_SAMPLES)
    a.full_list = not a.scenes and not a.quick
    a.scenes = a.scenes.split(",") if a.scenes else (QUICK_SCENES if a.quick else ALL_SCENES)
    suffix = "" if a.integrator == "PATH" else "-" + a.integrator.lower()
    a.out = Path(a.out or Path(a.build) / (("parity-quick" if a.quick else "parity") + suffix))
    a.rel_image, a.rel_block, a.grid = ps.REL_IMAGE, ps.REL_BLOCK, ps.GRID
    return a


def native_module(build):
    sys.path.insert(0, str(Path(build) / "scripts" / "addons" / "candela"))
    import _native
    return _native


def render_all(a):
    """Run tests/parity/render_pair.py in Blender; returns its JSON (cached in OUT/renders.json for --reuse)."""
    cache = a.out / "renders.json"
    if a.reuse and cache.exists():
        return json.loads(cache.read_text())
    cmd = [str(ROOT / "bin" / "candela-blender"), "-b", "--factory-startup", "-noaudio", "--python-exit-code", "1",
           "--python", str(HERE / "render_pair.py"), "--", "--scenes", ",".join(a.scenes), "--size", str(a.size),
           "--samples", str(a.samples), "--threads", str(a.threads), "--out", str(a.out / "exr"),
           "--integrator", a.integrator]
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env["CANDELA_SCRIPTS_DIR"] = str(Path(a.build) / "scripts")
    log = a.out / "blender.log"
    print("parity: rendering " + ", ".join(a.scenes) + f" at {a.size} px, {a.samples} spp per engine", flush=True)
    t0 = time.time()
    with open(log, "w") as f:
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env)
        f.write(proc.stdout)
    elapsed = time.time() - t0
    for line in proc.stdout.splitlines():
        if line.startswith("parity: "):
            print("  " + line[len("parity: "):], flush=True)
    if proc.returncode != 0:
        raise RuntimeError(f"Blender failed (exit {proc.returncode}); see {log}")
    for line in proc.stdout.splitlines():
        if line.startswith("PARITY_JSON "):
            result = json.loads(line[len("PARITY_JSON "):])
            result["blender_seconds"] = elapsed
            result["rendered"] = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
            cache.write_text(json.dumps(result, indent=1))
            return result
    raise RuntimeError(f"no result from Blender; see {log}")


# ---------------------------------------------------------------------------------------------------------------
# Pictures
# ---------------------------------------------------------------------------------------------------------------

def _srgb(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def picture(path, name, cycles, candela, result, dpi=100, grid=ps.GRID):
    """Cycles | Candela | difference (luminance, (Candela − Cycles)/image mean, 3 × 3 pixel box average to calm
    the noise), with every block's Candela/Cycles luminance ratio written on it (red: a failed check)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lum_c = ps.luminance(cycles)
    # One exposure for both: the Cycles image's 99th percentile luminance maps to 0.9 (display sRGB, Standard).
    exposure = 0.9 / max(float(np.percentile(lum_c, 99)), 1e-8)
    height, width = lum_c.shape
    diff = (ps.luminance(candela) - lum_c) / max(float(lum_c.mean()), 1e-12)
    pad = np.pad(diff, 1, mode="edge")
    smooth = sum(pad[dy:dy + height, dx:dx + width] for dy in range(3) for dx in range(3)) / 9.0
    scale = 280.0 / width                     # every panel about 280 px wide, whatever the render size
    fig, axes = plt.subplots(1, 3, figsize=(3 * width * scale / dpi + 0.8, height * scale / dpi + 0.7), dpi=dpi)
    for ax, img, title in ((axes[0], cycles, "Cycles 3.4"), (axes[1], candela, "Candela")):
        ax.imshow(_srgb(img[..., :3] * exposure), origin="lower", interpolation="nearest")
        ax.set_title(title, fontsize=9)
    im = axes[2].imshow(smooth, origin="lower", cmap="RdBu_r", vmin=-0.2, vmax=0.2, interpolation="nearest")
    axes[2].set_title("(Candela − Cycles) / mean, ±20 %", fontsize=9)
    for block in result["blocks"]:
        r, c = int(block["region"][-2]), int(block["region"][-1])
        cy = lum(block["cycles"])
        ratio = lum(block["candela"]) / cy if cy > 0 else float("nan")
        dark = all(block["dark"])
        text = "dark" if dark else f"{ratio:.3f}"
        x = (c + 0.5) * width / grid
        y = (grid - 1 - r + 0.5) * height / grid
        axes[2].text(x, y, text, ha="center", va="center", fontsize=7 if grid <= 4 else 4,
                     color="red" if not block["pass"] else "black")
    for ax in axes:
        ax.set_xticks([])
        ax.set_yticks([])
    for k in range(1, grid):
        axes[2].axhline(k * height / grid - 0.5, color="grey", lw=0.4)
        axes[2].axvline(k * width / grid - 0.5, color="grey", lw=0.4)
    fig.colorbar(im, ax=axes[2], fraction=0.046, pad=0.02)
    verdict = "PASS" if result["pass"] else "FAIL"
    fig.suptitle(f"{name}: image mean ratio {lum(result['image']['candela']) / lum(result['image']['cycles']):.4f} "
                 f"— {verdict}", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    try:   # a 256-colour palette keeps the committed pictures small (they are for looking, not measuring)
        from PIL import Image
        with Image.open(path) as im:
            small = im.convert("RGB").quantize(256, dither=Image.Dither.NONE)
        small.save(path, optimize=True)
    except ImportError:
        pass


def lum(rgb):
    return float(ps.luminance(np.asarray(rgb)))


# ---------------------------------------------------------------------------------------------------------------
# Summary
# ---------------------------------------------------------------------------------------------------------------

def scene_row(name, result, seconds):
    img = result["image"]
    cy, ca = lum(img["cycles"]), lum(img["candela"])
    sigma = float(np.sqrt(np.sum((np.array([0.2126, 0.7152, 0.0722]) * np.array(img["sigma"])) ** 2)))
    bright = [b for b in result["blocks"] if not all(b["dark"]) and lum(b["cycles"]) > 0]
    worst = max(bright, key=lambda b: abs(lum(b["candela"]) / lum(b["cycles"]) - 1.0)) if bright else None
    worst_excess = max(max(r["excess"]) for r in result["regions"])
    failed = [f"{r['region']}:{ch}" for r in result["regions"] for ch, ok_e in zip(ps.CHANNELS, r["excess"])
              if ok_e > 1.0]
    failed_regions = sorted({f.split(":")[0] for f in failed}, key=lambda n: (n != "image", n))
    return {
        "scene": name, "pass": result["pass"], "cycles_mean": cy, "candela_mean": ca, "ratio": ca / cy if cy else None,
        "sigma_ratio": sigma / cy if cy else None,
        "ratio_rgb": img["ratio"],
        "worst_block": worst["region"] if worst else None,
        "worst_block_ratio": lum(worst["candela"]) / lum(worst["cycles"]) if worst else None,
        "dark_blocks": sum(all(b["dark"]) for b in result["blocks"]),
        "worst_excess": worst_excess, "failed_checks": failed, "failed_regions": failed_regions,
        "seconds": seconds,
    }


def doc_name(a):
    if a.nodes:
        return "parity_nodes.md"
    return "parity.md" if a.integrator == "PATH" else f"parity_{a.integrator.lower()}.md"


def doc_sub(a):
    if a.nodes:
        return "parity/nodes"
    return "parity" if a.integrator == "PATH" else f"parity/{a.integrator.lower()}"


def write_summary(a, meta, rows, details, started, docs_dir=None):
    when = datetime.datetime.now().strftime("%Y-%m-%d %H:%M")
    cpu = machine()  # bench/accuracy.py's description: CPU model, cores, OS
    settings = meta["settings"]
    passed = sum(r["pass"] for r in rows)
    flags = (" --nodes" if a.nodes else "") + (" --quick" if a.quick else "")
    flags += f" --integrator {a.integrator}" if a.integrator != "PATH" else ""
    md = ["# Parity with Cycles 3.4" + (": one node at a time" if a.nodes else "") +
          (f", Candela's `{a.integrator}` integrator" if a.integrator != "PATH" else ""), "",
          f"Generated by `make parity` (`tests/parity/parity.py{flags}`); do not edit by hand.", "",
          f"Rendered {meta.get('rendered', when)} in {meta.get('blender_seconds', 0) / 60:.0f} minutes, Blender "
          f"{meta['blender']}, {cpu}, {a.threads} render threads. **{passed} of {len(rows)} scenes pass.**", "",
          f"Each scene is rendered by Cycles (CPU) and by Candela with the same settings: {a.size} px wide, "
          f"{a.samples} samples per pixel per engine (two renders of {a.samples // 2} with seeds "
          f"{settings['seeds'][0]} and {settings['seeds'][1]}), {settings['max_bounces']} bounces for every ray "
          f"type, caustics on, {settings['filter'].lower()} pixel filter {settings['filter_width']:g} px wide, no "
          "denoising, no adaptive sampling, no clamping, no light tree (Cycles 3.4 has none; Candela selects "
          f"lights by `{settings['candela_light_selection']}`), Standard view transform." +
          (f" `{a.integrator}` does not apply the path tracer's Light Paths limits and clamps (the add-on warns "
           "when they are set), so the `*_cycles_defaults` scenes render without them on both engines: Cycles' "
           "unbiased image of the same geometry is the reference (tests/parity/render_pair.py)"
           if a.integrator != "PATH" else ""), "",
          f"Checks, per RGB channel: the image mean within {a.rel_image:.0%} and each of the {a.grid} × {a.grid} "
          f"block means within {a.rel_block:.0%} of "
          "Cycles', each widened by the measured noise: |Candela − Cycles| ≤ tol · max(Cycles, 5 % of the image "
          "mean) + t · σ, σ from the two independent renders per engine, t the Student-t quantile at 5·10⁻⁵ "
          "for the effective degrees of freedom. Blocks darker than 5 % of the image mean get that absolute "
          "tolerance instead of a relative one. The derivation is in `tests/parity/parity_stats.py`.", "",
          "| scene | Cycles mean | Candela mean | ratio | ±1σ | worst bright block | dark blocks | "
          "worst check / allowed | render time (s) | result |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        wb = f"{r['worst_block_ratio']:.3f} ({r['worst_block']})" if r["worst_block"] else "—"
        regions = r["failed_regions"]
        where = ", ".join(regions) if len(regions) <= 4 else f"{regions[0]} and {len(regions) - 1} blocks"
        md.append(f"| {r['scene']} | {r['cycles_mean']:.4g} | {r['candela_mean']:.4g} | {r['ratio']:.4f} | "
                  f"{r['sigma_ratio']:.1g} | {wb} | {r['dark_blocks']} | {r['worst_excess']:.2f} | "
                  f"{r['seconds']:.0f} | {'pass' if r['pass'] else '**FAIL**: ' + where} |")
    zr = ps.z_rms([z for d in details.values() for z in d["z_half"]])
    md += ["", "Means are luminance; *ratio* is Candela/Cycles and ±1σ its noise (relative); *worst check / "
           "allowed* is the largest |difference| over its allowance of any check of the scene (≤ 1 passes); "
           "blocks are named by row (0 = top) and column; *render time* is both engines' four renders. "
           f"Noise-model self-check: the RMS of the half-vs-half z-scores over all regions is {zr:.2f} "
           "(1 for independent pixels).", ""]
    notes = HERE / ("notes_nodes.md" if a.nodes else "notes.md")
    if notes.exists():
        md += [notes.read_text().rstrip(), ""]
    sub = doc_sub(a)
    img_dir = (docs_dir / sub) if docs_dir else a.out
    md += ["## Pictures", "", "Each: Cycles | Candela (one exposure for both) | (Candela − Cycles) / image mean, "
           "smoothed over 3 × 3 pixels, with each block's Candela/Cycles luminance ratio (red: a failed check).", ""]
    for r in rows:
        rel = f"{sub}/{r['scene']}.png" if docs_dir else f"{r['scene']}.png"
        md += [f"### {r['scene']}", "", f"![{r['scene']}]({rel})", ""]
    md += [f"Rendering took {meta.get('blender_seconds', time.time() - started):.0f} s in all.", ""]
    text = "\n".join(md)
    (a.out / "summary.md").write_text(text)
    (a.out / "summary.json").write_text(json.dumps({"meta": meta, "size": a.size, "samples": a.samples,
                                                    "rows": rows, "details": details, "z_half_rms": zr},
                                                   indent=1))
    if docs_dir:
        (docs_dir / doc_name(a)).write_text(text)
    return img_dir


def main(argv=None):
    a = parse_args(argv)
    started = time.time()
    a.out.mkdir(parents=True, exist_ok=True)
    native = native_module(a.build)
    meta = render_all(a)
    docs_dir = Path(a.docs) if a.docs else None
    sub = doc_sub(a)
    if docs_dir:
        (docs_dir / sub).mkdir(parents=True, exist_ok=True)
    rows, details = [], {}
    for entry in meta["scenes"]:
        name = entry["scene"]
        halves = {e: [native.read_exr(p) for p in entry["renders"][e]["exr"]] for e in ("CYCLES", "CANDELA")}
        result = ps.compare(halves["CYCLES"], halves["CANDELA"], grid=a.grid, rel_image=a.rel_image,
                            rel_block=a.rel_block)
        seconds = sum(sum(entry["renders"][e]["seconds"]) for e in ("CYCLES", "CANDELA"))
        row = scene_row(name, result, seconds)
        rows.append(row)
        details[name] = result
        mean = {e: 0.5 * (h[0] + h[1]) for e, h in halves.items()}
        picture(a.out / f"{name}.png", name, mean["CYCLES"], mean["CANDELA"], result, grid=a.grid)
        if docs_dir:
            picture(docs_dir / sub / f"{name}.png", name, mean["CYCLES"], mean["CANDELA"], result, grid=a.grid)
        print(f"{name:24s} ratio {row['ratio']:.4f} ± {row['sigma_ratio']:.4f}  worst block "
              f"{row['worst_block_ratio'] if row['worst_block_ratio'] is not None else float('nan'):.3f}  "
              f"worst check/allowed {row['worst_excess']:.2f}  {'pass' if row['pass'] else 'FAIL'}", flush=True)
    write_summary(a, meta, rows, details, started, docs_dir)
    failed = [r["scene"] for r in rows if not r["pass"]]
    if a.full_list and list(meta.get("known_scenes", ALL_SCENES)) != ALL_SCENES:
        print(f"parity: ALL_SCENES in parity.py {ALL_SCENES} differs from parity_scenes.SCENES "
              f"{meta['known_scenes']}: update the list")
        failed.append("(scene list)")
    print(f"parity: {len(rows) - len(failed)} of {len(rows)} scenes pass; summary in {a.out / 'summary.md'}"
          + (f"; FAILED: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
