"""The statistics of `make accuracy` (bench/accuracy.py): error metrics, cost per sample, convergence fits and
the bounded time-to-error. Pure numpy, no Blender; every choice below is stated in docs/accuracy.md.

Error metrics, all on luminance against a reference made of two independent half renders a and b
(ref = (a + b)/2; the per-pixel noise variance of ref is estimated as v = (a − b)²/4 and subtracted, since
E[(L − ref)²] = E[(L − L_true)²] + Var(ref) when L and ref are independent):
  rrmse   relative RMSE:  √(mean(d² − v)) / mean(ref)                 (d = L − ref)
  relmse  relative MSE:   mean((d² − v) / (ref² + ε)), ε = 0.01       (the usual per-pixel relative MSE)
  robust  relative RMSE over the pixels left after dropping the TRIM fraction with the largest |d|,
          noise-corrected over the same pixels. Heavy-tailed scenes (small, very bright emitters seen directly
          or in mirrors, fireflies) put most of the squared error in a few pixels, so one image's rrmse
          swings by factors between sample counts; this metric says what the rest of the image does. It
          under-states the error by design and is labelled as such. Its noise correction subtracts the
          reference's estimated noise over the kept pixels (a − b is uncorrelated with d, so selecting on d
          does not bias that estimate for symmetric noise).
  top_share the share of the raw squared error in those dropped pixels (near 1: heavy-tailed).

Time: the cost of a render is its process CPU time (all render threads), which another job on this shared
machine slows far less than wall time (though still by up to ~30 %: the cores are shared; hence the
round-robin order of bench/accuracy_sequences.py), less the per-render set-up (render_times). Cycles' cost per
sample is not constant at these sizes (about 40 ms per 96×96 pass at 4–8 samples, 25 ms at 64–256 on one
run), so each point keeps its own measured time rather than a fitted cost × samples; cost_per_sample (a
Theil–Sen slope) is printed for comparison only.
"""

import math
import re

import numpy as np

EPS = 1e-2
TRIM = 0.01
# A fit is used only where the reference's own noise is under this fraction of the measured raw MSE: beyond it
# the subtraction of the reference noise, itself an estimate, decides the error.
REF_NOISE_MAX = 0.1
MIN_SAMPLES_FIT = 4
# Extrapolation bound (derivation in docs/accuracy.md, "Method"): the predicted time to an error X beyond the
# last measurement is t_max · (X / e_max)^(1/s). A slope off by Δs changes it by the factor F^(Δs/|s|), F being
# the extrapolation factor t / t_max. Asking that factor to stay under 1.3 for the slope's 1σ uncertainty and
# for a change of regime of Δs = 0.1 at the −0.5 slope of plain Monte Carlo (1.3 = F^(0.1/0.5) → F = 3.7):
#   F_max = min(3.7, 1.3^(|s| / σ_s)).
TIME_TOLERANCE = 1.3
REGIME_DS = 0.1
F_CAP = TIME_TOLERANCE ** (0.5 / REGIME_DS)


def luminance(rgba):
    return 0.2126 * rgba[..., 0] + 0.7152 * rgba[..., 1] + 0.0722 * rgba[..., 2]


def errors(image, ref_a, ref_b):
    """dict(rrmse, relmse, robust, ref_noise_fraction) of luminance `image` against the two reference halves."""
    ref = 0.5 * (ref_a + ref_b)
    v = 0.25 * (ref_a - ref_b) ** 2
    d2 = (image - ref) ** 2
    mean_ref = max(float(np.mean(ref)), 1e-12)
    raw = float(np.mean(d2))
    rrmse = math.sqrt(max(raw - float(np.mean(v)), 0.0)) / mean_ref
    relmse = max(float(np.mean((d2 - v) / (ref ** 2 + EPS))), 0.0)
    flat_d2, flat_v = d2.ravel(), v.ravel()
    keep = np.argsort(flat_d2)[: max(1, int(round(flat_d2.size * (1.0 - TRIM))))]
    kept_d2, kept_v = float(np.mean(flat_d2[keep])), float(np.mean(flat_v[keep]))
    robust = math.sqrt(max(kept_d2 - kept_v, 0.0)) / mean_ref
    total = float(np.sum(flat_d2))
    return {"rrmse": rrmse, "relmse": relmse, "robust": robust,
            "ref_noise_fraction": float(np.mean(v)) / raw if raw > 0 else 1.0,
            "robust_ref_noise_fraction": kept_v / kept_d2 if kept_d2 > 0 else 1.0,
            # how heavy-tailed the error is: the share of the raw squared error in the dropped pixels
            "top_share": 1.0 - float(np.sum(flat_d2[keep])) / total if total > 0 else 0.0}


