"""candela._native seen from Python: validation errors, progress, cancel latency, GIL release, passes,
and the CLI rendering a dump to the same image as the module."""
import subprocess
import threading
import time

import numpy as np
import pytest

from conftest import BUILD, box_scene, params, write_dump


def render(native, arrays, prms):
    s = native.Session(arrays, prms)
    s.start()
    s.join()
    assert s.error is None
    return s


def test_capabilities_publish_layouts(native):
    caps = native.capabilities()
    assert "PATH" in [entry[0] for entry in caps["integrators"]]
    # Each integrator publishes its settings (key, label, type, default, range or items, group).
    path = {spec["key"]: spec for spec in caps["integrator_params"]["PATH"]}
    assert path["max_bounces"]["type"] == "INT" and path["max_bounces"]["min"] == 0
    assert [item[0] for item in path["light_selection"]["items"]] == ["ALL", "UNIFORM", "AREA", "POWER", "TREE", "WARD"]
    assert {spec["key"] for spec in caps["common_params"]} >= {"samples", "seed", "sampler", "noise_threshold"}
    assert caps["light_types"] == {"POINT": 0, "SPOT": 1, "SUN": 2, "AREA": 3}
    assert set(caps["pixel_filters"]) == {"BOX", "GAUSSIAN", "BLACKMAN_HARRIS"}


def test_render_gives_bottom_up_rgba(native):
    s = render(native, box_scene(), params())
    img = s.get_pass("Combined")
    assert img.shape == (32 * 24, 4) and img.dtype == np.float32
    assert np.isfinite(img).all() and img[:, :3].mean() > 0
    assert np.all(img[:, 3] == 1.0)
    assert s.progress()["phase"] == "done" and s.progress()["fraction"] == 1.0
    st = s.stats()
    assert st["paths"] == 32 * 24 * 8 and st["rays"] > st["paths"] and st["nan_samples"] == 0


@pytest.mark.parametrize("mutate, message", [
    (lambda a: a.update(triangles=np.array([[0, 1, 99]], np.uint32), tri_material=np.zeros(1, np.uint32),
                        mesh_tri_start=np.array([0, 1, 1], np.uint32)), "triangles[0]"),
    (lambda a: a["positions"].__setitem__((2, 1), np.nan), "positions[2]"),
    (lambda a: a.pop("camera_to_world"), "camera_to_world"),
    (lambda a: a.update(positions=np.zeros((4, 2), np.float32)), "positions"),
])
def test_bad_arrays_raise_value_error_naming_the_array(native, mutate, message):
    arrays = box_scene()
    mutate(arrays)
    with pytest.raises(ValueError, match=message.replace("[", r"\[").replace("]", r"\]")):
        native.Session(arrays, params())


@pytest.mark.parametrize("bad, message", [
    ({"width": 0}, "resolution"),
    ({"pixel_filter": "TENT"}, "pixel_filter"),
    ({"integrator": "NOPE"}, "integrator"),
    ({"samples": "many"}, "samples"),
    ({"crop_x0": 30, "crop_x1": 10}, "border"),
])
def test_bad_params_raise_value_error(native, bad, message):
    with pytest.raises(ValueError, match=message):
        native.Session(box_scene(), params(**bad))


def test_unknown_params_are_reported(native):
    s = native.Session(box_scene(), params(smaples=4))
    assert any("smaples" in line for line in s.take_log())


def test_log_entries_tell_info_lines_from_warnings(native):
    # The box has no Transparent material: the session says what it skips (info), and warns of the unknown key.
    s = render(native, box_scene(), params(smaples=4))
    entries = s.take_log_entries()
    assert all(level in ("INFO", "WARNING") for level, _ in entries)
    warnings = [m for level, m in entries if level == "WARNING"]
    info = [m for level, m in entries if level == "INFO"]
    assert any("smaples" in m for m in warnings), entries
    assert any(m.startswith("Skipped, the scene does not need them") for m in info), entries
    assert not any("Skipped" in m for m in warnings), entries
    assert s.take_log_entries() == [] and s.take_log() == []   # drained


def test_cli_prints_info_lines_as_info_and_leaves_them_out_with_q(native, tmp_path):
    write_dump(tmp_path / "dump", box_scene(), params(threads=1, smaples=4))
    cli = [str(BUILD / "bin" / "candela"), str(tmp_path / "dump"), "-o", str(tmp_path / "out.exr")]
    loud = subprocess.run(cli, capture_output=True, text=True, timeout=60)
    quiet = subprocess.run(cli + ["-q"], capture_output=True, text=True, timeout=60)
    assert loud.returncode == 0 and quiet.returncode == 0, loud.stderr + quiet.stderr
    assert "info: Skipped, the scene does not need them" in loud.stderr
    assert "warning: Skipped" not in loud.stderr and "Skipped" not in quiet.stderr
    assert "smaples" in quiet.stderr   # warnings stay


