#!/usr/bin/python3
"""Reads runout's ParaView output with VTK's own reader and checks it against the LAMMPS dump
frames of the same steps (read by ASE, which tests/readers/check_dump.py checks against a
closed form), the scene's walls and a basal layer worked out by hand.

Usage: check_vtk.py SCENE.toml RUN_DIR   (the run made with equal --dump-every and --vtk-every)

For tests/readers/basal_pile.toml at t* = 0 the basal layer (measure.hpp) is: the large discs'
lower contour is their bottom edge, 0.201 m above the floor all along the pile; the nine small
discs on the floor (centres 0.1001 m up) lie below it and inside the deposit's body L1 (the
D-wide bins from the leftmost disc holding a tenth of the fullest bin's disc area: x in
[-2, 3)); the small disc on the middle large disc is above the contour, the one at x = 4.5 is
beyond L1, and large discs are never in the layer. So: the first nine discs, ids 1-9.
"""
import glob
import os
import sys
import tomllib
import xml.etree.ElementTree as ET

import ase.io
import ase.units
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

scene_path, run_dir = sys.argv[1], sys.argv[2]
scene = tomllib.load(open(scene_path, "rb"))
names = sorted(scene["species"])
discs = scene["particles"]
failures = []


def check(what, ok, detail=""):
    if not ok:
        failures.append(f"{what} {detail}")


def close(what, got, want, tol):
    got, want = np.atleast_1d(np.asarray(got, float)), np.atleast_1d(np.asarray(want, float))
    check(what, got.shape == want.shape and np.allclose(got, want, rtol=tol, atol=tol),
          f"got {got.tolist()[:6]}, want {want.tolist()[:6]}")


# The collection: valid XML, one DataSet per frame file, each with its time.
pvd = ET.parse(os.path.join(run_dir, "vtk", "frames.pvd")).getroot()
check("pvd root", pvd.tag == "VTKFile" and pvd.get("type") == "Collection", pvd.attrib)
datasets = pvd.findall("./Collection/DataSet")
files = sorted(os.path.basename(f) for f in glob.glob(os.path.join(run_dir, "vtk", "frame.*.vtp")))
check("pvd lists every frame file in step order", [d.get("file") for d in datasets] == files,
      f"{[d.get('file') for d in datasets]} vs {files}")
dumps = sorted(glob.glob(os.path.join(run_dir, "dump", "frame.*.lammpstrj")))
check("one VTK frame per dump frame", len(files) == len(dumps) == 5, f"{len(files)} vs {len(dumps)}")

# The walls: one line per segment of the scene's polylines, between its end points.
segments = []
for w in scene["walls"]:
    pts = w["points"]
    segments += [pts[i] + pts[i + 1] for i in range(len(pts) - 1)]

