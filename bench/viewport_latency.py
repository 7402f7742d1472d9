"""`make viewport-latency`: how long an artist waits, Candela beside Cycles, in Blender's real window (Xvfb, Mesa's
software OpenGL, the machine's CPU for both renderers):

- view change → first image: orbit the Rendered 3D view by 4° and wait for the first image of the new view
  (Candela's target: at most 100 ms on the example scenes);
- F12 → first pixels: from invoking the render until the image editor first shows the new render;
- beside them, the same view change in Solid shading (what Blender alone needs to show a new frame with software
  OpenGL here) and Candela's worker alone (from taking the view change to its first image).

Both engines are timed the same way, by what the screen shows (bench/viewport_latency_gui.py reads the Xvfb
framebuffer), on the example scenes (examples/scenes.py) and a 1-million-triangle scene, at 640 pixels wide
(F12, 16 samples) and in a 1321x852 viewport (64 samples, start resolution 64, pixel size 1). Medians of the
trials, in milliseconds, printed as a table (and written to --out/latency.md); with --docs DIR also
DIR/viewport_latency.md, the page `make viewport-latency` regenerates (never edited by hand), with the 100 ms
target's verdict from the measured values.

    /usr/bin/python3.11 bench/viewport_latency.py [--build build] [--quick] [--scenes cornell_box,million] [--docs docs]
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SCENES = ["cornell_box", "soft_shadow", "veach_mis", "glossy", "many_lights", "million"]
ENGINES = ["CANDELA", "CYCLES"]
TARGET_MS = 100.0   # issue 20: a view change shows its first new image within 100 ms


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=str(REPO / "build"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--quick", action="store_true", help="one scene, one view change and one F12 per engine")
    ap.add_argument("--settle", type=float, default=6.0, help="seconds recorded after each view change")
    ap.add_argument("--scenes", default=None, help="comma-separated scene names")
    ap.add_argument("--view-trials", type=int, default=5)
    ap.add_argument("--f12-trials", type=int, default=3)
    ap.add_argument("--docs", default=None, help="also write DOCS/viewport_latency.md")
    ap.add_argument("--reuse", action="store_true",
                    help="keep the results of scene/engine runs already complete in --out (same trial counts)")
    return ap.parse_args()


def clean_env(extra):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env.update(extra)
    return env


def reused(run_dir, view_trials, f12_trials):
    """An earlier complete measurement of the same trials in run_dir (--reuse), else None."""
    path = run_dir / "latency.json"
    if not path.exists():
        return None
    result = json.loads(path.read_text())
    if len(result["view_change"]) != view_trials or len(result["f12"]) != f12_trials:
        return None
    return result


def measure(build, scene, engine, work, view_trials, f12_trials, settle, reuse=False):
    run_dir = work / f"{scene}_{engine.lower()}"
    if reuse and reused(run_dir, view_trials, f12_trials) is not None:
        return reused(run_dir, view_trials, f12_trials)
    shutil.rmtree(run_dir, ignore_errors=True)
    (run_dir / "fb").mkdir(parents=True)
    blender = [str(REPO / "bin" / "candela-blender"), "--factory-startup", "-noaudio"]
    env = clean_env({"CANDELA_SCRIPTS_DIR": str(Path(build) / "scripts"), "CANDELA_GUI_DIR": str(run_dir),
                     "CANDELA_LATENCY_ENGINE": engine, "CANDELA_LATENCY_VIEW_TRIALS": str(view_trials),
                     "CANDELA_LATENCY_F12_TRIALS": str(f12_trials), "CANDELA_LATENCY_SETTLE_S": str(settle)})
    blend = work / f"{scene}.blend"
    if not blend.exists():
        subprocess.run(blender + ["-b", "--python-exit-code", "1", "--python",
                                  str(REPO / "bench" / "viewport_latency_scene.py"), "--", scene, str(blend)],
                       env=env, check=True, capture_output=True, timeout=900)
    sys.path.insert(0, str(REPO / "tests" / "blender"))
    from gui_run import display_failed, xvfb_command
    for attempt in range(3):   # another test may take the same display number at the same moment
        cmd = xvfb_command(run_dir / "fb") + blender + [str(blend), "--python", str(REPO / "bench" / "viewport_latency_gui.py")]
        proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=1800)
        if not display_failed(proc.stdout + proc.stderr):
            break
    (run_dir / "blender.log").write_text(proc.stdout + proc.stderr)
    path = run_dir / "latency.json"
    if proc.returncode != 0 or not path.exists():
        raise RuntimeError(f"{scene} / {engine}: Blender failed (status {proc.returncode}); see {run_dir}/blender.log")
    return json.loads(path.read_text())


def median_s(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def median_ms(values):
    m = median_s(values)
    return f"{1000 * m:.0f}" if m is not None else "—"


def span_ms(values):
    values = [1000 * v for v in values if v is not None]
    return f"{min(values):.0f}–{max(values):.0f} ms" if values else "—"


def verdict(rows):
    """What the numbers say about the 100 ms target and Candela against Cycles, computed from the medians."""
    worker = {r["scene"]: median_s(r["CANDELA"]["engine_first_image"]) for r in rows}
    over = [f"{s} ({1000 * w:.0f} ms)" for s, w in worker.items() if w is not None and 1000 * w > TARGET_MS]
    screen = {e: [median_s(r[e]["view_change"]) for r in rows] for e in ENGINES}
    floor = [f for f in (median_s(r["CANDELA"]["redraw_floor"] + r["CYCLES"]["redraw_floor"]) for r in rows)
             if f is not None]
    f12 = {e: [median_s(r[e]["f12"]) for r in rows] for e in ENGINES}
    ratio = [c / y for c, y in zip(screen["CANDELA"], screen["CYCLES"]) if c is not None and y]
    f12_ratio = [c / y for c, y in zip(f12["CANDELA"], f12["CYCLES"]) if c is not None and y]
    worker_values = [w for w in worker.values() if w is not None]
    lines = [
        f"- **Target: a view change shows its first new image within {TARGET_MS:.0f} ms.** Candela's own part (the "
        f"worker, from taking the view change to its first image): {span_ms(worker_values)} over the scenes, "
        + ("within the target on every scene." if not over else
           f"within the target except on {', '.join(over)}."),
        f"- On screen (what the user sees, Blender's redraw included): Candela {span_ms(screen['CANDELA'])}, "
        f"Cycles {span_ms(screen['CYCLES'])}; Candela's time is {min(ratio):.2f}–{max(ratio):.2f}× Cycles'. "
        f"The same view change in Solid shading, with no render engine at all, takes {span_ms(floor)} here: "
        + ("the 100 ms target on screen is below what this machine's software OpenGL needs for one redraw, so it "
           "is not met on screen by either engine." if floor and 1000 * min(floor) > TARGET_MS
           else "Blender's redraw fits within the target here."),
        f"- F12 → first pixels: Candela {span_ms(f12['CANDELA'])}, Cycles {span_ms(f12['CYCLES'])}; Candela's time "
        f"is {min(f12_ratio):.2f}–{max(f12_ratio):.2f}× Cycles' (Cycles' first update is a coarse pass, Candela's "
        f"the first full-resolution sample).",
    ] if ratio and f12_ratio else []
    return lines


def write_docs(docs, table, notes, view_trials, f12_trials):
    text = "\n".join([
        "# Viewport and F12 latency, Candela beside Cycles",
        "",
        "Generated by `make viewport-latency` (bench/viewport_latency.py); do not edit by hand. How it is measured: "
        "docs/viewport.md, *Measured*.",
        "",
        f"Run of {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}: {os.cpu_count()} CPUs shared with other "
        f"work, Blender's window under Xvfb with Mesa's software OpenGL, a 1321x852 viewport (64 samples, start "
        f"resolution 64, pixel size 1), 640-pixel-wide F12 renders at 16 samples; medians of {view_trials} view "
        f"changes (a 4° orbit) and {f12_trials} F12 renders per engine and scene.",
        "",
        table,
        "",
        "What the numbers say:",
        "",
        *notes,
        "",
    ])
    (Path(docs) / "viewport_latency.md").write_text(text)


def main():
    args = parse_args()
    if shutil.which("xvfb-run") is None:
        print("SKIPPED: viewport-latency: xvfb-run is not installed (make deps installs Debian's xvfb)")
        return 77
    scenes = args.scenes.split(",") if args.scenes else (["cornell_box"] if args.quick else SCENES)
    view_trials, f12_trials = (1, 1) if args.quick else (args.view_trials, args.f12_trials)
    out = Path(args.out or Path(args.build) / "viewport-latency").resolve()
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for scene in scenes:
        row = {"scene": scene}
        for engine in ENGINES:
            result = measure(args.build, scene, engine, out, view_trials, f12_trials, args.settle, args.reuse)
            row[engine] = result
            print(f"{scene:12s} {engine:8s} view change {median_ms(result['view_change'])} ms "
                  f"(Solid shading {median_ms(result['redraw_floor'])} ms), F12 {median_ms(result['f12'])} ms",
                  flush=True)
        rows.append(row)
    lines = ["| scene | view change → first image: Candela | Cycles | the same in Solid shading (Blender alone) | "
             "Candela's worker alone | F12 → first pixels: Candela | Cycles |", "|---|---:|---:|---:|---:|---:|---:|"]
    for row in rows:
        c, y = row["CANDELA"], row["CYCLES"]
        floor = median_ms(c["redraw_floor"] + y["redraw_floor"])
        lines.append(f"| {row['scene']} | {median_ms(c['view_change'])} ms | {median_ms(y['view_change'])} ms | "
                     f"{floor} ms | {median_ms(c['engine_first_image'])} ms | {median_ms(c['f12'])} ms | "
                     f"{median_ms(y['f12'])} ms |")
    loads = [r[e]["load_average"] for r in rows for e in ENGINES]
    lines.append("")
    lines.append(f"Load average during the runs: {min(loads):.1f}–{max(loads):.1f} on {os.cpu_count()} CPUs.")
    table = "\n".join(lines)
    notes = verdict(rows)
    (out / "latency.md").write_text(table + "\n\n" + "\n".join(notes) + "\n")
    if args.docs:
        write_docs(args.docs, table, notes, view_trials, f12_trials)
    (out / "latency.json").write_text(json.dumps(rows, indent=1))
    print()
    print(table)
    print()
    print("\n".join(notes))
    print(f"\nmedians of {view_trials} view changes and {f12_trials} F12 renders per engine; raw data in {out}")
    missing = [f"{r['scene']}/{e}/{k}" for r in rows for e in ENGINES for k in ("view_change", "f12", "redraw_floor")
               if any(v is None for v in r[e][k])]
    if missing:
        print("viewport-latency: no new image was seen within the recording time for " + ", ".join(missing))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
