"""`make bench`, step 5: samples per second on every scene of the accuracy report, Candela against Cycles.

For each scene of examples/scenes.py that `make accuracy` measures, one Blender process (bench/render_timed.py
--scene) renders Cycles, Candela at its defaults and Candela at Cycles 3.4's light selection and roulette (the
bench's "equal settings", bench/bench.py) at S1 and S2 samples, in paired rounds of alternating order, and each
configuration's samples/s = W·H·(S2 − S1)/(t2 − t1) (setup cancels). The ratio per scene is the median over the
rounds of each round's Candela/Cycles ratio (renders seconds apart share the machine's load). Issue 22's target:
at equal settings Candela's time per sample ≤ 0.5× Cycles', i.e. the ratio ≥ 2 on every scene.
"""

import os

SCENES = ["cornell_box", "soft_shadow", "veach_mis", "glossy", "room_window", "caustic", "door"]
SPEED_TARGET = 2.0


def scene_speed(bench, launcher, outdir, threads, size=128, s1=8, s2=24, rounds=3, scenes=None,
                equal_config=None):
    """Renders every scene, prints the table and returns its rows ({scene, width, height, cycles, candela,
    candela_equal (samples/s), default_ratio, equal_ratio (paired medians)}); `bench` is bench/bench.py's module
    (its run/find_json/round_rates helpers)."""
    rows = []
    configs = ["CYCLES=CYCLES", "CANDELA=CANDELA", "CANDELA_POWER=" + equal_config]
    print(f"[5] per-scene speed: {size} px wide, {s1} and {s2} spp, {rounds} paired rounds, "
          f"Cycles / Candela defaults / Candela at equal settings")
    for name in scenes or SCENES:
        args = ["--scene", name, "--samples", f"{s1},{s2}", "--out", os.path.join(outdir, "scenes", name),
                "--threads", str(threads), "--repeats", str(rounds), "--size", str(size)]
        for c in configs:
            args += ["--config", c]
        rc, out = bench.run(bench.blender_cmd(launcher, os.path.join(bench.HERE, "render_timed.py"), args),
                            os.path.join(outdir, f"scene_{name}.log"))
        res = bench.find_json(out)
        if rc != 0 or res is None:
            print(f"    {name}: the renders failed:\n" + bench.tail(out))
            rows.append({"scene": name, "error": f"exit {rc}"})
            continue
        rounds_ = bench.round_rates(res["configs"], res["rounds"], s1, s2)
        row = {"scene": name, "width": res.get("width"), "height": res.get("height"),
               "cycles": bench.rate(res["configs"].get("CYCLES"), s1, s2),
               "candela": bench.rate(res["configs"].get("CANDELA"), s1, s2),
               "candela_equal": bench.rate(res["configs"].get("CANDELA_POWER"), s1, s2),
               "default_ratio": bench.median(bench.paired_ratios(rounds_, "CANDELA", "CYCLES")),
               "equal_ratio": bench.median(bench.paired_ratios(rounds_, "CANDELA_POWER", "CYCLES"))}
        rows.append(row)
        print(f"    {name:12s} Cycles {bench.fmt_rate(row['cycles'])}, Candela {bench.fmt_rate(row['candela'])} "
              f"({bench.fmt(row['default_ratio'], '.2f')}x), equal settings {bench.fmt_rate(row['candela_equal'])} "
              f"({bench.fmt(row['equal_ratio'], '.2f')}x)", flush=True)
    return rows


def table_lines(rows):
    """The per-scene table for the results section (Markdown-like, one line per scene)."""
    lines = ["per-scene samples/s, Candela / Cycles (paired medians; target at equal settings >= "
             f"{SPEED_TARGET:.1f}):",
             f"    {'scene':12s} {'Cycles':>10s} {'Candela':>10s} {'ratio':>6s} {'equal':>10s} {'ratio':>6s}  target"]
    for r in rows:
        if "error" in r:
            lines.append(f"    {r['scene']:12s} failed ({r['error']})")
            continue
        ok = r["equal_ratio"] is not None and r["equal_ratio"] >= SPEED_TARGET
        lines.append(f"    {r['scene']:12s} {_rate(r['cycles']):>10s} {_rate(r['candela']):>10s} "
                     f"{_ratio(r['default_ratio']):>6s} {_rate(r['candela_equal']):>10s} "
                     f"{_ratio(r['equal_ratio']):>6s}  {'met' if ok else 'NOT met'}")
    return lines


def _rate(x):
    return "n/a" if x is None else f"{x / 1e3:.0f} k/s"


def _ratio(x):
    return "n/a" if x is None else f"{x:.2f}x"
