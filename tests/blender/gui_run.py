"""Runs one GUI test script in Blender's real window under Xvfb with Mesa's software OpenGL:

    /usr/bin/python3.11 tests/blender/gui_run.py tests/blender/gui_viewport.py [--quick] [--keep DIR]

1. builds the test scene in `blender -b` (gui_scene.py) and saves it (opening a file skips the splash screen);
2. starts Blender on it in an Xvfb display (xvfb-run, 1600x1000, 24 bit, its framebuffer in a file the script
   can read: gui_steps.py) with the script, which steps through its checks on a timer and writes a JSON verdict;
3. passes if Blender exited normally (no crash, also not while quitting with a viewport rendering), printed no
   Python traceback and every check passed.

--quick (CANDELA_GUI_QUICK=1 for the script, gui_steps.QUICK) runs the script's quick mode, which `make test`
runs: the same kinds of checks with fewer repetitions and lower sample targets; `make test-gui` runs the full ones.

Exit status 77 (ctest's SKIP_RETURN_CODE) only when no X display can be started here (no xvfb-run or Xvfb, or
Xvfb refusing to start), with a message saying so.
"""

import argparse
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
SKIP = 77


def skip(message):
    print(f"SKIPPED: {message}")
    sys.exit(SKIP)


def xvfb_command(fbdir):
    """xvfb-run on a free display from a random start (fewer collisions with other tests), the screen's
    framebuffer in a file under `fbdir` (gui_steps.framebuffer)."""
    return ["xvfb-run", "-a", "-n", str(random.randint(100, 9000)), "-s", f"-screen 0 1600x1000x24 -fbdir {fbdir}"]


def display_failed(output):
    return "Xvfb failed to start" in output or "cannot open display" in output.lower()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("script")
    parser.add_argument("--keep", default=None, help="keep screenshots and logs in this directory")
    parser.add_argument("--timeout", type=float, default=400.0)
    parser.add_argument("--quick", action="store_true", help="the script's quick mode (gui_steps.QUICK)")
    args = parser.parse_args()
    if shutil.which("xvfb-run") is None or shutil.which("Xvfb") is None:
        skip("no X display can be started: xvfb-run/Xvfb are not installed (make deps installs Debian's xvfb)")
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="candela-gui-"))
    work.mkdir(parents=True, exist_ok=True)
    (work / "fb").mkdir(exist_ok=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env["CANDELA_GUI_DIR"] = str(work)
    env["CANDELA_GUI_QUICK"] = "1" if args.quick else "0"
    blender = [str(REPO / "bin" / "candela-blender"), "--factory-startup", "-noaudio"]
    blend = work / "scene.blend"
    setup = subprocess.run(blender + ["-b", "--python-exit-code", "1", "--python", str(HERE / "gui_scene.py"), "--",
                                      str(blend)], env=env, capture_output=True, text=True, timeout=300)
    if setup.returncode != 0 or not blend.exists():
        print(setup.stdout[-4000:], setup.stderr[-4000:])
        print("FAILED: could not build the GUI test scene")
        return 1
    result = work / "result.json"
    if result.exists():
        result.unlink()
    for attempt in range(3):   # xvfb-run -a can race another test for a display number: retry elsewhere
        cmd = xvfb_command(work / "fb") + blender + [str(blend), "--python", str(HERE / args.script)]
        try:
            proc = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=args.timeout)
        except subprocess.TimeoutExpired as e:
            out = (e.stdout or b"").decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")
            print(out[-6000:])
            print(f"FAILED: Blender did not finish within {args.timeout:.0f} s (a hang)")
            return 1
        output = proc.stdout + proc.stderr
        if not display_failed(output):
            break
        time.sleep(2.0 + 3.0 * random.random())
    (work / "blender.log").write_text(output)
    if display_failed(output):
        skip(f"no X display can be started here (xvfb-run: {output.strip().splitlines()[-1] if output else ''})")
    failures = []
    if proc.returncode != 0:
        failures.append(f"Blender exited with status {proc.returncode} (a crash, or a crash while quitting)")
    if "Traceback" in output:
        failures.append("Blender printed a Python traceback")
    if not result.exists():
        failures.append("the GUI script wrote no verdict (it did not run to the end)")
    else:
        verdict = json.loads(result.read_text())
        for check in verdict["checks"]:
            print(("ok   " if check["ok"] else "FAIL ") + check["name"] + (f": {check['detail']}" if check["detail"] else ""))
            if not check["ok"]:
                failures.append(check["name"])
        for line in verdict.get("notes", []):
            print("note " + line)
    if failures:
        print(output[-6000:])
        print("FAILED: " + "; ".join(failures) + f" (logs in {work})")
        return 1
    print(f"passed ({work})")
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
