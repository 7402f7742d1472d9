"""Writes the small test scene of tests/python (a floor under an emissive quad) as a scene dump, for renders
outside Blender and Python (make test-sanitize).    write_dump.py [--build build] DIR"""

import argparse
import os
import sys
from pathlib import Path

ap = argparse.ArgumentParser()
ap.add_argument("--build", default="build")
ap.add_argument("dir")
a = ap.parse_args()
os.environ["CANDELA_BUILD_DIR"] = str(Path(a.build).resolve())
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
from conftest import box_scene, params, write_dump  # noqa: E402

write_dump(Path(a.dir), box_scene(), params(width=48, height=32, samples=4))
print(f"wrote {a.dir}")
