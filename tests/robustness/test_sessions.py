"""Session lifecycle under stress, through the native module (no Blender): cancel then render again, many
times; resident memory must not grow by more than 5 % after warm-up."""

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from conftest import _native, box_scene, params  # noqa: E402


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


def cycle(native, cancel):
    s = native.Session(box_scene(), params(width=64, height=48, samples=64 if cancel else 4))
    s.start()
    if cancel:
        time.sleep(0.005)
        s.cancel()
    assert s.wait(10.0)
    s.join()
    assert s.error is None
    img = s.get_pass("Combined")
    assert np.isfinite(img).all()
    return s.progress()["phase"]


def test_cancel_then_render_again_fifty_times_without_growing():
    native = _native
    for i in range(10):  # warm-up: allocator pools, TBB threads, Embree's caches
        cycle(native, cancel=i % 2 == 0)
    before = resident_bytes()
    phases = [cycle(native, cancel=i % 2 == 0) for i in range(50)]
    after = resident_bytes()
    assert "cancelled" in phases and "done" in phases
    assert after <= before * 1.05, f"resident memory grew from {before / 1e6:.1f} MB to {after / 1e6:.1f} MB"
