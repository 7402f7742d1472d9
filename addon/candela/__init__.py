"""Candela: a Monte Carlo renderer for Blender (engine id CANDELA).

The heavy lifting lives in the native module `candela._native` (C++), copied next to this file by the build.
"""

bl_info = {
    "name": "Candela",
    "author": "Candela developers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render > Render Engine > Candela",
    "description": "Monte Carlo path tracing renderer",
    "category": "Render",
}

import traceback

# Registered modules, in order; unregister() walks it backwards so a partial registration is undone exactly.
_registered = []


def _register_modules(modules):
    for module in modules:
        module.register()
        _registered.append(module)


def register():
    """Never raises: a raising register() leaves Blender with half-registered classes."""
    from . import engine, native, preferences
    native.load()
    preferences.registration_error = None
    try:
        if native.module is None:
            # Only what explains the problem: the preferences panel, and an engine whose render reports it.
            print(f"Candela: {native.error}")
            _register_modules([preferences, engine])
            return
        from . import dump, properties, ui
        _register_modules([preferences, properties, engine, dump, ui])
    except Exception as e:
        traceback.print_exc()
        _unregister_modules()
        preferences.registration_error = f"registering the add-on failed: {e}"
        try:
            _register_modules([preferences])
        except Exception:
            traceback.print_exc()


def _unregister_modules():
    while _registered:
        module = _registered.pop()
        try:
            module.unregister()
        except Exception:
            traceback.print_exc()


def unregister():
    _unregister_modules()
