#!/usr/bin/python3
"""Opens a Peridot Exodus file the way users look at it, with meshio and with ParaView's own Python (pvpython),
and checks that each shows the file's points, blocks, node sets, fields and times, and one value known in
closed form.

The deck (tests/regression/decks/postprocessors.yaml) has two bodies of different models, so two element
blocks, two node sets and five frames. What each reader must show:
  * meshio (Debian python3-meshio, installed by scripts/install_deps.sh): every point with its coordinates,
    one vertex cell block per body with its point count, the node sets by name with their sizes, every nodal
    field by name. meshio's Exodus reader takes the first frame only (it warns "Skipping some time data"), so
    its values are checked at t = 0: the initial velocity 5 (x - 0.006)/0.006 m/s of the deck, exactly.
  * ParaView's IOSS reader (Debian paraview and python3-paraview,
    scripts/install_paraview.sh; skipped with a message when pvpython is not installed): the blocks and node
    sets by name, the five times, the fields as vectors (displacement, velocity, force_density, joined from
    their _x, _y, _z) and scalars, each block's point count, and at the last time each point's velocity equal
    to the file's, matched through the node ids; the points it draws are the deformed ones (x + u), since it
    applies the field named displacement.

Exits 1 if any check fails. Runs on Debian's /usr/bin/python3 with numpy and netCDF4.
"""
import argparse
import contextlib
import io
import json
import os
import shutil
import subprocess
import sys

import netCDF4
import numpy as np

VECTORS = ("displacement", "velocity", "force_density")
SCALARS = ("damage", "dilatation", "weighted_volume", "volume")


def strings(var):
    return [row.tobytes().split(b"\0")[0].decode().strip() for row in np.asarray(var[:])]


class Truth:
    """The file read directly with netCDF4: what every reader must reproduce."""

    def __init__(self, path):
        with netCDF4.Dataset(path) as nc:
            nc.set_auto_mask(False)
            self.x = np.column_stack([nc.variables[f"coord{a}"][:] for a in "xyz"])
            self.times = np.asarray(nc.variables["time_whole"][:])
            self.block_names = strings(nc.variables["eb_names"])
            self.block_sizes = [len(nc.dimensions[f"num_el_in_blk{k + 1}"]) for k in range(len(self.block_names))]
            self.node_set_names = strings(nc.variables["ns_names"])
            self.node_sets = [np.asarray(nc.variables[f"node_ns{k + 1}"][:]) - 1 for k in range(len(self.node_set_names))]
            self.names = strings(nc.variables["name_nod_var"])
            self.values = {name: np.asarray(nc.variables[f"vals_nod_var{k + 1}"][:]) for k, name in enumerate(self.names)}
            self.node_ids = np.asarray(nc.variables["node_num_map"][:])  # the deck's point ids, 1-based

    def index_of(self, node_ids):
        """The file's node index of each node id (a reader shows the ids of node_num_map, not file positions)."""
        order = np.argsort(self.node_ids)
        return order[np.searchsorted(self.node_ids, node_ids, sorter=order)]


class Checker:
    def __init__(self):
        self.failures = 0
        self.passes = 0

    def check(self, ok, message):
        if ok:
            self.passes += 1
        else:
            self.failures += 1
            print(f"FAIL {message}")


def initial_velocity_x(x):
    return 5 * (x - 0.006) / 0.006  # the deck's initial condition


def check_meshio(c, path, truth):
    import meshio

    with contextlib.redirect_stderr(io.StringIO()):  # "Skipping some time data" per field: the first frame only
        mesh = meshio.read(path)
    c.check(mesh.points.shape == truth.x.shape and np.array_equal(mesh.points, truth.x),
            f"meshio: points {mesh.points.shape} differ from the file's {truth.x.shape}")
    blocks = [(block.type, len(block.data)) for block in mesh.cells]
    c.check(blocks == [("vertex", n) for n in truth.block_sizes],
            f"meshio: cell blocks {blocks}, expected vertex blocks of {truth.block_sizes}")
    covered = np.sort(np.concatenate([block.data.ravel() for block in mesh.cells]))
    c.check(np.array_equal(covered, np.arange(len(truth.x))), "meshio: the blocks do not hold every point once")
    sets = {name: np.sort(ids) for name, ids in mesh.point_sets.items()}
    c.check(sorted(sets) == sorted(truth.node_set_names),
            f"meshio: node sets {sorted(sets)}, expected {sorted(truth.node_set_names)}")
    for name, ids in zip(truth.node_set_names, truth.node_sets):
        c.check(name in sets and np.array_equal(sets[name], np.sort(ids)), f"meshio: node set {name} differs")
    c.check(sorted(mesh.point_data) == sorted(truth.names),
            f"meshio: fields {sorted(mesh.point_data)}, expected {sorted(truth.names)}")
    for name in truth.names:
        if name in mesh.point_data:
            c.check(np.array_equal(np.asarray(mesh.point_data[name]).ravel(), truth.values[name][0]),
                    f"meshio: {name} at t = 0 differs from the file's")
    # The value known in closed form: the initial velocity away from the end the boundary condition drives.
    driven = set(truth.node_sets[truth.node_set_names.index("right_end")].tolist())
    free = np.array([i for i in range(len(truth.x)) if i not in driven])
    vx = np.asarray(mesh.point_data["velocity_x"])[free]
    expected = initial_velocity_x(truth.x[free, 0])
    c.check(np.max(np.abs(vx - expected)) <= 1e-12 * 5, f"meshio: velocity_x at t = 0 is not 5 (x - 0.006)/0.006: "
            f"largest error {np.max(np.abs(vx - expected)):.3g} m/s")
    print(f"meshio {meshio.__version__}: {len(mesh.points)} points, blocks {blocks}, "
          f"node sets {[(n, len(s)) for n, s in sets.items()]}, {len(mesh.point_data)} fields")


