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
trials, in milliseconds, printed as a table (and written to --out/latency.md).

    /usr/bin/python3.11 bench/viewport_latency.py [--build build] [--quick] [--scenes cornell_box,million]
"""

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SCENES = ["cornell_box", "soft_shadow", "veach_mis", "glossy", "many_lights", "million"]
ENGINES = ["CANDELA", "CYCLES"]


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=str(REPO / "build"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--quick", action="store_true", help="one scene, one view change and one F12 per engine")
    ap.add_argument("--settle", type=float, default=6.0, help="seconds recorded after each view change")
    ap.add_argument("--scenes", default=None, help="comma-separated scene names")
    ap.add_argument("--view-trials", type=int, default=5)
    ap.add_argument("--f12-trials", type=int, default=3)
    return ap.parse_args()


def clean_env(extra):
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env.update(extra)
    return env


def measure(build, scene, engine, work, view_trials, f12_trials, settle):
    run_dir = work / f"{scene}_{engine.lower()}"
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


def median_ms(values):
    values = [v for v in values if v is not None]
    return f"{1000 * statistics.median(values):.0f}" if values else "—"


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
            result = measure(args.build, scene, engine, out, view_trials, f12_trials, args.settle)
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
    (out / "latency.md").write_text(table + "\n")
    (out / "latency.json").write_text(json.dumps(rows, indent=1))
    print()
    print(table)
    print(f"\nmedians of {view_trials} view changes and {f12_trials} F12 renders per engine; raw data in {out}")
    missing = [f"{r['scene']}/{e}/{k}" for r in rows for e in ENGINES for k in ("view_change", "f12", "redraw_floor")
               if any(v is None for v in r[e][k])]
    if missing:
        print("viewport-latency: no new image was seen within the recording time for " + ", ".join(missing))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
