"""The add-on refuses to import a native module built for CPU features this machine lacks (a SIGILL would kill
Blender): addon/candela/native.py reads the features the build wrote next to the module (`_native.cpu`)."""
import importlib.util
import os

from conftest import BUILD

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def addon_native():
    spec = importlib.util.spec_from_file_location("candela_native_py", os.path.join(ROOT, "addon", "candela", "native.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def staged_requirements():
    return os.path.join(BUILD, "scripts", "addons", "candela", "_native.cpu")


def test_the_build_writes_its_cpu_requirements():
    with open(staged_requirements()) as f:
        flags = f.read().split()
    with open(os.path.join(BUILD, "CMakeCache.txt")) as f:
        arch = next(line.split("=", 1)[1].strip() for line in f if line.startswith("CANDELA_TARGET_ARCH"))
    if arch == "x86-64-v3":
        assert {"avx2", "fma", "bmi2", "movbe"} <= set(flags)
        assert "avx512f" not in flags


def test_this_machine_runs_its_own_build():
    assert addon_native().missing_cpu_features(staged_requirements()) == []


def test_a_cpu_without_avx2_is_refused(tmp_path):
    needed = tmp_path / "needed.cpu"
    needed.write_text("sse4_2\navx\navx2\nfma\n")
    cpuinfo = tmp_path / "cpuinfo"
    cpuinfo.write_text("processor\t: 0\nflags\t\t: fpu sse sse2 ssse3 sse4_1 sse4_2 avx\n")
    assert addon_native().missing_cpu_features(str(needed), str(cpuinfo)) == ["avx2", "fma"]


def test_no_check_where_the_files_cannot_be_read(tmp_path):
    assert addon_native().missing_cpu_features(str(tmp_path / "none"), str(tmp_path / "none2")) == []