def test_unknown_arrays_are_reported(native):
    arrays = box_scene()
    arrays["positons"] = np.zeros((1, 3), np.float32)
    s = native.Session(arrays, params())
    assert any("positons" in line for line in s.take_log())


def test_cancel_stops_within_100_ms_and_keeps_the_partial_image(native):
    s = native.Session(box_scene(), params(width=256, height=256, samples=100000, max_bounces=12))
    s.start()
    while s.progress()["samples_done"] < 1:
        time.sleep(0.01)
    t0 = time.perf_counter()
    s.cancel()
    assert s.wait(2.0)
    latency = time.perf_counter() - t0
    assert latency < 0.1, f"cancel took {latency * 1000:.0f} ms"
    assert s.progress()["phase"] == "cancelled"
    img = s.get_pass("Combined")
    assert img[:, :3].mean() > 0  # the partial image survives


def test_wait_releases_the_gil(native):
    s = native.Session(box_scene(), params(width=128, height=128, samples=20000))
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.005)

    t = threading.Thread(target=ticker)
    t.start()
    s.start()
    s.wait(0.3)
    stop.set()
    t.join()
    s.cancel()
    s.join()
    assert len(ticks) > 20  # Python ran while the render thread worked and wait() blocked


def test_same_seed_same_image_and_seed_changes_it(native):
    a = render(native, box_scene(), params()).get_pass("Combined")
    b = render(native, box_scene(), params()).get_pass("Combined")
    c = render(native, box_scene(), params(seed=2)).get_pass("Combined")
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)


def test_border_renders_the_window_of_the_full_frame(native):
    full = render(native, box_scene(), params()).get_pass("Combined").reshape(24, 32, 4)
    s = render(native, box_scene(), params(crop_x0=8, crop_x1=20, crop_y0=4, crop_y1=16))
    part = s.get_pass("Combined").reshape(12, 12, 4)
    assert (s.width, s.height) == (12, 12)
    assert np.array_equal(part, full[4:16, 8:20])  # same pixels, same samples


def test_cli_renders_a_dump_to_the_same_image(native, tmp_path):
    arrays, prms = box_scene(), params(threads=1)
    write_dump(tmp_path / "dump", arrays, prms)
    out = tmp_path / "out.exr"
    proc = subprocess.run([str(BUILD / "bin" / "candela"), str(tmp_path / "dump"), "-o", str(out), "--threads", "2"],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    assert "samples/s" in proc.stdout
    from_cli = native.read_exr(str(out))
    from_module = render(native, arrays, prms).get_pass("Combined").reshape(24, 32, 4)
    assert np.array_equal(from_cli, from_module)  # two threads in the CLI, one in the module


def test_cli_reports_bad_dumps(tmp_path):
    proc = subprocess.run([str(BUILD / "bin" / "candela"), str(tmp_path / "missing")], capture_output=True, text=True)
    assert proc.returncode == 1 and "not a directory" in proc.stderr


def test_vertex_normals_equal_the_same_normals_per_corner(native):
    """`vertex_normals` (V, 3) is a compact form of `normals` (T, 3, 3): the same smooth normals give the same
    image, bit for bit; and normals that differ per vertex do change the image (so the array is used)."""
    a = box_scene()
    V, T = len(a["positions"]), len(a["triangles"])
    rng = np.random.default_rng(3)
    vn = np.array([0.0, 0.0, 1.0], np.float32) + 0.3 * rng.standard_normal((V, 3)).astype(np.float32)
    vn /= np.linalg.norm(vn, axis=1, keepdims=True)
    a["tri_smooth"] = np.ones(T, np.uint8)
    per_vertex = dict(a, vertex_normals=vn)
    per_corner = dict(a, normals=vn[a["triangles"]])
    imgs = [render(native, scene, params()).get_pass("Combined") for scene in (per_vertex, per_corner)]
    assert np.array_equal(imgs[0], imgs[1])
    flat = render(native, a, params()).get_pass("Combined")
    assert not np.array_equal(imgs[0], flat)


def test_vertex_normals_need_one_row_per_position(native):
    a = box_scene()
    a["vertex_normals"] = np.zeros((len(a["positions"]) - 1, 3), np.float32)
    with pytest.raises(ValueError, match="vertex_normals"):
        native.Session(a, params())


def test_a_thousand_instances_cost_one_meshs_memory(native):
    """A mesh drawn by 1,000 instances is stored once (Embree instancing): the scene's memory (Embree's buffers
    and BVHs from its memory monitor, plus Candela's shading data) grows by a per-instance record only, far
    below a second copy of the mesh."""
    n = 64                                              # an n × n grid: 2n² = 8,192 triangles
    xs = np.linspace(-1, 1, n + 1, dtype=np.float32)
    gx, gy = np.meshgrid(xs, xs)
    pos = np.stack([gx, gy, np.zeros_like(gx)], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n), np.arange(n))
    v0 = (j * (n + 1) + i).ravel()
    tri = np.concatenate([np.stack([v0, v0 + 1, v0 + n + 2], -1), np.stack([v0, v0 + n + 2, v0 + n + 1], -1)])
    T = len(tri)

    def scene_bytes(count):
        a = box_scene()
        xf = np.tile(np.eye(4, dtype=np.float32), (count, 1, 1))
        xf[:, 0, 3] = np.arange(count, dtype=np.float32) * 3.0
        xf[:, 2, 3] = -4.0
        a.update(positions=pos, triangles=tri.astype(np.uint32), tri_material=np.zeros(T, np.uint32),
                 mesh_tri_start=np.array([0, T], np.uint32), instance_mesh=np.zeros(count, np.uint32),
                 instance_transform=xf)
        st = render(native, a, params(width=4, height=4, samples=1)).stats()
        assert st["unique_triangles"] == T and st["instanced_triangles"] == count * T
        return st["scene_bytes"]

    one, many = scene_bytes(1), scene_bytes(1000)
    # A second copy of the mesh would add at least its vertex and index buffers (12 + 12 bytes per triangle
    # here) and its BVH. An instance's budget is 320 bytes: Candela's record (three affine transforms, 144 bytes:
    # object-to-world, its inverse and the normal cofactor; ids, flags, Object Info colour/alpha/random and the
    # terminator offset, 48) and Embree's instance with its share of the top-level BVH (about 80).
    per_instance = 320
    assert one > 24 * T
    assert many - one < 1000 * per_instance < one


