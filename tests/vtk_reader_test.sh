#!/usr/bin/env bash
# runout's ParaView frames (--vtk-every) read by VTK's own reader (python3-vtk9,
# vtkXMLPolyDataReader) and the .pvd collection by an XML parser, checked against the dump
# frames of the same steps, the scene's walls and a basal layer worked out by hand
# (tests/readers/check_vtk.py).
# Usage: vtk_reader_test.sh RUNOUT_BINARY SOURCE_DIR
set -euo pipefail
bin=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$src/tests/readers/basal_pile.toml
"$bin" run "$scene" --out "$work/run" -q --threads 1 --dump-every 0.5 --vtk-every 0.5 >/dev/null
/usr/bin/python3 "$src/tests/readers/check_vtk.py" "$scene" "$work/run"
# The scene key does the same as the option.
"$bin" run "$scene" --out "$work/key" -q --threads 1 --set output.vtk_every=0.5 --dump-every 0.5 >/dev/null
diff -r "$work/run/vtk" "$work/key/vtk"
