"""The parity suite's statistics (pure numpy): is Candela's image the same as Cycles' up to a tolerance, given
that both are Monte Carlo estimates with noise?

Inputs per engine: two renders of the same scene with independent seeds, a and b (H, W, 3), each with n/2
samples per pixel. The engine's estimate is m = (a + b)/2, and since a and b are independent and identically
distributed, (a − b)²/4 is an unbiased estimate of Var(m) per pixel (one degree of freedom each). With a box
filter of width 1 every sample lands in exactly one pixel and both engines scramble their sample sequences per
pixel, so pixels are independent and the variance of a region's mean is Σ_p Var(m_p)/P².

Check (per region — the whole image, or one of GRID × GRID blocks — and per RGB channel):

    |μ_Candela − μ_Cycles|  ≤  REL · max(μ_Cycles, DARK · M_Cycles)  +  t · σ_d

  REL     the tolerance of issue #3: 2 % for the image mean, 5 % for a block mean.
  DARK    a region is "dark" when its Cycles mean is below DARK = 5 % of the image mean M (same channel):
          relative error means nothing near zero, so a dark region is held to the absolute tolerance that
          REL allows at the threshold (REL · DARK · M) instead of REL · μ. A region bright in Candela but
          dark in Cycles is therefore still caught.
  σ_d²    = σ²_Candela + σ²_Cycles, each Σ_p (a_p − b_p)²/4 / P² (above).
  t       the allowance for noise: the one-sided Student-t quantile with ν_eff degrees of freedom
          (Welch–Satterthwaite: ν_eff = (Σ v_p)² / Σ v_p², every per-pixel estimate v_p having one degree of
          freedom) at level ALPHA = 5·10⁻⁵. A check fails falsely with probability ≤ ALPHA when the true
          difference sits exactly at the tolerance REL·μ (the worst case allowed); with about 700 checks in a
          full run (14 scenes × 17 regions × 3 channels) the chance of one false failure is then < 4 %, and for
          engines that truly agree (difference ≪ tolerance) it is negligible. Noise therefore widens the
          tolerance only as far as the measured noise justifies: at high sample counts t·σ_d is small against
          REL·μ, and in the quick mode (small images, few samples) it is wider — by the measured noise, not by
          a guessed factor.

  ROUNDING an absolute floor of ROUNDING · (the brightest channel's image mean) on every allowance: a channel that
          is exactly 0 in Cycles (a plane's object-space z) and 10⁻⁸ in Candela (float rounding of a transform) has
          no noise and no relative tolerance to absorb it.

Self-check of the noise model: for every region and channel, z_half = Σ_p (a_p − b_p) / √(Σ_p (a_p − b_p)²) —
the difference of the two halves over its own estimated standard deviation — is ~N(0, 1) when pixels are
independent; the RMS of z_half over all regions is reported (≈ 1; clearly more would mean correlated pixels and a
too narrow σ).
"""

import functools
import math

import numpy as np

REL_IMAGE = 0.02
REL_BLOCK = 0.05
DARK = 0.05
GRID = 4
ALPHA = 5e-5
ROUNDING = 1e-5
CHANNELS = ("R", "G", "B")


def t_quantile(p_upper, nu):
    """t with P(T > t) = p_upper for Student's t with nu (real, > 0) degrees of freedom, by bisection on the
    exact tail P(T > t) = ½·I_{ν/(ν+t²)}(ν/2, ½) (regularised incomplete beta; no scipy on a fresh machine).
    nu is rounded DOWN to 2 significant digits (a slightly larger, conservative t) so that the few distinct
    values are computed once."""
    if not math.isfinite(nu) or nu > 1e6:
        return _normal_quantile(p_upper)
    digits = 10.0 ** (math.floor(math.log10(nu)) - 1)
    return _t_quantile_cached(p_upper, max(math.floor(nu / digits) * digits, 1e-3))


@functools.lru_cache(maxsize=4096)
def _t_quantile_cached(p_upper, nu):
    lo, hi = 0.0, 1.0
    while _t_tail(hi, nu) > p_upper:
        hi *= 2.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if _t_tail(mid, nu) > p_upper:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _t_tail(t, nu):
    return 0.5 * _betainc(0.5 * nu, 0.5, nu / (nu + t * t))


