"""Helpers for GUI test scripts running inside Blender's window (gui_run.py starts them):

- run(steps): drives a generator of checks on a timer (`yield seconds` waits without blocking Blender's event
  loop, so the viewport keeps drawing), records each check, writes the JSON verdict and quits Blender;
- the 3D view's area/region/space, screenshots of its region (bpy.ops.screen.screenshot) as float RGB arrays,
  the screen as the Xvfb framebuffer file shows it (for timing: reading it costs milliseconds);
- live Candela viewport state: the engine's ViewportRender objects, its named worker threads, resident memory.
"""

import json
import os
import sys
import time
import traceback

import bpy
import numpy as np

WORK = os.environ.get("CANDELA_GUI_DIR", "/tmp")
# Quick mode (gui_run.py --quick, in `make test`): the scripts repeat less and aim at fewer samples.
QUICK = os.environ.get("CANDELA_GUI_QUICK", "0") == "1"
_checks, _notes = [], []


def check(name, ok, detail=""):
    _checks.append({"name": name, "ok": bool(ok), "detail": str(detail)})
    print(f"GUI check {'ok' if ok else 'FAILED'}: {name} {detail}")
    return bool(ok)


def note(text):
    _notes.append(str(text))
    print(f"GUI note: {text}")


def _finish():
    with open(os.path.join(WORK, "result.json"), "w") as f:
        json.dump({"checks": _checks, "notes": _notes}, f, indent=1)
    bpy.ops.wm.quit_blender()


def run(steps, first=1.0):
    """Drive the generator `steps()` from a timer; any exception is a failed check (never a traceback)."""
    state = {"gen": None}

    def tick():
        try:
            if state["gen"] is None:
                state["gen"] = steps()
            delay = next(state["gen"])
            return max(0.0, float(delay))
        except StopIteration:
            _finish()
            return None
        except Exception as e:
            check("no error in the test script", False, "".join(traceback.format_exception_only(type(e), e)).strip()
                  + " at " + " / ".join(f"{f.name}:{f.lineno}" for f in traceback.extract_tb(e.__traceback__)[-3:]))
            _finish()
            return None

    bpy.app.timers.register(tick, first_interval=first)


def wait_until(condition, timeout, poll=0.05):
    """Yields until condition() is true; returns whether it became true in time."""
    end = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > end:
            return False
        yield poll
    return True


def view3d():
    """(window, area, WINDOW region, SpaceView3D) of the first 3D view."""
    window = bpy.context.window_manager.windows[0]
    for area in window.screen.areas:
        if area.type == 'VIEW_3D':
            region = [r for r in area.regions if r.type == 'WINDOW'][0]
            return window, area, region, area.spaces.active
    raise RuntimeError("no 3D view in the window")


def screenshot(name):
    """The 3D view's region in a screenshot of the window (bpy.ops.screen.screenshot), as (H, W, 3) floats in
    display space, row 0 at the bottom (Blender's image order)."""
    window, area, region, _ = view3d()
    path = os.path.join(WORK, f"{name}.png")
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.screen.screenshot(filepath=path)
    image = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = image.size
        px = np.empty(w * h * 4, np.float32)
        image.pixels.foreach_get(px)
        px = px.reshape(h, w, 4)[..., :3]
    finally:
        bpy.data.images.remove(image)
    return px[region.y:region.y + region.height, region.x:region.x + region.width]


def framebuffer():
    """The whole Xvfb screen from its framebuffer file (XWD, 32 bits per pixel, BGRX) as (H, W, 3) uint8 RGB, row
    0 at the top; None when the display has no framebuffer file."""
    path = os.path.join(WORK, "fb", "Xvfb_screen0")
    if not os.path.exists(path):
        return None
    with open(path, "rb") as f:
        data = f.read()
    header, ncolors = int.from_bytes(data[0:4], "big"), int.from_bytes(data[76:80], "big")
    w, h, bpl = (int.from_bytes(data[i:i + 4], "big") for i in (16, 20, 48))
    pixels = np.frombuffer(data, np.uint8, count=bpl * h, offset=header + 12 * ncolors).reshape(h, bpl)
    return pixels[:, :4 * w].reshape(h, w, 4)[..., 2::-1]


def region_pixels(screen, region, window_height):
    """A region of framebuffer() pixels, flipped to row 0 at the bottom like screenshot()."""
    top = window_height - region.y - region.height
    return screen[top:top + region.height, region.x:region.x + region.width][::-1].astype(np.float32) / 255.0


def viewports():
    """Candela's open ViewportRender objects."""
    render = sys.modules.get("candela.viewport.render")
    return list(render._live) if render is not None else []


def viewport_threads():
    """Native viewport worker threads alive in this process (named candela-view)."""
    count = 0
    for task in os.listdir("/proc/self/task"):
        try:
            with open(f"/proc/self/task/{task}/comm") as f:
                count += f.read().strip() == "candela-view"
        except OSError:
            pass
    return count


def resident_mb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2 ** 20


def project(region, rv3d, location):
    """Region pixel (x, y from the bottom-left) where Blender draws a world location."""
    from bpy_extras.view3d_utils import location_3d_to_region_2d
    p = location_3d_to_region_2d(region, rv3d, location)
    return None if p is None else (float(p[0]), float(p[1]))


def high_pass_noise(pixels):
    """Noise of an image patch: the standard deviation of the difference between neighbouring pixels (flat
    regions only: it grows with the pixel noise, not with the picture)."""
    grey = pixels.mean(axis=2)
    return float(np.std(np.diff(grey, axis=1)) / np.sqrt(2.0))
