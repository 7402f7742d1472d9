"""Fixtures for testing candela._native directly (no Blender): the staged module and tiny scenes."""
import json
import os
import sys
from pathlib import Path

import numpy as np
import pytest

BUILD = Path(os.environ.get("CANDELA_BUILD_DIR", Path(__file__).resolve().parents[2] / "build"))
sys.path.insert(0, str(BUILD / "scripts" / "addons" / "candela"))

import _native  # noqa: E402  (the staged module, built against Debian's Python 3.11)


def quad(x0, x1, y0, y1, z):
    pos = np.array([[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]], np.float32)
    tri = np.array([[0, 1, 2], [0, 2, 3]], np.uint32)
    return pos, tri


def box_scene(light_strength=5.0):
    """A floor and an emissive ceiling quad seen from a camera at the origin looking down −Z."""
    cols = _native.capabilities()["material_columns"]
    p0, t0 = quad(-2, 2, -2, 2, -3.0)
    p1, t1 = quad(-0.15, 0.15, -0.15, 0.15, -1.0)
    mats = np.zeros((2, len(cols)), np.float32)
    mats[0, :3] = 0.8
    mats[1, 3:6] = light_strength
    return {
        "positions": np.concatenate([p0, p1]),
        "triangles": np.concatenate([t0, t1 + 4]),
        "tri_material": np.array([0, 0, 1, 1], np.uint32),
        "mesh_tri_start": np.array([0, 2, 4], np.uint32),
        "instance_mesh": np.array([0, 1], np.uint32),
        "instance_transform": np.stack([np.eye(4, dtype=np.float32)] * 2),
        "material_type": np.zeros(2, np.uint32),
        "materials": mats,
        "camera_to_world": np.eye(4, dtype=np.float32),
        "world_color": np.array([0.1, 0.1, 0.1], np.float32),
    }


def params(**overrides):
    p = {"width": 32, "height": 24, "samples": 8, "seed": 1, "max_bounces": 4, "pixel_filter": "BOX",
         "filter_width": 1.0}
    p.update(overrides)
    return p


def write_dump(directory: Path, arrays, prms):
    directory.mkdir(parents=True, exist_ok=True)
    for k, v in arrays.items():
        np.save(directory / f"{k}.npy", v)
    (directory / "params.json").write_text(json.dumps(prms))


@pytest.fixture
def native():
    return _native
