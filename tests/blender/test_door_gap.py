"""Light through a gap whose edges and receiver carry coplanar overlapping faces (issue 22 item 4, docs/door_gap.md):
Candela must render bench/door_gap_analytic.py's closed-form image mean, with PATH and with BDPT.

The scene (bench/door_gap_render.py, `slit_overlap`): sky light through a slit between two black slabs onto a white
floor in a black room, each slab two overlapping boxes and a quad of the floor's material lying on the floor under
the slit. Cycles 3.4 renders this image 37 % too dark (its rays skip only their own triangle, so the coplanar twin
shadows every point of it; `make door-gap`); a renderer that lets rays leak through the touching boxes or skip a
slab would render it too bright.

Statistics: R renders with independent seeds give R image means; |mean − exact| ≤ t·s/√R with s their sample
standard deviation and t Student's two-sided quantile at 10⁻⁴ for R − 1 degrees of freedom (the image mean of
32² pixels × N samples is close to normal). The exact value's quadrature error is below 10⁻⁵ relative. The test
also requires s/√R ≤ 0.33 % of the mean, so the allowance t·s/√R stays below 2 % (t = 5.92 for 11 degrees of
freedom): a 2 % error fails it, and Cycles' loss on the rug is 18 times that.
"""

import os
import sys

import bpy
import numpy as np

import scenes

sys.path[:0] = [os.path.join(scenes.REPO, "bench"), os.path.join(scenes.REPO, "tests", "parity")]

import door_gap_analytic as an  # noqa: E402
import door_gap_render as dg  # noqa: E402
import parity_stats as ps  # noqa: E402

SIZE, SEEDS = 32, 12
SAMPLES = {"PATH": 768, "BDPT": 768}   # standard errors measured: 0.18 % and 0.16 % of the mean
MAX_SE = 0.0033


def image_means(tmp_path, integrator):
    scenes.ensure_addon()
    scene = dg.build_variant(bpy.context.scene, "slit_overlap", SIZE)
    scene.render.engine = "CANDELA"
    means = []
    for seed in range(1, SEEDS + 1):
        dg.mirror_settings(scene, seed, integrator)
        scene.candela.samples = SAMPLES[integrator]
        scene.render.filepath = str(tmp_path / f"slit_{integrator}_{seed}.exr")
        bpy.ops.render.render(write_still=True)
        rgba = scenes.read_image_pixels(scene.render.filepath)
        means.append(float(ps.luminance(rgba[..., :3]).mean()))
    return np.array(means)


def check(tmp_path, integrator):
    m = image_means(tmp_path, integrator)
    exact = an.mean(slab=an.SLAB)
    se = m.std(ddof=1) / np.sqrt(len(m))
    t = ps.t_quantile(0.5e-4, len(m) - 1)
    print(f"{integrator}: image mean {m.mean():.6f} ± {se:.6f} ({se / exact:.4f}), exact {exact:.6f}")
    assert se <= MAX_SE * exact, f"{integrator}: too noisy to see a 2 % error ({se / exact:.4f} relative)"
    assert abs(m.mean() - exact) <= t * se, \
        f"{integrator}: image mean {m.mean():.6f} ± {se:.6f}, exact {exact:.6f} ({m.mean() / exact - 1:+.4f})"


def test_path_renders_the_slit_exactly(tmp_path):
    check(tmp_path, "PATH")


def test_bdpt_renders_the_slit_exactly(tmp_path):
    check(tmp_path, "BDPT")
