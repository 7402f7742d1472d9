"""`make install-addon` (bin/install-addon) never puts an incomplete add-on where Blender loads it: a truncated
native module (which crashes Blender at start-up with SIGBUS) is caught in the copy and in the build."""

import importlib.machinery
import importlib.util
import os
import shutil
from pathlib import Path

import pytest

import scenes

BUILD = Path(os.environ.get("CANDELA_BUILD_DIR", os.path.join(scenes.REPO, "build")))
SOURCE = BUILD / "scripts" / "addons" / "candela"


def installer():
    loader = importlib.machinery.SourceFileLoader("install_addon", os.path.join(scenes.REPO, "bin", "install-addon"))
    spec = importlib.util.spec_from_loader("install_addon", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def truncate(path, keep=0.5):
    size = path.stat().st_size
    with open(path, "r+b") as f:
        f.truncate(int(size * keep))


def test_install_copies_a_checked_addon(tmp_path):
    inst = installer()
    dest = tmp_path / "scripts" / "addons" / "candela"
    assert inst.main(["--build", str(BUILD), "--dest", str(dest)]) == 0
    for rel in inst.files(SOURCE):
        assert (dest / rel).read_bytes() == (SOURCE / rel).read_bytes(), rel
    assert not dest.with_name("candela.installing").exists() and not dest.with_name("candela.previous").exists()


def test_a_truncated_copy_is_caught(tmp_path):
    inst = installer()
    copy = tmp_path / "copy"
    shutil.copytree(SOURCE, copy)
    truncate(inst.native_module(copy))
    with pytest.raises(inst.InstallError, match=r"_native.*differs from the build"):
        inst.verify_copy(SOURCE, copy)


def test_a_truncated_build_leaves_the_installed_addon_alone(tmp_path):
    inst = installer()
    dest = tmp_path / "addons" / "candela"
    assert inst.main(["--build", str(BUILD), "--dest", str(dest)]) == 0
    before = {rel: (dest / rel).read_bytes() for rel in inst.files(dest)}
    broken_build = tmp_path / "build"
    shutil.copytree(SOURCE, broken_build / "scripts" / "addons" / "candela")
    truncate(inst.native_module(broken_build / "scripts" / "addons" / "candela"))
    assert inst.main(["--build", str(broken_build), "--dest", str(dest)]) == 1
    assert {rel: (dest / rel).read_bytes() for rel in inst.files(dest)} == before