def rrmse_log_sigma(image, ref_a, ref_b, block=2):
    """σ of log(rel. RMSE) of one image: the standard error of the mean squared error (less the reference's noise)
    over the image's pixels, from the scatter of its means over block × block tiles (a tile holds a pixel and the
    neighbours the reconstruction filter correlates it with, so tiles are close to independent), halved for the
    square root (delta method). It is the noise of the error figure itself: another seed would move the rel. RMSE
    by about this factor in logs. Heavy-tailed errors (fireflies) make it large, as they should."""
    ref = 0.5 * (ref_a + ref_b)
    e = (image - ref) ** 2 - 0.25 * (ref_a - ref_b) ** 2
    h, w = (e.shape[0] // block) * block, (e.shape[1] // block) * block
    tiles = e[:h, :w].reshape(h // block, block, w // block, block).mean(axis=(1, 3)).ravel()
    mean = float(np.mean(tiles))
    if tiles.size < 2 or mean <= 0:
        return float("inf")
    return 0.5 * float(np.std(tiles, ddof=1)) / (math.sqrt(tiles.size) * mean)

def cost_per_sample(samples, cpu_seconds):
    """Theil–Sen slope of CPU seconds against samples: the median of all pairwise slopes."""
    slopes = [(t1 - t0) / (n1 - n0) for i, (n0, t0) in enumerate(zip(samples, cpu_seconds))
              for n1, t1 in list(zip(samples, cpu_seconds))[i + 1:] if n1 != n0]
    if not slopes:
        return cpu_seconds[0] / samples[0]
    return max(float(np.median(slopes)), 1e-12)


def render_times(samples, cpu_seconds):
    """(setup, times): the per-render set-up estimated as 2·t(1) − t(2) (clamped to [0, t(1)]; the cost of
    the first sample is then t(1) − setup) and each render's CPU time less it."""
    t = dict(zip(samples, cpu_seconds))
    setup = min(max(2.0 * t[1] - t[2], 0.0), t[1]) if 1 in t and 2 in t else 0.0
    return setup, [max(c - setup, 1e-9) for c in cpu_seconds]


def fit(samples, errs, ref_noise_fractions):
    """Least-squares line log(error) = s·log(n) + b on the counts n ≥ MIN_SAMPLES_FIT whose reference noise is
    negligible (REF_NOISE_MAX). Returns dict(slope, sigma, intercept, points) or None with fewer than 3 points.
    Since time = c·n, s is also the exponent of error ∝ time^s. σ_s is the regression's standard error; the
    points are one progressive sequence (nested samples for a fixed seed), so it is a lower bound."""
    pts = [(n, e) for n, e, f in zip(samples, errs, ref_noise_fractions)
           if n >= MIN_SAMPLES_FIT and e > 0 and f <= REF_NOISE_MAX]
    if len(pts) < 3:
        return None
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    (slope, intercept), cov = np.polyfit(x, y, 1, cov="unscaled")
    resid = y - (slope * x + intercept)
    dof = len(pts) - 2
    sigma = math.sqrt(float(cov[0, 0]) * float(resid @ resid) / dof) if dof > 0 else float("inf")
    return {"slope": float(slope), "sigma": sigma, "intercept": float(intercept), "points": len(pts)}


def fit_is_usable(line):
    """A fit that may extrapolate: a decreasing error, a slope in the range any of these estimators can have
    (−1.5 … −0.2: QMC on smooth integrands is at best about n^−1.5 in RMSE) and an uncertainty under 0.15."""
    return (line is not None and -1.5 <= line["slope"] <= -0.2 and line["sigma"] <= 0.15)


def extrapolation_factor(line):
    """F_max: how far beyond the last measured time the fit may be followed (see the bound above)."""
    if not fit_is_usable(line):
        return 1.0
    if line["sigma"] <= 0:
        return F_CAP
    log_f = math.log(TIME_TOLERANCE) * abs(line["slope"]) / line["sigma"]   # in logs: 1.3^(|s|/σ) overflows
    return max(1.0, math.exp(min(math.log(F_CAP), log_f)))


def time_to(target, samples, times, errs, line):
    """(seconds, how): the time to reach `target` error. how = "measured" (interpolated between two measured
    points, log-log), "extrapolated" (past the last point, from the fit, within F_max), or "beyond" (not
    reached within the trusted range: seconds is then the last measured time, shown as "> t")."""
    pts = [(t, e) for t, e in zip(times, errs) if t > 0 and e > 0]
    n_max = max(samples)
    if not pts:
        return None, "beyond"
    if pts[0][1] <= target:
        return pts[0][0], "measured"
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e0 >= target >= e1 and e1 < e0:
            f = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0))), "measured"
    t_max = pts[-1][0]
    if any(e <= target for _, e in pts):   # reached, then lost again (noise): the first crossing counts
        return next(t for t, e in pts if e <= target), "measured"
    factor = extrapolation_factor(line)
    if factor > 1.0:
        # Follow the fitted line beyond n_max (its value there is steadier than the last point's):
        # t = t_max · (target / e_fit(n_max))^(1/s).
        e_fit = math.exp(line["intercept"] + line["slope"] * math.log(n_max))
        t = max(t_max, t_max * (target / e_fit) ** (1.0 / line["slope"]))
        if t <= factor * t_max:
            return t, "extrapolated"
    return t_max, "beyond"