for entry, dump in zip(datasets, dumps):
    name = entry.get("file")
    known = len(failures)
    reader = vtk.vtkXMLPolyDataReader()
    errors = []
    reader.AddObserver("ErrorEvent", lambda obj, event: errors.append(event))
    reader.SetFileName(os.path.join(run_dir, "vtk", name))
    reader.Update()
    poly = reader.GetOutput()
    check(f"{name}: VTK reader errors", not errors and reader.GetErrorCode() == 0, errors)

    # The dump frame of the same step, by ASE (ids sorted); radius and spin by column name.
    step = int(name.split(".")[1])
    check(f"{name}: dump of the same step", os.path.basename(dump) == f"frame.{step:09d}.lammpstrj", dump)
    atoms = ase.io.read(dump, format="lammps-dump-text", index=-1, units="si")
    lines = open(dump).read().splitlines()
    time = float(lines[lines.index("ITEM: TIME") + 1])
    header = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
    cols = lines[header].split()[2:]
    table = np.array([l.split() for l in lines[header + 1:]], float)
    table = table[np.argsort(table[:, cols.index("id")])]
    n = len(atoms)

    # Times: the .pvd's, the frame's own TimeValue (ParaView's time) and the dump's, all t*.
    field = poly.GetFieldData()
    check(f"{name}: TimeValue", field.GetArray("TimeValue") is not None)
    if field.GetArray("TimeValue") is not None:
        close(f"{name}: TimeValue vs dump TIME", field.GetArray("TimeValue").GetValue(0), time, 1e-12)
        close(f"{name}: step", field.GetArray("step").GetValue(0), step, 0)
    close(f"{name}: pvd timestep vs dump TIME", float(entry.get("timestep")), time, 1e-12)

    # Points: the discs, then two per wall segment; a vertex cell per disc, a line per segment.
    check(f"{name}: points", poly.GetNumberOfPoints() == n + 2 * len(segments),
          f"{poly.GetNumberOfPoints()} for {n} discs and {len(segments)} segments")
    check(f"{name}: verts", poly.GetNumberOfVerts() == n, poly.GetNumberOfVerts())
    check(f"{name}: lines", poly.GetNumberOfLines() == len(segments), poly.GetNumberOfLines())
    if len(failures) > known:
        continue  # the rest of this frame cannot be compared
    pts = vtk_to_numpy(poly.GetPoints().GetData())
    pd = poly.GetPointData()
    arrays = {pd.GetArrayName(i): pd.GetArray(i) for i in range(pd.GetNumberOfArrays())}
    want_types = {"radius": (vtk.VTK_DOUBLE, 1), "velocity": (vtk.VTK_DOUBLE, 3), "spin": (vtk.VTK_DOUBLE, 1),
                  "species": (vtk.VTK_INT, 1), "basal_layer": (vtk.VTK_UNSIGNED_CHAR, 1),
                  "id": (vtk.VTK_TYPE_INT64, 1)}
    got_types = {k: (a.GetDataType(), a.GetNumberOfComponents()) for k, a in arrays.items()}
    check(f"{name}: point arrays", got_types == want_types, f"{got_types} vs {want_types}")
    if len(failures) > known:
        continue  # the rest of this frame cannot be compared
    a = {k: vtk_to_numpy(v) for k, v in arrays.items()}
    order = np.argsort(a["id"][:n])  # the frame lists discs in the world's order; ids match the dump
    close(f"{name}: disc ids", a["id"][:n][order], table[:, cols.index("id")], 0)
    close(f"{name}: x, y", pts[:n][order, :2], atoms.get_positions()[:, :2] / ase.units.m, 1e-8)
    close(f"{name}: z", pts[:, 2], np.zeros(len(pts)), 0)
    close(f"{name}: velocity", a["velocity"][:n][order],
          atoms.get_velocities() / (ase.units.m / ase.units.s), 1e-8)
    close(f"{name}: radius", a["radius"][:n][order], table[:, cols.index("radius")], 1e-9)
    close(f"{name}: spin", a["spin"][:n][order], table[:, cols.index("omegaz")], 1e-8)
    close(f"{name}: species (dump type - 1)", a["species"][:n][order], atoms.get_atomic_numbers() - 1, 0)
    # Wall end points: no disc data on them.
    close(f"{name}: wall point radius, spin, basal",
          np.concatenate([a["radius"][n:], a["spin"][n:], a["basal_layer"][n:]]), np.zeros(3 * (len(pts) - n)), 0)
    close(f"{name}: wall point species and id", np.concatenate([a["species"][n:], a["id"][n:]]),
          -np.ones(2 * (len(pts) - n)), 0)
    lines_cells = vtk_to_numpy(poly.GetLines().GetConnectivityArray()).reshape(-1, 2)
    close(f"{name}: wall lines", np.hstack([pts[lines_cells[:, 0], :2], pts[lines_cells[:, 1], :2]]),
          segments, 1e-12)
    verts = vtk_to_numpy(poly.GetVerts().GetConnectivityArray())
    close(f"{name}: one vertex per disc", np.sort(verts), np.arange(n), 0)

    basal = a["basal_layer"][:n][order]
    small = names.index("small")
    check(f"{name}: basal layer only small discs",
          np.all(basal[atoms.get_atomic_numbers() - 1 != small] == 0), basal.tolist())
    if step == 0:
        want = [1 if i < 9 else 0 for i in range(len(discs))]
        close(f"{name}: basal layer at t* = 0 (worked out by hand)", basal, want, 0)

if failures:
    print("\n".join("FAIL " + f for f in failures))
    sys.exit(1)
print(f"{len(files)} VTK frames read by vtkXMLPolyDataReader match the dump frames, the walls "
      "and the basal layer")
