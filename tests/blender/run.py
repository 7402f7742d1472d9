"""Runs pytest inside Blender:

    bin/candela-blender -b --factory-startup -noaudio --python-exit-code 1 --python tests/blender/run.py -- \
        tests/blender/test_X.py [pytest args]

Falls back to a tiny runner (plain `test_*` functions, `tmp_path` only) if pytest cannot be imported.
"""

import inspect
import os
import sys
import tempfile
import traceback
import importlib.util
from pathlib import Path

HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:
    sys.path.insert(0, HERE)


def _args():
    args = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    return args or [HERE]


def _tiny_runner(args):
    files = []
    for arg in args:
        if os.path.isdir(arg):
            files += sorted(str(p) for p in Path(arg).glob("test_*.py"))
        elif arg.endswith(".py"):
            files.append(arg)
    failed = passed = 0
    for path in files:
        spec = importlib.util.spec_from_file_location(Path(path).stem, path)
        module = importlib.util.module_from_spec(spec)
        try:
            spec.loader.exec_module(module)
        except Exception:   # e.g. a test file that needs pytest itself
            failed += 1
            print(f"FAILED importing {path}")
            traceback.print_exc()
            continue
        for name, fn in sorted(vars(module).items()):
            if not (name.startswith("test_") and callable(fn)):
                continue
            kwargs = {}
            with tempfile.TemporaryDirectory() as tmp:
                if "tmp_path" in inspect.signature(fn).parameters:
                    kwargs["tmp_path"] = Path(tmp)
                try:
                    fn(**kwargs)
                    passed += 1
                except Exception:
                    failed += 1
                    print(f"FAILED {path}::{name}")
                    traceback.print_exc()
    print(f"{passed} passed, {failed} failed")
    return 1 if failed or not passed else 0


def main():
    args = _args()
    try:
        import pytest
    except ImportError:
        print("run.py: pytest is not importable in Blender's Python; using the fallback runner")
        return _tiny_runner(args)
    return pytest.main(args + ["-q", "-p", "no:cacheprovider", "--rootdir", HERE])


sys.exit(main())
