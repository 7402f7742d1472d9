"""`make bench`'s pipeline in quick mode: tiny renders, so the numbers say nothing about speed, but every stage
must run and report (the paired rounds, the brightness comparison, the raw Embree rate, the export numbers)."""

import json
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "bench"))

import bench  # noqa: E402


def test_paired_ratios_pair_rounds_and_skip_unmeasured_ones():
    rounds = [{"samples_per_second": {"A": 4.0, "B": 2.0}},
              {"samples_per_second": {"A": 3.0}},                 # B not measured in this round
              {"samples_per_second": {"A": 9.0, "B": 3.0}}]
    assert bench.paired_ratios(rounds, "A", "B") == [2.0, 3.0]
    assert bench.median([3.0, 1.0, 2.0]) == 2.0
    assert bench.median([4.0, 1.0, 2.0, 3.0]) == 2.5
    assert bench.median([]) is None


def test_round_rates_use_each_rounds_own_renders():
    # 10x10 pixels, 4 -> 20 samples: 1600 samples more; round 0 takes 1 s for them, round 1 takes 2 s.
    runs = [{"samples": 4, "seconds": 0.5, "repeat": 0}, {"samples": 20, "seconds": 1.5, "repeat": 0},
            {"samples": 4, "seconds": 0.5, "repeat": 1}, {"samples": 20, "seconds": 2.5, "repeat": 1}]
    configs = {"A": {"width": 10, "height": 10, "runs": runs}}
    rounds = bench.round_rates(configs, [{"round": 0}, {"round": 1}], 4, 20)
    assert [r["samples_per_second"]["A"] for r in rounds] == [1600.0, 800.0]


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    build = os.environ.get("CANDELA_BUILD_DIR", os.path.join(ROOT, "build"))
    out = tmp_path_factory.mktemp("bench")
    cmd = [sys.executable, os.path.join(ROOT, "bench", "bench.py"), "--build", build, "--outdir", str(out),
           "--size", "48", "--samples", "8", "--rounds", "2", "--rays", "200000",
           "--export-triangles", "20000", "--instances", "20", "--scene-size", "24"]
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    with open(out / "bench.json") as f:
        return json.load(f), proc.stdout


def test_every_stage_reports(report):
    rep, stdout = report
    assert rep["errors"] == []
    assert set(rep["engines"]) == {"CYCLES", "CANDELA", "CANDELA_POWER"}
    assert len(rep["rounds"]) == 2
    assert [r["order"] for r in rep["rounds"]] == [["CYCLES", "CANDELA", "CANDELA_POWER"],
                                                   ["CANDELA_POWER", "CANDELA", "CYCLES"]]
    res = rep["results"]
    for key in ("cycles_samples_per_second", "candela_samples_per_second", "candela_power_samples_per_second",
                "raw_rays_per_second", "speed_ratio", "brightness_ratio", "light_tracer_rays_per_second"):
        assert res[key] is not None and res[key] > 0, key
    assert rep["export"]["export"]["best"]["triangles"] == 20000
    assert "paired speed ratio" in stdout
    assert "light tracer share of raw" in stdout
    # SPPM against PATH, both scenes of candela_bench_sppm.
    assert [r["scene"] for r in rep["sppm"]] == ["cornell", "caustic"]
    assert all(r["sppm_cpu_seconds"] > 0 and r["path_cpu_seconds"] > 0 for r in rep["sppm"])
    # The per-scene speed table: every accuracy scene, all three configurations measured.
    assert "per-scene samples/s" in stdout
    assert [r["scene"] for r in rep["scenes"]] == ["cornell_box", "soft_shadow", "veach_mis", "glossy", "room_window",
                                                   "caustic", "door"]
    for row in rep["scenes"]:
        assert "error" not in row, row
        assert row["width"] == 24 and row["height"] > 0, row
        # Rates come from time differences of tiny renders here: timing noise may leave one unmeasurable (None).
        for key in ("cycles", "candela", "candela_equal", "default_ratio", "equal_ratio"):
            assert row[key] is None or row[key] > 0, (row["scene"], key)


def test_the_equal_run_uses_cycles_light_selection_and_roulette(report):
    rep, _ = report
    eq = rep["engines"]["CANDELA_POWER"]["settings"]
    assert eq["light_selection"] == "POWER" and eq["rr_mode"] == "SQRT_THROUGHPUT"
    # Cycles' roulette runs at vertices whose bounce count exceeds min_light_bounces (bounce 0 = the first
    # vertex); Candela's arrival roulette runs at vertex v when v + 1 >= rr_start_bounce.
    assert eq["rr_start_bounce"] == rep["engines"]["CYCLES"]["settings"]["min_light_bounces"] + 2
    # Settings of one configuration must not leak into the next (the defaults run keeps the scene's own).
    default = rep["engines"]["CANDELA"]["settings"]
    assert (default["light_selection"], default["rr_mode"]) != ("POWER", "SQRT_THROUGHPUT")


def test_images_are_finite_and_agree_in_brightness(report):
    rep, _ = report
    for name, e in rep["engines"].items():
        for s, img in e["images"].items():
            assert img["finite"], (name, s)
    # The tolerance from the renders' own noise. Candela estimates its image's relative RMSE per pixel (ε, from its
    # two noise replicates); the image mean's relative standard error is then ε/√P over P pixels (pixels are
    # independent). Cycles traces the same paths (path tracing, NEE + MIS, the same roulette at equal settings),
    # so its error is taken as at most twice Candela's (a generous margin: docs/parity.md measures them equal within
    # a few per cent). The ratio of the two means then has σ ≤ ε/√P·√(1 + 2²); the band is 5σ (two-sided false
    # alarm 6e-7) plus the parity suite's 2 % for a real systematic difference.
    can = rep["engines"]["CANDELA"]
    eps = max(float((r.get("native_stats") or {}).get("relative_error") or 0.0)
              for r in can["runs"] if r["samples"] == max(int(k) for k in can["images"]))
    assert eps > 0.0, "Candela reported no noise estimate"
    img = can["images"][str(max(int(k) for k in can["images"]))]
    sigma = eps / (img["width"] * img["height"]) ** 0.5 * (1.0 + 2.0 ** 2) ** 0.5
    assert abs(rep["results"]["brightness_ratio"] - 1.0) < 0.02 + 5.0 * sigma, (rep["results"]["brightness_ratio"], sigma)
