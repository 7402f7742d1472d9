"""The one place that loads `candela._native` and checks its ABI.

The shared library is copied next to this file by the build. Importing it can fail (not built, built for another
Python, stale ABI); the add-on then still registers a preferences panel and an engine that reports `error`, because
a raising `register()` leaves Blender half-registered.
"""

import importlib
import os
import sys

# Must equal `_native.ABI_VERSION`; bump both together whenever the array schema or params change incompatibly.
ABI_VERSION = 5

module = None   # the loaded candela._native, or None
error = None    # why it is None


CPU_REQUIREMENTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_native.cpu")


def missing_cpu_features(requirements_path=CPU_REQUIREMENTS, cpuinfo_path="/proc/cpuinfo"):
    """The /proc/cpuinfo flags the build needs (`_native.cpu`, written by the build from its target instruction set)
    that this CPU lacks; [] when it has them all, or where either file cannot be read (another OS: no check)."""
    try:
        with open(requirements_path) as f:
            needed = [line.strip() for line in f if line.strip()]
        with open(cpuinfo_path) as f:
            flags = next((line.split(":", 1)[1].split() for line in f if line.startswith("flags")), None)
    except OSError:
        return []
    if flags is None:
        return []
    have = set(flags)
    return [flag for flag in needed if flag not in have]


def load():
    """Import the native module (once per Blender process; a .so cannot be unloaded) and check its ABI."""
    global module, error
    module, error = None, None
    missing = missing_cpu_features()
    if missing:
        # Importing would execute instructions this CPU does not have: Blender would die of SIGILL.
        error = (f"this build of Candela's native module needs CPU features this machine lacks ({', '.join(missing)}): "
                 f"rebuild it with `cmake -DCANDELA_TARGET_ARCH=x86-64-v2` (or x86-64) on this machine")
        return None
    try:
        mod = importlib.import_module(__package__ + "._native")
    except Exception as e:  # ImportError, or whatever a broken shared library raises while initialising
        error = (f"cannot import candela._native: {e} (Blender runs Python {sys.version.split()[0]}; the module must "
                 f"be a cpython-311-x86_64-linux-gnu build placed next to the add-on's __init__.py)")
        return None
    abi = getattr(mod, "ABI_VERSION", None)
    if abi != ABI_VERSION:
        error = (f"candela._native has ABI_VERSION {abi} but this add-on expects {ABI_VERSION}: rebuild the add-on "
                 f"and restart Blender")
        return None
    module = mod
    return mod


def require():
    """The native module, or a RuntimeError saying why it is unavailable."""
    if module is None:
        raise RuntimeError(error or "the native module is not loaded (is the add-on enabled?)")
    return module


def capabilities():
    """`_native.capabilities()`, or {} when the module is unavailable (callers keep documented fallbacks)."""
    if module is None:
        return {}
    try:
        return dict(module.capabilities())
    except Exception:
        return {}
