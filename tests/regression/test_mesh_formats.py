#!/usr/bin/python3
"""Meshes written by another program (meshio) read as bodies: the same box, 4 x 3 x 2 mm, as hexahedra,
tetrahedra (6 per cube) and prisms (2 per cube), each in Gmsh 4.1 ASCII, Gmsh 4.1 binary and Abaqus, the
hexahedra also in Exodus II; and a 4 x 3 mm plate as quadrilaterals and triangles in 2D. For each file
`peridot run` (one step) must give the element count as points, the total volume (24 mm³; 12 mm² x the
1 mm thickness) and the centroid of the box to round-off, and every hexahedron file must give the motion of a
short elastic run of the built-in box to round-off. A node set written by meshio into the Abaqus and Exodus files
selects the elements that touch it.

Exits 1 if a check fails. Runs on Debian's /usr/bin/python3 with numpy, netCDF4 and meshio (python3-meshio,
installed by scripts/install_deps.sh).
"""
import argparse
import os
import shutil
import subprocess
import sys

import meshio
import netCDF4
import numpy as np

NX, NY, NZ = 4, 3, 2


def box():
    points = np.array([[i, j, k] for k in range(NZ + 1) for j in range(NY + 1) for i in range(NX + 1)], float)
    node = lambda i, j, k: i + (NX + 1) * (j + (NY + 1) * k)
    hexes = [[node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
              node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)]
             for k in range(NZ) for j in range(NY) for i in range(NX)]
    tets = [[h[a] for a in t] for h in hexes
            for t in [(0, 1, 2, 6), (0, 2, 3, 6), (0, 3, 7, 6), (0, 7, 4, 6), (0, 4, 5, 6), (0, 5, 1, 6)]]
    tets = np.array(tets)
    corners = points[tets]
    signed = np.einsum("ij,ij->i", np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]),
                       corners[:, 3] - corners[:, 0])
    tets[signed < 0] = tets[signed < 0][:, [0, 2, 1, 3]]  # every tetrahedron positive, as mesh generators write them
    wedges = [w for h in hexes for w in ([h[0], h[1], h[2], h[4], h[5], h[6]], [h[0], h[2], h[3], h[4], h[6], h[7]])]
    return points, {"hexahedron": np.array(hexes), "tetra": tets, "wedge": np.array(wedges)}


def plate():
    points = np.array([[i, j, 0.0] for j in range(NY + 1) for i in range(NX + 1)])
    node = lambda i, j: i + (NX + 1) * j
    quads = [[node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)] for j in range(NY) for i in range(NX)]
    triangles = [t for q in quads for t in ([q[0], q[1], q[2]], [q[0], q[2], q[3]])]
    return points, {"quad": np.array(quads), "triangle": np.array(triangles)}


DECK_3D = """discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
materials:
  steel: {{model: pmb, density: 7800, youngs_modulus: 200 GPa}}
bodies:
  box: {{material: steel, {source}}}
initial_conditions:
  - {{velocity: {{x: "10 * (x - 0.002) / 0.002", z: "2 * sin(2000 * y)"}}}}
solver: {{num_steps: {steps}}}
output: {{progress: false, exodus: {{every: {steps}, file: r.e}}}}
"""
DECK_2D = """discretization: {{dimension: 2, plane: stress, thickness: 1 mm, spacing: 1 mm, horizon_factor: 3.015}}
materials:
  steel: {{model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}}
bodies:
  plate: {{material: steel, {source}}}
solver: {{num_steps: {steps}}}
output: {{progress: false, exodus: {{every: {steps}, file: r.e}}}}
"""


