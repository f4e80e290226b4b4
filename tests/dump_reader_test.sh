#!/usr/bin/env bash
# runout's LAMMPS dump frames read by real readers: ASE (python3-ase, `lammps-dump-text`) and
# LAMMPS itself (`read_dump`), each frame checked against the closed-form state of discs in
# free flight (tests/readers/check_dump.py).
# Usage: dump_reader_test.sh RUNOUT_BINARY SOURCE_DIR
set -euo pipefail
bin=$1 src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=$src/tests/readers/free_flight.toml
"$bin" run "$scene" --out "$work/run" -q --threads 1 --dump-every 1 >/dev/null
lmp=$(command -v lmp || true)
[ -n "$lmp" ] || { echo "FAIL: LAMMPS (lmp, Debian package lammps) is not installed"; exit 1; }
/usr/bin/python3 "$src/tests/readers/check_dump.py" "$scene" "$work/run" "$lmp"
