#!/usr/bin/python3
"""Reads runout's LAMMPS dump frames with ASE and with LAMMPS itself, and checks every frame
against the closed-form state of the free-flight scene (tests/readers/free_flight.toml).

Usage: check_dump.py SCENE.toml RUN_DIR [LMP]

In free flight a disc feels gravity alone, and runout's semi-implicit Euler step (v += a dt,
then x += v dt) gives after n steps
    v_n = v_0 + a n dt,   x_n = x_0 + v_0 n dt + a dt^2 n (n + 1) / 2,   omega_n = omega_0,
worked out here from the scene file alone (dt is taken from summary.json). Nothing is read
back from runout's own state, so a wrong column, a swapped id, a lost species or a unit slip
in the writer shows up as a mismatch.

ASE reads ids, types, positions, velocities and the box; it has no place for a radius or an
angular velocity, so those two columns are taken from the same frame by the column names of
its ATOMS header. LAMMPS (read_dump, then write_dump) reads ids, types, x, y, vx, vy again.
"""
import glob
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib

import ase.io
import ase.units
import numpy as np

scene_path, run_dir = sys.argv[1], sys.argv[2]
lmp = sys.argv[3] if len(sys.argv) > 3 else None
scene = tomllib.load(open(scene_path, "rb"))
summary = json.load(open(os.path.join(run_dir, "summary.json")))
dt = summary["dt"]
g = scene["integration"]["gravity"]
names = sorted(scene["species"])  # LAMMPS types: the species in name order, from 1
d_small = min(s["diameter"] for s in scene["species"].values())
unit_time = math.sqrt(d_small / g)  # t* = t sqrt(g / d)
discs = scene["particles"]
failures = []


def close(what, got, want, tol, rtol=None):
    got, want = np.asarray(got, float), np.asarray(want, float)
    if got.shape != want.shape or not np.allclose(got, want, rtol=tol if rtol is None else rtol, atol=tol):
        failures.append(f"{what}: got {got.tolist()}, want {want.tolist()}")


def expected(n):
    """The state after n steps, rows in id order (ids are the scene's particles from 1)."""
    t = n * dt
    rows = []
    for k, p in enumerate(discs):
        vx0, vy0 = p.get("vx", 0.0), p.get("vy", 0.0)
        radius = 0.5 * p.get("diameter", scene["species"][p["species"]]["diameter"])
        rows.append(dict(id=k + 1, type=names.index(p["species"]) + 1,
                         x=p["x"] + vx0 * t, y=p["y"] + vy0 * t - g * dt * dt * n * (n + 1) / 2,
                         vx=vx0, vy=vy0 - g * t, radius=radius, omega=p.get("omega", 0.0)))
    return rows


frames = sorted(glob.glob(os.path.join(run_dir, "dump", "frame.*.lammpstrj")))
steps = [int(os.path.basename(f).split(".")[1]) for f in frames]
# The schedule: one frame at each whole t* from 0 to the end, each on the step nearest it.
want_times = np.arange(0, scene["output"]["end_time"] + 1e-9, 1.0)
if len(steps) != len(want_times):
    failures.append(f"{len(steps)} frames for the {len(want_times)} times {want_times.tolist()}")
else:
    close("frame times (t*)", [n * dt / unit_time for n in steps], want_times, 0.51 * dt / unit_time, rtol=0)

for path, n in zip(frames, steps):
    name = os.path.basename(path)
    want = expected(n)
    images = ase.io.read(path, format="lammps-dump-text", index=":", units="si")
    if len(images) != 1:
        failures.append(f"{name}: ASE read {len(images)} frames, want 1")
        continue
    atoms = images[0]  # ASE sorts the atoms by id
    if len(atoms) != len(want):
        failures.append(f"{name}: ASE read {len(atoms)} atoms, want {len(want)}")
        continue
    metre, metre_per_second = ase.units.m, ase.units.m / ase.units.s
    pos = atoms.get_positions() / metre
    vel = atoms.get_velocities() / metre_per_second
    close(f"{name} types", atoms.get_atomic_numbers(), [w["type"] for w in want], 0)
    close(f"{name} x, y", pos[:, :2], [[w["x"], w["y"]] for w in want], 1e-8)
    close(f"{name} z", pos[:, 2], np.zeros(len(want)), 0)
    close(f"{name} vx, vy", vel[:, :2], [[w["vx"], w["vy"]] for w in want], 1e-8)
    close(f"{name} vz", vel[:, 2], np.zeros(len(want)), 1e-12)
    # The box: the walls' extent (the discs are inside it) and +-the largest radius in z.
    close(f"{name} box origin", atoms.get_celldisp().ravel() / metre, [-30, 0, -0.5], 1e-12)
    close(f"{name} box size", atoms.cell.lengths() / metre, [60, 60, 1.0], 1e-12)

    lines = open(path).read().splitlines()
    header = lines.index(next(l for l in lines if l.startswith("ITEM: ATOMS")))
    close(f"{name} TIME (t*)", float(lines[lines.index("ITEM: TIME") + 1]), n * dt / unit_time, 1e-8)
    columns = lines[header].split()[2:]
    table = np.array([l.split() for l in lines[header + 1:]], float)
    table = table[np.argsort(table[:, columns.index("id")])]
    close(f"{name} ids", table[:, columns.index("id")], [w["id"] for w in want], 0)
    close(f"{name} radius", table[:, columns.index("radius")], [w["radius"] for w in want], 1e-12)
    close(f"{name} omegaz", table[:, columns.index("omegaz")], [w["omega"] for w in want], 1e-12)

    if lmp:
        # LAMMPS builds the atoms from the frame (read_dump ... add keep: with the frame's ids)
        # and writes them back at full precision: ids, types, positions and velocities as
        # LAMMPS understood them.
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "out.txt")
            script = f"""units si
dimension 2
atom_style sphere
boundary f f p
region box block -1 1 -1 1 -0.5 0.5
create_box {len(names)} box
read_dump {os.path.abspath(path)} {n} x y vx vy box yes add keep
write_dump all custom {out} id type x y vx vy modify sort id format float %.17g
"""
            run = subprocess.run([lmp, "-log", "none", "-screen", "none"], input=script, text=True,
                                 capture_output=True, cwd=tmp)
            if run.returncode != 0 or not os.path.exists(out):
                failures.append(f"{name}: LAMMPS read_dump failed: {run.stdout[-400:]} {run.stderr[-400:]}")
                continue
            back = np.loadtxt(out, skiprows=9, ndmin=2)
            close(f"{name} LAMMPS ids, types", back[:, :2], [[w["id"], w["type"]] for w in want], 0)
            close(f"{name} LAMMPS x, y", back[:, 2:4], [[w["x"], w["y"]] for w in want], 1e-8)
            close(f"{name} LAMMPS vx, vy", back[:, 4:6], [[w["vx"], w["vy"]] for w in want], 1e-8)

if failures:
    print("\n".join("FAIL " + f for f in failures))
    sys.exit(1)
print(f"{len(frames)} frames of {len(discs)} discs read by ASE" + (" and LAMMPS" if lmp else "") +
      " match the closed form")