def run(peridot, work, name, deck_text):
    folder = os.path.join(work, "runs", name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    deck = os.path.join(work, "meshes", name + ".yaml")
    with open(deck, "w") as f:
        f.write(deck_text)
    result = subprocess.run([peridot, "run", deck, "-o", folder, "-q"], capture_output=True, text=True)
    if result.returncode != 0:
        return None, result.stderr.strip()
    with netCDF4.Dataset(os.path.join(folder, "r.e")) as nc:
        nc.set_auto_mask(False)
        names = [row.tobytes().split(b"\0")[0].decode().strip() for row in np.asarray(nc.variables["name_nod_var"][:])]
        x = np.column_stack([nc.variables[f"coord{a}"][:] for a in "xyz" if f"coord{a}" in nc.variables])
        values = {n: np.asarray(nc.variables[f"vals_nod_var{k + 1}"][-1]) for k, n in enumerate(names)}
    return (x, values), ""


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--peridot", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(os.path.join(args.work, "meshes"))
    failures = 0

    def check(ok, message):
        nonlocal failures
        if not ok:
            failures += 1
            print("FAIL", message)

    files = []  # (file, deck template, elements, volume m³, centroid m, is a hexahedron file)
    points, cells = box()
    for kind, elements in cells.items():
        mesh = meshio.Mesh(points, [(kind, elements)])
        for suffix, writer in [("ascii.msh", dict(file_format="gmsh", binary=False)),
                               ("binary.msh", dict(file_format="gmsh", binary=True)),
                               ("inp", dict(file_format="abaqus"))] + ([("e", dict(file_format="exodus"))] if kind == "hexahedron" else []):
            name = f"{kind}_{suffix.replace('.', '_')}"
            path = os.path.join(args.work, "meshes", f"{kind}_{suffix}" if "." in suffix else f"{kind}.{suffix}")
            mesh.write(path, **writer)
            files.append((name, path, DECK_3D, len(elements), 24e-9, [0.002, 0.0015, 0.001], kind == "hexahedron"))
    points, cells = plate()
    for kind, elements in cells.items():
        path = os.path.join(args.work, "meshes", f"{kind}.msh")
        meshio.Mesh(points, [(kind, elements)]).write(path, file_format="gmsh", binary=False)
        files.append((kind, path, DECK_2D, len(elements), 12e-6 * 1e-3, [0.002, 0.0015], False))

    reference, message = run(args.peridot, args.work, "built_in", DECK_3D.format(
        source="shape: {box: {min: [0, 0, 0], max: [0.004, 0.003, 0.002]}}", steps=40))
    check(reference is not None, f"the built-in box does not run: {message}")
    for name, path, template, elements, volume, centroid, is_hex in files:
        result, message = run(args.peridot, args.work, name, template.format(
            source=f"mesh: {{file: {os.path.basename(path)}, scale: 1e-3}}", steps=40 if is_hex else 1))
        if result is None:
            check(False, f"{name}: {message}")
            continue
        x, values = result
        v = values["volume"]
        total = v.sum()
        mean = (x * v[:, None]).sum(axis=0) / total
        check(len(v) == elements, f"{name}: {len(v)} points, {elements} elements")
        check(abs(total - volume) <= 1e-14 * volume, f"{name}: total volume {total:.17g}, expected {volume:g}")
        check(np.allclose(mean, centroid, rtol=0, atol=1e-15), f"{name}: centroid {mean}, expected {centroid}")
        line = f"{name:22s} {len(v):4d} points  volume {total:.17g} m³  centroid {mean}"
        if is_hex and reference is not None:
            # The centroids are the lattice points to round-off, not bit for bit: compare point by point, in an
            # order that does not depend on the file.
            order, reference_order = np.lexsort(np.round(x.T * 1e9)), np.lexsort(np.round(reference[0].T * 1e9))
            u = np.column_stack([values[f"displacement_{a}"] for a in "xyz"])[order]
            u_reference = np.column_stack([reference[1][f"displacement_{a}"] for a in "xyz"])[reference_order]
            difference = np.max(np.abs(u - u_reference))
            check(np.allclose(x[order], reference[0][reference_order], rtol=0, atol=1e-17) and
                  difference <= 1e-9 * np.max(np.abs(u_reference)) and np.max(np.abs(u_reference)) > 1e-7,
                  f"{name}: 40 steps differ from the built-in box's by {difference:.3g} m")
            line += f"  40 steps: |u - u_built-in| <= {difference:.2g} m of {np.max(np.abs(u_reference)):.2g} m"
        print(line)
    # Node sets written by meshio (Abaqus *NSET, Exodus node set): the face x = 0 selects the elements touching it,
    # the column of NY x NZ hexahedra at x = 0, as a node set by shape does.
    points, cells = box()
    face = np.where(points[:, 0] == 0)[0]
    mesh = meshio.Mesh(points, [("hexahedron", cells["hexahedron"])], point_sets={"left_face": face})
    for suffix, file_format in [("inp", "abaqus"), ("e", "exodus")]:
        path = os.path.join(args.work, "meshes", f"node_set.{suffix}")
        mesh.write(path, file_format=file_format)
        deck = os.path.join(args.work, "meshes", f"node_set_{suffix}.yaml")
        with open(deck, "w") as f:
            f.write(DECK_3D.format(source=f"mesh: {{file: node_set.{suffix}, scale: 1e-3}}", steps=1)
                    + "node_sets:\n  face: {mesh_set: left_face}\n"
                    + "  by_shape: {shape: {box: {min: [-1, -1, -1], max: [0.001, 1, 1]}}}\n")
        result = subprocess.run([args.peridot, "check", deck], capture_output=True, text=True)
        counts = dict(line.split()[2:4:1] for line in result.stdout.splitlines() if line.strip().startswith("node set"))
        check(result.returncode == 0 and counts.get("face") == str(NY * NZ) and counts.get("by_shape") == str(NY * NZ),
              f"node set of a meshio {file_format} file: {counts or result.stderr.strip()}, expected {NY * NZ} points")
        print(f"node set left_face of a meshio {file_format} file: {counts.get('face')} points (by shape: "
              f"{counts.get('by_shape')})")
    print(f"{len(files)} meshes, {failures} failures")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
