#!/usr/bin/env bash
# `make demo` (after `make build`): generate the example scene and render it with Candela.
#   examples/render_demo.sh [OUT_DIR] [extra demo.py args, e.g. --samples 16 --size 256]
# Produces  build/examples/cornell_box.blend, OUT_DIR/cornell_box.exr (scene-linear), OUT_DIR/cornell_box.png.
# Environment: BUILD_DIR (default build), ENGINE (default CANDELA).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-out}"
[ $# -gt 0 ] && shift
build="${BUILD_DIR:-build}"
case "$build" in /*) ;; *) build="$here/$build" ;; esac
engine="${ENGINE:-CANDELA}"
launcher="$here/bin/candela-blender"
export CANDELA_SCRIPTS_DIR="$build/scripts"

blend="$build/examples/cornell_box.blend"
mkdir -p "$build/examples" "$out"
"$launcher" -b --factory-startup --python-exit-code 1 \
    --python "$here/examples/cornell_box.py" -- "$blend" --engine "$engine"
"$launcher" -b --factory-startup --python-exit-code 1 \
    --python "$here/examples/demo.py" -- --blend "$blend" --out "$out" --engine "$engine" "$@"