def crossing(target, samples, times, errs, line, err_log_sigmas=None):
    """How the time to `target` was found, for the reader of the report: (text, σ of log(time) or None).
    text = "interpolated N–2N spp" (between the two measured counts whose errors bracket the target, log-log),
    "at N spp" (the first count is already below it), "first at N spp" (reached, then lost again by noise),
    "extrapolated ×F past N spp" (along the fit, F = t / t_last), or "not reached by N spp". σ (interpolated
    crossings only, with `err_log_sigmas` the σ of log(error) of each point): an error figure off by δ in logs moves
    the crossing by δ/|s| in log time, s the local slope between the bracketing points; the larger σ of the two
    is taken. The render times' own scatter (the load) is not in it."""
    pts = [(n, t, e, (err_log_sigmas or [0.0] * len(errs))[i])
           for i, (n, t, e) in enumerate(zip(samples, times, errs)) if t > 0 and e > 0]
    if not pts:
        return "no data", None
    if pts[0][2] <= target:
        return f"at {pts[0][0]} spp", None
    for (n0, t0, e0, s0), (n1, t1, e1, s1) in zip(pts, pts[1:]):
        if e0 >= target >= e1 and e1 < e0:
            slope = (math.log(e1) - math.log(e0)) / (math.log(t1) - math.log(t0)) if t1 != t0 else float("-inf")
            sigma = max(s0, s1) / abs(slope) if math.isfinite(slope) and slope != 0 else None
            return f"interpolated {n0}–{n1} spp", sigma
    if any(e <= target for _, _, e, _ in pts):
        return f"first at {next(n for n, _, e, _ in pts if e <= target)} spp", None
    t, how = time_to(target, samples, times, errs, line)
    if how == "extrapolated":
        return f"extrapolated ×{t / pts[-1][1]:.2g} past {pts[-1][0]} spp", None
    return f"not reached by {pts[-1][0]} spp", None


def reference_integrator_for(features_line):
    """(integrator, why) for a Candela reference, from AUTO's "Auto: scene features:" log line (docs/auto.md,
    "Acceptance"): ("BDPT", …) where the analysis finds caustic paths (L S+ D) and a light no ray can hit (point, spot,
    sun: `unhittable`) and no object hidden from some ray type; else (None, …): PATH. PATH cannot build light → delta
    surface(s) → diffuse paths from such a light, so its image lacks those caustics altogether, and a reference that
    lacks a path class makes every integrator that renders it look wrong (window_glass: the sun's caustic under a
    glass sphere); BDPT's light subpaths carry them, and BDPT is unbiased for every path PATH samples. BDPT cannot
    honour per-ray-type visibility, hence PATH where objects are hidden."""
    m = re.search(r"unhittable (\d+),", features_line)
    unhittable = int(m.group(1)) if m else 0
    caustic = "caustic paths yes" in features_line
    hidden = re.search(r"hidden ray types 0x([0-9a-f]+)", features_line)
    if caustic and unhittable > 0 and (hidden is None or int(hidden.group(1), 16) == 0):
        return "BDPT", (f"{unhittable} light(s) no ray can hit and caustic paths (L S+ D): PATH cannot sample "
                        "their caustics")
    return None, "PATH samples every path class the analysis finds"
