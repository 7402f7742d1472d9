"""bench/accuracy_stats.py: the report's statistics on synthetic data with known answers (no rendering)."""

import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
import accuracy_stats as st  # noqa: E402

COUNTS = [1, 2, 4, 8, 16, 32, 64]


def test_cost_per_sample_ignores_setup_and_one_outlier():
    cpu = [0.5 + 0.01 * n for n in COUNTS]
    cpu[4] *= 3.0                      # one render slowed by another job
    assert abs(st.cost_per_sample(COUNTS, cpu) - 0.01) < 1e-12


def test_fit_recovers_slope_and_skips_noisy_reference():
    errs = [0.8 * n ** -0.5 for n in COUNTS]
    errs[-1] = 0.9                     # reference noise dominates there: must be left out
    frac = [0.0] * (len(COUNTS) - 1) + [0.5]
    line = st.fit(COUNTS, errs, frac)
    assert line["points"] == 4 and abs(line["slope"] + 0.5) < 1e-9 and line["sigma"] < 1e-9


def test_extrapolation_is_bounded():
    errs = [0.8 * n ** -0.5 for n in COUNTS]            # 0.1 at 64 samples
    times = [0.01 * n for n in COUNTS]
    line = st.fit(COUNTS, errs, [0.0] * len(COUNTS))
    t, how = st.time_to(0.06, COUNTS, times, errs, line)  # needs (0.1/0.06)^2 = 2.8x: inside F_CAP = 3.7
    assert how == "extrapolated" and math.isclose(t, 0.64 * (0.1 / 0.06) ** 2, rel_tol=1e-9)
    t, how = st.time_to(0.02, COUNTS, times, errs, line)  # needs 25x: refused
    assert how == "beyond" and t == times[-1]


def test_uncertain_or_absurd_slopes_are_not_extrapolated():
    rng = np.random.default_rng(1)
    errs = [10.0 * n ** -1.4 * math.exp(rng.normal(0, 0.8)) for n in COUNTS]
    line = st.fit(COUNTS, errs, [0.0] * len(COUNTS))
    assert not st.fit_is_usable(line) and st.extrapolation_factor(line) == 1.0
    t, how = st.time_to(1e-6, COUNTS, [0.01 * n for n in COUNTS], errs, line)
    assert how == "beyond"


def test_interpolated_time_is_measured():
    errs = [0.8 * n ** -0.5 for n in COUNTS]
    t, how = st.time_to(0.8 / math.sqrt(3.0), COUNTS, [0.01 * n for n in COUNTS], errs, None)
    assert how == "measured" and math.isclose(t, 0.03, rel_tol=1e-9)


def test_errors_subtract_reference_noise_and_trim():
    rng = np.random.default_rng(2)
    truth = np.full((64, 64), 2.0)
    a = truth + rng.normal(0, 0.05, truth.shape)
    b = truth + rng.normal(0, 0.05, truth.shape)
    img = truth + rng.normal(0, 0.2, truth.shape)
    e = st.errors(img, a, b)
    # True rel. RMSE 0.2/2 = 0.1; the estimate of mean(d²) over 4096 pixels has a relative standard error
    # √(2/4096) ≈ 2.2 %, so the RMSE is within 1.1 % at 1σ: 5 % is over 4σ.
    assert abs(e["rrmse"] - 0.1) < 0.005
    img[0, 0] = 1e3                    # one firefly: dominates rrmse, not the trimmed figure
    e = st.errors(img, a, b)
    assert e["rrmse"] > 1.0 and e["robust"] < 0.1


def test_render_times_drop_the_setup():
    cpu = [0.3 + 0.01 * n for n in COUNTS]
    setup, times = st.render_times(COUNTS, cpu)
    assert math.isclose(setup, 0.3, rel_tol=1e-9)
    assert all(math.isclose(t, 0.01 * n, rel_tol=1e-9) for t, n in zip(times, COUNTS))


def test_crossing_says_interpolated_or_extrapolated():
    errs = [0.8 * n ** -0.5 for n in COUNTS]            # 0.1 at 64 samples
    times = [0.01 * n for n in COUNTS]
    line = st.fit(COUNTS, errs, [0.0] * len(COUNTS))
    text, sigma = st.crossing(0.8 / math.sqrt(3.0), COUNTS, times, errs, line, [0.02] * len(COUNTS))
    assert text == "interpolated 2–4 spp" and math.isclose(sigma, 0.04, rel_tol=1e-9)  # δ/|s| = 0.02/0.5
    assert st.crossing(0.06, COUNTS, times, errs, line)[0] == "extrapolated ×2.8 past 64 spp"
    assert st.crossing(0.02, COUNTS, times, errs, line)[0] == "not reached by 64 spp"
    assert st.crossing(0.9, COUNTS, times, errs, line)[0] == "at 1 spp"
    bumpy = errs[:4] + [0.05, 0.3, 0.3]                   # below 0.06 at 16 spp only
    assert st.crossing(0.06, COUNTS, times, bumpy, None)[0] == "interpolated 8–16 spp"


FEATURES = ("Auto: scene features: lights {n} (unhittable {u}, delta 0, small 0, large 1, zero-power 0; power share "
            "unhittable 50 %, small 0 %), world constant; area: diffuse 90 %, glossy 0 %, specular 5 %, transmissive 5 "
            "%, emissive 0.0 %; caustic paths {c}; camera perspective; hidden ray types 0x{h}")


def test_reference_integrator_is_bdpt_only_for_caustics_from_lights_no_ray_hits():
    # window_glass: a sun (unhittable) and a glass sphere → BDPT
    assert st.reference_integrator_for(FEATURES.format(n=2, u=1, c="yes", h=0))[0] == "BDPT"
    # caustic paths from a small area light only (hittable: PATH samples them, if slowly) → PATH
    assert st.reference_integrator_for(FEATURES.format(n=1, u=0, c="yes", h=0))[0] is None
    # a sun but no delta surface → PATH
    assert st.reference_integrator_for(FEATURES.format(n=1, u=1, c="no", h=0))[0] is None
    # hidden objects: BDPT cannot honour them → PATH
    assert st.reference_integrator_for(FEATURES.format(n=1, u=1, c="yes", h=2))[0] is None
    # no analysis line (a failed features run) → PATH
    assert st.reference_integrator_for("")[0] is None
