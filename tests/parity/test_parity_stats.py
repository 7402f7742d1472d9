"""The parity check's statistics (tests/parity/parity_stats.py) on synthetic images with known truth: the
t quantiles, the tolerance being met or missed, the dark-block rule, and the false-alarm rate at the tolerance's
edge being the chosen level (checked at alpha = 0.05, where a few hundred trials resolve it)."""

import numpy as np
import pytest

import parity_stats as ps


def test_t_quantiles_match_tables():
    # Two-sided 95 % and 99 % points of Student's t (any statistics table), and the normal limit.
    assert ps.t_quantile(0.025, 10) == pytest.approx(2.2281, abs=1e-4)
    assert ps.t_quantile(0.005, 3) == pytest.approx(5.8409, abs=1e-4)
    assert ps.t_quantile(0.025, 1) == pytest.approx(12.7062, abs=1e-3)
    assert ps.t_quantile(0.025, float("inf")) == pytest.approx(1.95996, abs=1e-4)


def halves(rng, truth, sigma):
    """Two independent noisy renders of `truth` (H, W, 3) with per-pixel standard deviation `sigma` each."""
    return [truth + sigma * rng.standard_normal(truth.shape) for _ in range(2)]


def image(value=1.0, size=64):
    return np.full((size, size, 3), value, np.float64)


def test_equal_images_pass_and_a_biased_block_fails():
    rng = np.random.default_rng(1)
    truth = image()
    assert ps.compare(halves(rng, truth, 0.05), halves(rng, truth, 0.05))["pass"]
    biased = truth.copy()
    biased[:16, :16] *= 1.08          # one 16 × 16 block 8 % bright (block tolerance 5 %; σ of its mean ≈ 0.2 %)
    r = ps.compare(halves(rng, truth, 0.05), halves(rng, biased, 0.05))
    assert not r["pass"]
    failed = [b["region"] for b in r["blocks"] if not b["pass"]]
    assert failed == ["block30"]      # row 0 of the array is the bottom: the bottom-left block as displayed
    assert r["image"]["pass"]         # 8 % on 1/16 of the image is 0.5 %: within 2 %


def test_image_mean_tolerance_is_two_percent():
    rng = np.random.default_rng(2)
    truth = image()
    assert ps.compare(halves(rng, truth, 0.01), halves(rng, truth * 1.015, 0.01))["image"]["pass"]
    assert not ps.compare(halves(rng, truth, 0.01), halves(rng, truth * 1.03, 0.01))["image"]["pass"]


def test_noise_widens_the_tolerance_only_as_far_as_measured():
    rng = np.random.default_rng(3)
    truth = image(size=16)
    # 8 % bias in every block: caught with little noise, not provable with a lot (σ of a block mean ≈ 12 %).
    assert not ps.compare(halves(rng, truth, 0.02), halves(rng, truth * 1.08, 0.02))["pass"]
    r = ps.compare(halves(rng, truth, 2.0), halves(rng, truth * 1.08, 2.0))
    assert r["pass"]
    assert all(b["sigma"][0] > 0.05 for b in r["blocks"])


def test_dark_blocks_get_an_absolute_tolerance():
    rng = np.random.default_rng(4)
    truth = image()
    truth[:16, :16] = 0.001            # dark: 0.1 % of the image mean, below DARK = 5 %
    brighter = truth.copy()
    brighter[:16, :16] = 0.002         # doubled, but by 0.1 % of the image mean: fine
    assert ps.compare(halves(rng, truth, 0.001), halves(rng, brighter, 0.001))["pass"]
    lit = truth.copy()
    lit[:16, :16] = 0.2                # a light where Cycles has none: caught
    assert not ps.compare(halves(rng, truth, 0.001), halves(rng, lit, 0.001))["pass"]


def test_false_alarm_rate_at_the_edge_of_the_tolerance_is_alpha():
    """True difference exactly REL_IMAGE, noise comparable to it: the image check of one channel must fail in a
    fraction alpha of the trials (alpha = 0.05 here; 400 trials: ±3σ is ±0.033). (The whole image check fails
    in 1 − 0.95³ of them: each RGB channel is a check of its own.)"""
    rng = np.random.default_rng(5)
    truth = image(size=8)
    fails = 0
    trials = 400
    for _ in range(trials):
        r = ps.compare(halves(rng, truth, 0.2), halves(rng, truth * (1 + ps.REL_IMAGE), 0.2), alpha=0.05)
        fails += r["image"]["excess"][0] > 1.0
    rate = fails / trials
    assert 0.05 - 0.033 < rate < 0.05 + 0.033, rate


def test_noise_model_self_check_is_one_for_independent_pixels():
    rng = np.random.default_rng(6)
    truth = image()
    r = ps.compare(halves(rng, truth, 0.3), halves(rng, truth, 0.3))
    assert ps.z_rms(r["z_half"]) == pytest.approx(1.0, abs=0.25)


def test_a_channel_that_is_zero_in_cycles_tolerates_float_rounding_only():
    rng = np.random.default_rng(7)
    base = rng.uniform(0.2, 0.8, (16, 16, 3))
    base[..., 2] = 0.0
    cycles = (base, base.copy())
    close = base.copy()
    close[..., 2] = 1e-8
    assert ps.compare(cycles, (close, close.copy()))["pass"]
    far = base.copy()
    far[..., 2] = 1e-3
    assert not ps.compare(cycles, (far, far.copy()))["pass"]