def _betainc(a, b, x):
    """Regularised incomplete beta I_x(a, b): its continued fraction (modified Lentz), on the side where it
    converges fast (x < (a+1)/(a+b+2)), and the symmetry I_x(a, b) = 1 − I_{1−x}(b, a) otherwise."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    if x > (a + 1.0) / (a + b + 2.0):
        return 1.0 - _betainc(b, a, 1.0 - x)
    log_front = a * math.log(x) + b * math.log1p(-x) - (math.lgamma(a) + math.lgamma(b) - math.lgamma(a + b))
    tiny = 1e-300
    f, c, d = 1.0, 1.0, 0.0
    for i in range(0, 400):
        m = i // 2
        if i == 0:
            num = 1.0
        elif i % 2 == 0:
            num = m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m))
        else:
            num = -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))
        d = 1.0 + num * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + num / c
        c = c if abs(c) > tiny else tiny
        f *= c * d
        if abs(1.0 - c * d) < 1e-14:
            break
    return math.exp(log_front) * (f - 1.0) / a


@functools.lru_cache(maxsize=64)
def _normal_quantile(p_upper):
    """z with P(Z > z) = p_upper, by bisection on erfc."""
    lo, hi = -10.0, 40.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if 0.5 * math.erfc(mid / math.sqrt(2.0)) > p_upper:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _regions(height, width, grid):
    """[(name, row slice, column slice)]: the whole image, then grid × grid blocks (row 0 = bottom, as stored)."""
    out = [("image", slice(0, height), slice(0, width))]
    ys = np.linspace(0, height, grid + 1).round().astype(int)
    xs = np.linspace(0, width, grid + 1).round().astype(int)
    for by in range(grid):
        for bx in range(grid):
            # Blocks named by their place in the displayed image: row 0 at the top.
            out.append((f"block{grid - 1 - by}{bx}", slice(ys[by], ys[by + 1]), slice(xs[bx], xs[bx + 1])))
    return out


def _region_stats(a, b, rows, cols):
    """Mean (3,), variance of the mean (3,), the per-pixel variance estimates' Σv² (3,), and the half-split z."""
    ra, rb = a[rows, cols].reshape(-1, 3).astype(np.float64), b[rows, cols].reshape(-1, 3).astype(np.float64)
    p = ra.shape[0]
    v = (ra - rb) ** 2 / 4.0                        # per-pixel Var((a+b)/2) estimates
    mean = 0.5 * (ra.mean(0) + rb.mean(0))
    var = v.sum(0) / p ** 2
    sum_v2 = (v ** 2).sum(0) / p ** 4               # for Welch–Satterthwaite, in the same units as var²
    diff = ra.mean(0) - rb.mean(0)                  # Var = 4·var
    with np.errstate(divide="ignore", invalid="ignore"):
        z_half = np.where(var > 0, diff / np.sqrt(4.0 * var), 0.0)
    return mean, var, sum_v2, z_half


def compare(cycles_halves, candela_halves, grid=GRID, rel_image=REL_IMAGE, rel_block=REL_BLOCK, dark=DARK,
            alpha=ALPHA):
    """Check Candela against Cycles. Each argument is (a, b): two (H, W, ≥3) float arrays of independent renders.

    Returns {"pass": bool, "regions": [per-region dicts], "image": the image region, "z_half": [...]}."""
    ca, cb_ = (np.asarray(x)[..., :3] for x in cycles_halves)
    na, nb = (np.asarray(x)[..., :3] for x in candela_halves)
    if ca.shape != na.shape or ca.shape != cb_.shape or na.shape != nb.shape:
        raise ValueError(f"image shapes differ: {ca.shape} {cb_.shape} {na.shape} {nb.shape}")
    height, width = ca.shape[:2]
    regions, z_half = [], []
    image_mean = None
    for name, rows, cols in _regions(height, width, grid):
        cm, cv, cs, cz = _region_stats(ca, cb_, rows, cols)
        nm, nv, ns, nz = _region_stats(na, nb, rows, cols)
        if image_mean is None:
            image_mean = cm
        z_half += [float(z) for z in np.concatenate([cz, nz])]
        rel = rel_image if name == "image" else rel_block
        sigma = np.sqrt(cv + nv)
        with np.errstate(divide="ignore", invalid="ignore"):
            nu = np.where(cs + ns > 0, (cv + nv) ** 2 / (cs + ns), np.inf)
        t = np.array([t_quantile(alpha, n) if np.isfinite(n) else _normal_quantile(alpha) for n in nu])
        is_dark = cm < dark * image_mean
        scale = np.maximum(cm, dark * image_mean)
        allowed = rel * scale + t * sigma + ROUNDING * float(np.max(image_mean))
        diff = nm - cm
        ok = np.abs(diff) <= allowed
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(cm > 0, nm / cm, np.nan)
        regions.append({
            "region": name, "cycles": cm.tolist(), "candela": nm.tolist(), "ratio": ratio.tolist(),
            "sigma": sigma.tolist(), "t": t.tolist(), "nu_eff": nu.tolist(), "dark": is_dark.tolist(),
            "allowed": allowed.tolist(), "rel_tolerance": rel, "excess": (np.abs(diff) / np.where(allowed > 0, allowed, np.inf)).tolist(),
            "pass": bool(ok.all()),
        })
    return {"pass": all(r["pass"] for r in regions), "regions": regions, "image": regions[0],
            "blocks": regions[1:], "z_half": z_half}


def luminance(rgb):
    rgb = np.asarray(rgb)
    return 0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2]


def z_rms(values):
    v = np.asarray(values, np.float64)
    v = v[np.isfinite(v) & (v != 0.0)]
    return float(np.sqrt(np.mean(v ** 2))) if v.size else float("nan")
