"""The bias of the irradiance cache's Reuse at Later Bounces (docs/irradiance_cache.md): renders a scene dump with
it off and on for N seeds (the same seed for both, so the camera samples are shared) and prints the mean difference
of the images (with its standard error over the seeds), the relative RMS of the mean difference image with its
noise subtracted, and each setting's relative RMSE against a reference given as two independent halves.

    /usr/bin/python3.11 bench/ic_reuse_bias.py --dump DUMP_DIR --ref REF_A.exr REF_B.exr [--samples 64] [--seeds 8]

DUMP_DIR: a scene dump (bpy.ops.candela.export_dump) with integrator IRRADIANCE_CACHE; the references: PATH renders
of the same dump with different seeds (build/bin/candela DUMP --set integrator=PATH --samples 2048 --seed 1000 …).
"""

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
import accuracy_stats as st  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--dump", required=True)
    ap.add_argument("--ref", nargs=2, required=True)
    ap.add_argument("--samples", type=int, default=64)
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    sys.path.insert(0, os.path.join(a.build, "scripts", "addons", "candela"))
    import _native
    lum = lambda f: st.luminance(_native.read_exr(f))  # noqa: E731
    ref_a, ref_b = lum(a.ref[0]), lum(a.ref[1])
    mean_ref = float(np.mean(0.5 * (ref_a + ref_b)))
    images = {"off": [], "on": []}
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(a.seeds):
            for name, value in (("off", "false"), ("on", "true")):
                out = os.path.join(tmp, f"{name}_{seed}.exr")
                subprocess.run([os.path.join(a.build, "bin", "candela"), a.dump, "-o", out, "--samples",
                                str(a.samples), "--seed", str(seed), "--threads", str(a.threads), "-q",
                                "--set", f"ic_reuse_at_bounces={value}"], check=True, capture_output=True)
                images[name].append(lum(out))
    off, on = np.array(images["off"]), np.array(images["on"])
    d = on - off
    per_seed = d.mean(axis=(1, 2))
    print(f"image mean, on/off - 1: {per_seed.mean() / mean_ref:+.5f} ± "
          f"{per_seed.std(ddof=1) / np.sqrt(a.seeds) / mean_ref:.5f}")
    d_mean = d.mean(axis=0)
    noise = float(d.var(axis=0, ddof=1).mean()) / a.seeds
    print(f"relative RMS of the mean difference image: {np.sqrt(max(float(np.mean(d_mean ** 2)) - noise, 0.0)) / mean_ref:.4f}"
          f" (noise subtracted; raw {np.sqrt(float(np.mean(d_mean ** 2))) / mean_ref:.4f})")
    for name, imgs in (("off", off), ("on", on)):
        e = [st.errors(img, ref_a, ref_b)["rrmse"] for img in imgs]
        print(f"{name}: image mean / reference - 1 = {imgs.mean() / mean_ref - 1:+.5f}, rel. RMSE per seed "
              f"{np.mean(e):.4f}")


if __name__ == "__main__":
    main()
