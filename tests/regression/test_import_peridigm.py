#!/usr/bin/python3
"""`peridot import-peridigm` on Peridigm decks written here, in Peridigm's YAML and XML formats, covering what the
translation takes: discretizations (a text point file, an Exodus mesh with its node sets, a PdQuickGrid box with a
rectangular bond filter), the five materials (Elastic, Elastic Plastic, Viscoelastic, Elastic Correspondence, Elastic
Bond Based), critical-stretch damage on some blocks, node sets from files and inline ids, prescribed displacements,
initial velocities, body forces, the Verlet and quasi-static solvers and Exodus output.

For each deck: the import exits 0, writes a deck that `peridot check` accepts, notes what it left out (an
unknown parameter is named with its line), and the translated deck runs; the points it makes are the Peridigm
file's (positions and volumes) or the grid's. A deck that cannot be translated exits 2 naming file:line:col and
writes nothing.

Exits 1 if a check fails. Runs on Debian's /usr/bin/python3 with numpy, netCDF4 and meshio.
"""
import argparse
import os
import shutil
import subprocess
import sys

import meshio
import netCDF4
import numpy as np

TEXT_DECK = """Peridigm:
  Discretization:
    Type: "Text File"
    Input Mesh File: "points.txt"
  Materials:
    Steel:
      Material Model: "Elastic"
      Density: 7800.0
      Bulk Modulus: 130.0e9
      Shear Modulus: 78.0e9
      Apply Shear Correction Factor: false
    Polymer:
      Material Model: "Viscoelastic"
      Density: 1200.0
      Bulk Modulus: 3.0e9
      Shear Modulus: 1.0e9
      lambda_i: 0.5
      tau b: 1.0e-6
  Damage Models:
    Brittle:
      Damage Model: "Critical Stretch"
      Critical Stretch: 0.02
  Blocks:
    Metal Block:
      Block Names: "block_1"
      Material: "Steel"
      Damage Model: "Brittle"
      Horizon: 0.003015
    Soft Block:
      Block Names: "block_2"
      Material: "Polymer"
      Horizon: 0.003015
  Boundary Conditions:
    Left Nodes: "left.txt"
    Right Nodes: "{right_ids}"
    Hold Left:
      Type: "Prescribed Displacement"
      Node Set: "Left Nodes"
      Coordinate: "x"
      Value: "0.0"
    Push Right:
      Type: "Initial Velocity"
      Node Set: "Right Nodes"
      Coordinate: "x"
      Value: "-5.0"
    Gravity:
      Type: "Body Force"
      Node Set: "All"
      Coordinate: "z"
      Value: "-9.81*7800.0"
  Solver:
    Verbose: false
    Initial Time: 0.0
    Final Time: 2.0e-6
    Verlet:
      Safety Factor: 0.7
  Output:
    Output File Type: "ExodusII"
    Output Filename: "text_deck"
    Output Frequency: 10
    Output Variables:
      Displacement: true
      Damage: true
"""