# Run by pvpython: what ParaView's IOSS reader shows, as JSON on the last line. The
# blocks are merged into one grid to fetch them; each cell's object_id says which block it came from.
PVPYTHON_SCRIPT = r"""
import json, sys
from paraview import simple, servermanager
from vtkmodules.numpy_interface import dataset_adapter as dsa
import numpy as np
reader = simple.IOSSReader(FileName=[sys.argv[1]])
times = list(reader.TimestepValues)
merged = simple.MergeBlocks(Input=reader)
merged.UpdatePipeline(times[-1])
grid = dsa.WrapDataObject(servermanager.Fetch(merged))
print(json.dumps({
    "times": times,
    "blocks": list(reader.ElementBlocks),
    "node_sets": list(reader.NodeSets.Available),
    "fields": list(reader.NodeBlockFields),
    "apply_displacements": int(reader.ApplyDisplacements),
    "point_arrays": list(grid.PointData.keys()),
    "ids": np.asarray(grid.PointData["ids"]).tolist(),
    "points": np.asarray(grid.Points).tolist(),
    "velocity": np.asarray(grid.PointData["velocity"]).tolist(),
    "cell_block": np.asarray(grid.CellData["object_id"]).tolist(),
    "radius": np.asarray(grid.CellData["radius"]).ravel().tolist(),
}))
"""


def check_paraview(c, path, truth, work):
    pvpython = shutil.which("pvpython")
    if pvpython is None:
        print("SKIP ParaView: pvpython is not installed (scripts/install_paraview.sh installs Debian's paraview)")
        return
    script = os.path.join(work, "paraview_read.py")
    with open(script, "w") as f:
        f.write(PVPYTHON_SCRIPT)
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    run = subprocess.run([pvpython, "--force-offscreen-rendering", script, path], capture_output=True, text=True,
                         env=env, timeout=300)
    if run.returncode != 0 or not run.stdout.strip():
        c.check(False, f"pvpython exited {run.returncode}:\n{run.stdout[-2000:]}\n{run.stderr[-2000:]}")
        return
    shown = json.loads(run.stdout.strip().splitlines()[-1])
    c.check(shown["times"] == truth.times.tolist(), f"ParaView: times {shown['times']}, expected {truth.times.tolist()}")
    c.check(shown["blocks"] == truth.block_names, f"ParaView: blocks {shown['blocks']}, expected {truth.block_names}")
    c.check(shown["node_sets"] == truth.node_set_names,  # the sets offered (none is read unless asked)
            f"ParaView: node sets {shown['node_sets']}, expected {truth.node_set_names}")
    expected_fields = sorted(VECTORS + SCALARS)
    c.check(sorted(shown["fields"]) == expected_fields,
            f"ParaView: fields {sorted(shown['fields'])}, expected {expected_fields} (vectors joined from _x, _y, _z)")
    per_block = np.bincount(np.asarray(shown["cell_block"], dtype=int), minlength=len(truth.block_sizes) + 1)[1:]
    c.check(per_block.tolist() == truth.block_sizes,
            f"ParaView: points per block {per_block.tolist()}, expected {truth.block_sizes}")
    c.check(np.array_equal(np.sort(shown["ids"]), np.sort(truth.node_ids)),
            "ParaView: the node ids are not the file's, every point once")
    if len(shown["ids"]) != len(truth.x):
        return
    ids = truth.index_of(np.asarray(shown["ids"], dtype=int))
    c.check(np.all(np.asarray(shown["radius"]) > 0), "ParaView: a point without a positive radius attribute")
    last = len(truth.times) - 1
    displacement = np.column_stack([truth.values[f"displacement_{a}"][last] for a in "xyz"])
    velocity = np.column_stack([truth.values[f"velocity_{a}"][last] for a in "xyz"])
    drawn = np.asarray(shown["points"])
    # The points are drawn in single precision where the reader applies the displacements.
    c.check(shown["apply_displacements"] == 1 and
            np.allclose(drawn, (truth.x + displacement)[ids], rtol=0, atol=1e-7 * np.max(np.abs(truth.x))),
            f"ParaView: the drawn points are not x + u at the last time (largest difference "
            f"{np.max(np.abs(drawn - (truth.x + displacement)[ids])):.3g} m)")
    c.check(np.array_equal(np.asarray(shown["velocity"]), velocity[ids]),
            "ParaView: the velocity at the last time differs from the file's")
    c.check(np.max(np.abs(displacement)) > 1e-5, "the deck should move its points")
    print(f"ParaView (IOSS reader): blocks {shown['blocks']} with {per_block.tolist()} points, node sets "
          f"{shown['node_sets']}, {len(shown['times'])} times, fields {sorted(shown['fields'])}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--peridot", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    out = os.path.join(args.work, "out")
    shutil.rmtree(out, ignore_errors=True)
    deck = os.path.join(args.source, "tests/regression/decks/postprocessors.yaml")
    subprocess.run([args.peridot, "run", deck, "-o", out], check=True, stdout=subprocess.DEVNULL)
    path = os.path.join(out, "results.e")
    truth = Truth(path)
    c = Checker()
    c.check(len(truth.times) == 5 and truth.block_names == ["soft", "hard"] and
            truth.node_set_names == ["left_end", "right_end"], "the deck's file is not what this test expects")
    check_meshio(c, path, truth)
    check_paraview(c, path, truth, args.work)
    print(f"{c.passes} checks passed, {c.failures} failed")
    sys.exit(1 if c.failures else 0)


if __name__ == "__main__":
    main()
