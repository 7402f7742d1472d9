"""Input-node semantics against Cycles 3.4: an emission plane whose colour is a Math / Mix / ColorRamp / colour
model / Mapping chain over its UVs, rendered by both engines. Emission seen directly has no light-transport
noise: the only difference is where each engine's 64 pixel samples fall. For a function whose value changes by
at most Δ across a pixel, a pixel mean's sampling error is below Δ/√(12·64) ≈ 0.036Δ; a 4 × 4 block averages 16
pixels, so its error is below 0.01Δ. The chains below keep Δ ≲ 0.3 (gradients ≤ 8 over 1/32 of the UV square),
so a 4 × 4 block mean off by more than 0.01 + 1 % is a semantic difference, not noise. Math operations with a
pole or a jump inside the image (division, logarithm, tangent, inverse root; comparisons, rounding, modulo) are
checked by the native unit tests instead: their pixel means depend on where samples fall."""

import numpy as np
import pytest

import texture_scenes as ts

SMOOTH_MATH = [op for op in ts.MATH_OPS
               if op not in ("DIVIDE", "LOGARITHM", "TANGENT", "INVERSE_SQRT", "LESS_THAN", "GREATER_THAN", "COMPARE",
                             "ROUND", "FLOOR", "CEIL", "TRUNC", "MODULO", "WRAP", "SNAP", "SIGN", "DEGREES")]
KINDS = ["math_" + op for op in SMOOTH_MATH] + ["mix_" + b for b in ts.MIX_BLENDS] + ["ramp", "hsv", "misc"]


def blocks(img, n=4):
    h, w = img.shape[:2]
    return img[: h // n * n, : w // n * n].reshape(n, h // n, n, w // n, -1).mean(axis=(1, 3))


@pytest.mark.parametrize("kind", KINDS)
def test_node_chain_matches_cycles(tmp_path, kind):
    out = {}
    for engine in ('CYCLES', 'CANDELA'):
        out[engine] = ts.render(ts.node_scene(kind), engine, 64, str(tmp_path / f"{engine}.exr"), 0)[..., :3]
    # Candela never emits negative radiance (a Subtract blend can go below 0; Cycles renders that as is).
    cycles = np.maximum(out['CYCLES'], 0.0)
    a, b = blocks(out['CANDELA']), blocks(cycles)
    assert np.all(np.abs(a - b) <= 0.01 + 0.01 * np.abs(b)), (kind, float(np.abs(a - b).max()))