XML_DECK = """<ParameterList>
  <ParameterList name="Discretization">
    <Parameter name="Type" type="string" value="Exodus" />
    <Parameter name="Input Mesh File" type="string" value="box.g" />
  </ParameterList>
  <ParameterList name="Materials">
    <ParameterList name="Aluminium">
      <Parameter name="Material Model" type="string" value="Elastic Plastic" />
      <Parameter name="Density" type="double" value="2700.0" />
      <Parameter name="Young's Modulus" type="double" value="70.0e9" />
      <Parameter name="Poisson's Ratio" type="double" value="0.3" />
      <Parameter name="Yield Stress" type="double" value="250.0e6" />
    </ParameterList>
  </ParameterList>
  <ParameterList name="Blocks">
    <ParameterList name="My Block">
      <Parameter name="Block Names" type="string" value="block_0" /> <!-- meshio numbers blocks from 0 -->
      <Parameter name="Material" type="string" value="Aluminium" />
      <Parameter name="Horizon" type="double" value="0.003015" />
    </ParameterList>
  </ParameterList>
  <ParameterList name="Boundary Conditions">
    <Parameter name="Far End" type="string" value="{far_ids}" />
    <ParameterList name="Fix">
      <Parameter name="Type" type="string" value="Prescribed Displacement" />
      <Parameter name="Node Set" type="string" value="left_face" />
      <Parameter name="Coordinate" type="string" value="x" />
      <Parameter name="Value" type="string" value="0.0" />
    </ParameterList>
    <ParameterList name="Fix Y">
      <Parameter name="Type" type="string" value="Prescribed Displacement" />
      <Parameter name="Node Set" type="string" value="left_face" />
      <Parameter name="Coordinate" type="string" value="y" />
      <Parameter name="Value" type="string" value="0.0" />
    </ParameterList>
    <ParameterList name="Fix Z">
      <Parameter name="Type" type="string" value="Prescribed Displacement" />
      <Parameter name="Node Set" type="string" value="left_face" />
      <Parameter name="Coordinate" type="string" value="z" />
      <Parameter name="Value" type="string" value="0.0" />
    </ParameterList>
    <ParameterList name="Pull">
      <Parameter name="Type" type="string" value="Prescribed Displacement" />
      <Parameter name="Node Set" type="string" value="Far End" />
      <Parameter name="Coordinate" type="string" value="x" />
      <Parameter name="Value" type="string" value="1.0e-6*t" />
    </ParameterList>
  </ParameterList>
  <ParameterList name="Solver">
    <Parameter name="Initial Time" type="double" value="0.0" />
    <Parameter name="Final Time" type="double" value="1.0" />
    <ParameterList name="QuasiStatic">
      <Parameter name="Number of Load Steps" type="int" value="2" />
      <Parameter name="Absolute Tolerance" type="double" value="1.0e-2" />
      <Parameter name="Maximum Solver Iterations" type="int" value="20000" />
    </ParameterList>
  </ParameterList>
  <ParameterList name="Output">
    <Parameter name="Output File Type" type="string" value="ExodusII" />
    <Parameter name="Output Filename" type="string" value="xml_deck" />
    <Parameter name="Output Frequency" type="int" value="1" />
  </ParameterList>
</ParameterList>
"""

GRID_DECK = """Peridigm:
  Discretization:
    Type: "PdQuickGrid"
    TensorProduct3DMeshGenerator:
      Type: "PdQuickGrid"
      X Origin: 0.0
      Y Origin: 0.0
      Z Origin: 0.0
      X Length: 0.010
      Y Length: 0.006
      Z Length: 0.004
      Number Points X: 10
      Number Points Y: 6
      Number Points Z: 4
    Bond Filters:
      Crack:
        Type: "Rectangular_Plane"
        Normal: "1.0 0.0 0.0"
        Lower_Left_Corner: "0.005 -0.001 -0.001"
        Bottom_Unit_Vector: "0.0 1.0 0.0"
        Bottom_Length: 0.004
        Side_Length: 0.006
  Materials:
    Rock:
      Material Model: "{model}"
      Density: 2500.0
      Bulk Modulus: 20.0e9
      Shear Modulus: 12.0e9
      Hourglass Coefficient: 0.02
  Blocks:
    All:
      Block Names: "block_1"
      Material: "Rock"
      Horizon: 0.0031
  Boundary Conditions:
    Spread:
      Type: "Initial Velocity"
      Coordinate: "x"
      Value: "20.0*(x - 0.005)/0.005"
  Solver:
    Final Time: 1.0e-6
    Verlet:
      Safety Factor: 0.5
  Output:
    Output File Type: "ExodusII"
    Output Filename: "grid"
    Output Frequency: 5
"""

BAD_DECK = """Peridigm:
  Discretization:
    Type: "PdQuickGrid"
  Materials:
    Wood:
      Material Model: "Pals"
      Density: 500.0
"""


def run(command):
    return subprocess.run(command, capture_output=True, text=True)