def test_irradiance_cache_reports_its_stage_records_and_pass(native):
    """The pre-pass shows as a stage in percent with the record count beside it, the count stays in the progress
    while rendering, the IC Records pass counts the same records, and the noise stop is refused with a log line
    (both noise replicates read one cache)."""
    s = native.Session(box_scene(), params(width=96, height=72, samples=4, integrator="IRRADIANCE_CACHE",
                                           ic_gather_rays=2048, passes="IC Records", noise_threshold=0.01))
    s.start()
    seen = []
    while not s.wait(0.002):
        p = s.progress()
        if p["stage"]:
            seen.append((p["stage"], p["stage_percent"], p["stage_done"], p["stage_total"]))
    assert s.error is None
    # The polling may miss a pre-pass shorter than its interval; the statistics keep every stage that ended.
    assert all(name == "Irradiance cache" and percent for name, percent, _, _ in seen)
    assert all(0 <= done <= total for _, _, done, total in seen)
    stages = s.stats()["stages"]
    assert [st["name"] for st in stages] == ["Irradiance cache"]
    assert stages[0]["runs"] == 1 and stages[0]["seconds"] > 0 and 0 < stages[0]["done"] == stages[0]["total"]
    p = s.progress()
    records = s.get_pass("IC Records")
    assert records.shape == (96 * 72, 1) and records.sum() > 0 and records.max() >= 1
    assert p["note"] == f"{int(records.sum())} records"
    assert p["relative_error"] is None and p["stop_reason"] == "samples"
    log = " ".join(s.take_log())
    assert "noise threshold is off" in log and "irradiance cache:" in log


def test_irradiance_cache_cancels_within_100_ms_in_the_pre_pass(native):
    s = native.Session(box_scene(), params(width=256, height=256, samples=16, integrator="IRRADIANCE_CACHE",
                                           ic_gather_rays=8192))
    s.start()
    while s.progress()["stage_done"] < 1:
        assert not s.wait(0.005), "the render ended before its pre-pass was seen: make the pre-pass longer"
    t0 = time.perf_counter()
    s.cancel()
    assert s.wait(2.0)
    latency = time.perf_counter() - t0
    print(f"irradiance cache pre-pass cancel latency {latency * 1000:.1f} ms")
    assert latency < 0.1, f"cancel took {latency * 1000:.0f} ms"
    assert s.progress()["phase"] == "cancelled" and s.progress()["stop_reason"] == "cancelled"


def test_sppm_reports_no_noise_estimate_and_path_does(native):
    """SPPM's two half-images share photons: no honest noise estimate, so the progress says "unavailable" (the status
    line shows n/a); PATH's estimate is there once a pass is done."""
    sppm = render(native, box_scene(), params(integrator="SPPM", samples=2, sppm_photons=2000))
    assert sppm.progress()["noise_unavailable"] is True and sppm.progress()["relative_error"] is None
    path = render(native, box_scene(), params())
    assert path.progress()["noise_unavailable"] is False and path.progress()["relative_error"] is not None
