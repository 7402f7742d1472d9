"""Per-sample variance under a very bright sun in an HDR, Candela against Cycles in the same run (issue 22).

    /usr/bin/python3.11 tests/parity/env_variance.py [--build build] [--out DIR] [--size 64] [--samples 128] [--quick]

The scenes sun_hdr_linear and sun_hdr_closest (tests/parity/parity_scenes.py): a diffuse floor and sphere under a
sky of radiance ~1 with a 2 × 2-texel sun of 160 000, read with Linear (Blender's default) and Closest
interpolation. Both engines render each scene twice with independent seeds at the parity suite's mirrored
settings (tests/parity/render_pair.py: box filter of 1 px, so pixels are independent). With N samples per half,
d = A − B per pixel has E[d²] = 2σ²/N, so N·mean(d²)/2 over the pixels estimates the mean per-sample variance
σ² of a pixel (luminance), and the spread of N·d²/2 over the pixels gives its standard error s.

Pass: Candela's variance ≤ Cycles' + 3·√(s_candela² + s_cycles²) on each scene — one-sided at 3σ of the two
estimates' noise (false-alarm rate ≈ 0.13 % per scene if the estimate's error is normal, which the mean over a few
thousand pixels makes it nearly; heavy tails from fireflies widen s, they do not shrink it). Prints the ratios.

Measured at 64 px, 128 spp (docs/textures.md), Candela / Cycles in one run: the centre-valued map gave 7300× with
Linear; the integrated piecewise-constant map 18× (313.8 ± 14 against 17.49 ± 0.86) and 1.27× with Closest
(17.98 ± 0.86 against 14.09 ± 0.77); the piecewise-bilinear map with MIS compensation (lights/environment_bake.h)
0.42× with Linear (7.34 ± 0.78) and 0.51× with Closest (7.23 ± 0.67). `--quick` (32 px; `make test`, ctest
env_variance_quick) runs the same check on a quarter of the pixels.
"""

import argparse
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))
sys.path.insert(1, str(ROOT / "bench"))

import parity  # noqa: E402  (render_all: render_pair.py in one Blender process)
import parity_stats as ps  # noqa: E402

SCENES = ["sun_hdr_linear", "sun_hdr_closest"]


def per_sample_variance(a, b, samples_per_half):
    """Mean per-pixel per-sample variance of the luminance and its standard error, from two independent renders."""
    d = ps.luminance(a) - ps.luminance(b)
    v = samples_per_half * d * d / 2.0
    return float(v.mean()), float(v.std(ddof=1) / np.sqrt(v.size))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--size", type=int, default=64)
    ap.add_argument("--samples", type=int, default=128, help="samples per pixel per engine, over two seeds")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="32 px (make test)")
    a = ap.parse_args(argv)
    if a.quick:
        a.size = 32
    a.out = Path(a.out or Path(a.build) / "env-variance")
    a.out.mkdir(parents=True, exist_ok=True)
    a.scenes, a.reuse, a.integrator = SCENES, False, "PATH"
    result = parity.render_all(a)
    native = parity.native_module(a.build)
    ok = True
    for entry in result["scenes"]:
        n = entry["samples_per_render"]
        var = {}
        for engine in ("CYCLES", "CANDELA"):
            halves = [native.read_exr(p) for p in entry["renders"][engine]["exr"]]
            var[engine] = per_sample_variance(halves[0], halves[1], n) + (
                float(np.mean([ps.luminance(h).mean() for h in halves])), sum(entry["renders"][engine]["seconds"]))
        (vc, sc, mc, tc), (vy, sy, my, ty) = var["CANDELA"], var["CYCLES"]
        passed = vc <= vy + 3.0 * np.hypot(sc, sy)
        ok &= passed
        print(f"{entry['scene']}: per-sample variance Candela {vc:.4g} ± {sc:.2g}, Cycles {vy:.4g} ± {sy:.2g}, "
              f"ratio {vc / vy:.3f}; mean Candela {mc:.4f}, Cycles {my:.4f} (ratio {mc / my:.4f}); "
              f"time Candela {tc:.1f} s, Cycles {ty:.1f} s — {'PASS' if passed else 'FAIL'}", flush=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