def exodus(path):
    with netCDF4.Dataset(path) as nc:
        nc.set_auto_mask(False)
        x = np.column_stack([nc.variables[f"coord{a}"][:] for a in "xyz"])
        names = [r.tobytes().split(b"\0")[0].decode().strip() for r in np.asarray(nc.variables["name_nod_var"][:])]
        volume = np.asarray(nc.variables[f"vals_nod_var{names.index('volume') + 1}"][0])
        sets = {}
        if "ns_names" in nc.variables:
            set_names = [r.tobytes().split(b"\0")[0].decode().strip() for r in np.asarray(nc.variables["ns_names"][:])]
            sets = {n: x[np.asarray(nc.variables[f"node_ns{k + 1}"][:]) - 1] for k, n in enumerate(set_names)}
        return x, volume, sets, len(nc.dimensions["time_step"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--peridot", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    failures = 0

    def check(ok, message):
        nonlocal failures
        if not ok:
            failures += 1
            print("FAIL", message)

    def translate_and_run(deck, expect_notes):
        out = os.path.splitext(deck)[0] + ".peridot.yaml"
        result = run([args.peridot, "import-peridigm", deck, "-o", out])
        check(result.returncode == 0, f"{os.path.basename(deck)}: import exit {result.returncode}: {result.stderr.strip()}")
        for text in expect_notes:
            check(text in result.stderr, f"{os.path.basename(deck)}: no note containing '{text}' in:\n{result.stderr}")
        check("valid" in result.stdout, f"{os.path.basename(deck)}: the translated deck was not checked: {result.stdout}")
        folder = os.path.join(work, "run_" + os.path.basename(deck).replace(".", "_"))
        ran = run([args.peridot, "run", "-q", out, "-o", folder])
        check(ran.returncode == 0, f"{os.path.basename(deck)}: the translated deck does not run: {ran.stderr.strip()}")
        return out, folder, result

    # 1. Text file, YAML: two blocks, node sets from a file and inline ids, damage on one block.
    grid = np.array([[(i + 0.5) * 1e-3, (j + 0.5) * 1e-3, (k + 0.5) * 1e-3] for k in range(4) for j in range(4)
                     for i in range(6)])
    block = np.where(grid[:, 0] < 3e-3, 1, 2)
    with open(os.path.join(work, "points.txt"), "w") as f:
        f.write("# x y z block volume\n")
        for p, b in zip(grid, block):
            f.write(f"{p[0]!r} {p[1]!r} {p[2]!r} {b} 1.0e-9\n")
    left = np.where(grid[:, 0] < 1e-3)[0] + 1
    right = np.where(grid[:, 0] > 5e-3)[0] + 1
    with open(os.path.join(work, "left.txt"), "w") as f:
        f.write("\n".join(str(i) for i in left) + "\n")
    deck = os.path.join(work, "text_deck.yaml")
    with open(deck, "w") as f:
        f.write(TEXT_DECK.replace("{right_ids}", " ".join(str(i) for i in right)))
    out, folder, _ = translate_and_run(deck, ["'Apply Shear Correction Factor' of material 'Steel' has no equivalent",
                                              "'Output Variables' is not needed"])
    x, volume, sets, frames = exodus(os.path.join(folder, "text_deck.e"))
    order = np.lexsort(np.round(x.T * 1e9))
    expected = np.lexsort(np.round(grid.T * 1e9))
    check(len(x) == len(grid) and np.array_equal(x[order], grid[expected]) and np.all(volume == 1e-9),
          "text deck: the points are not the file's positions and volumes")
    check(sorted(sets) == ["left_nodes", "right_nodes"] and len(sets["left_nodes"]) == len(left) and
          len(sets["right_nodes"]) == len(right) and np.all(sets["left_nodes"][:, 0] < 1e-3) and
          np.all(sets["right_nodes"][:, 0] > 5e-3), "text deck: the node sets are not the file's left and right points")
    sets = {name: len(points) for name, points in sets.items()}
    with open(out) as f:
        translated = f.read()
    check("critical_stretch: 0.02" in translated and translated.count("critical_stretch") == 1,
          "text deck: damage is not on the metal block alone")
    print(f"text deck (YAML): {len(x)} points as the file gives them, node sets {sets}, {frames} frames")

    # 2. Exodus mesh, XML: the mesh's node set by name, a node set of inline ids, the quasi-static solver.
    # 10 x 4 x 4 hexahedra of 1 mm: an LPS body two elements thick does not relax (see the closing note).
    nx, ny, nz = 10, 4, 4
    points = np.array([[i, j, k] for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)], float) * 1e-3
    node = lambda i, j, k: i + (nx + 1) * (j + (ny + 1) * k)
    hexes = np.array([[node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k), node(i, j, k + 1),
                       node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)]
                      for k in range(nz) for j in range(ny) for i in range(nx)])
    meshio.Mesh(points, [("hexahedron", hexes)], point_sets={"left_face": np.where(points[:, 0] == 0)[0]}).write(
        os.path.join(work, "box.g"), file_format="exodus")
    far = [e + 1 for e, h in enumerate(hexes) if points[h[1], 0] == nx * 1e-3]  # the last column of elements, 1-based
    deck = os.path.join(work, "xml_deck.xml")
    with open(deck, "w") as f:
        f.write(XML_DECK.replace("{far_ids}", " ".join(str(i) for i in far)))
    out, folder, _ = translate_and_run(deck, ["'Absolute Tolerance' of the QuasiStatic solver has no equivalent"])
    x, volume, sets, frames = exodus(os.path.join(folder, "xml_deck.e"))
    check(len(x) == len(hexes) and abs(volume.sum() - 160e-9) < 1e-20, f"xml deck: {len(x)} points, volume {volume.sum()}")
    check(sorted(sets) == ["far_end", "left_face"] and np.all(sets["left_face"][:, 0] < 1e-3) and
          np.all(sets["far_end"][:, 0] > (nx - 1) * 1e-3) and len(sets["far_end"]) == ny * nz and frames == 3,
          f"xml deck: node sets {sets}, {frames} frames")
    sets = {name: len(points) for name, points in sets.items()}
    print(f"Exodus mesh (XML): {len(x)} points, volume {volume.sum():.3g} m³, node sets {sets}, {frames} frames")

    # 3. PdQuickGrid with a bond filter, as correspondence and as bond-based.
    for model, expect in [("Elastic Correspondence", "constitutive_law: hypoelastic"), ("Elastic Bond Based", "model: pmb")]:
        deck = os.path.join(work, f"grid_{model.split()[-1].lower()}.yaml")
        with open(deck, "w") as f:
            f.write(GRID_DECK.replace("{model}", model))
        notes = ["a bond-based solid takes the bulk modulus alone"] if model == "Elastic Bond Based" else []
        out, folder, _ = translate_and_run(deck, notes)
        with open(out) as f:
            translated = f.read()
        x, volume, sets, frames = exodus(os.path.join(folder, "grid.e"))
        check(len(x) == 240 and np.allclose(volume, 1e-9, rtol=1e-12) and expect in translated and "rectangle" in translated,
              f"grid ({model}): {len(x)} points")
        check(np.allclose(np.sort(np.unique(np.round(x[:, 0] * 1e4))), np.arange(5, 100, 10)),
              f"grid ({model}): points not at the cell centres")
        # The bond filter cuts bonds: the same deck without its pre-crack has more.
        uncut = out.replace(".peridot.yaml", ".uncut.yaml")
        with open(uncut, "w") as f:
            f.write(translated[:translated.index("precracks:")] + translated[translated.index("initial_conditions:"):])
        bonds = [int(next(line.split()[1] for line in run([args.peridot, "check", d]).stdout.splitlines()
                          if line.startswith("bonds"))) for d in (out, uncut)]
        check(bonds[0] < bonds[1], f"grid ({model}): the pre-crack cuts no bond ({bonds[0]} against {bonds[1]})")
        print(f"PdQuickGrid ({model}): {len(x)} points at the cell centres, the bond filter a pre-crack cutting "
              f"{bonds[1] - bonds[0]} of {bonds[1]} bonds")

    # 4. A deck that cannot be translated: exit 2 at the Material Model's line, nothing written.
    deck = os.path.join(work, "bad.yaml")
    with open(deck, "w") as f:
        f.write(BAD_DECK)
    result = run([args.peridot, "import-peridigm", deck])
    check(result.returncode == 2 and f"{deck}:6:23: error: material model 'Pals' has no Peridot equivalent" in result.stderr,
          f"bad deck: exit {result.returncode}: {result.stderr.strip()}")
    check(not os.path.exists(os.path.join(work, "bad.peridot.yaml")), "bad deck: something was written")
    print(f"bad deck: {result.stderr.strip().splitlines()[0]}")
    print(f"{failures} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
