#!/usr/bin/python3
"""Writes the mesh fuzzer's seeds into the folder given: small Gmsh 4.1 (ASCII and binary) and Abaqus meshes of
every element type the readers take, with element sets, node sets and physical groups, each prefixed by the format byte
fuzz/mesh_fuzzer.cpp reads ('g' Gmsh, 'a' Abaqus). Needs meshio (python3-meshio)."""
import os
import sys
import tempfile

import meshio
import numpy as np

folder = sys.argv[1]
os.makedirs(folder, exist_ok=True)
cube = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
meshes = {
    "hex": meshio.Mesh(cube, [("hexahedron", np.array([[0, 1, 2, 3, 4, 5, 6, 7]]))]),
    "tet": meshio.Mesh(cube, [("tetra", np.array([[0, 1, 2, 6], [0, 2, 3, 6]]))]),
    "wedge": meshio.Mesh(cube, [("wedge", np.array([[0, 1, 2, 4, 5, 6], [0, 2, 3, 4, 6, 7]]))]),
    "quad": meshio.Mesh(cube[:4], [("quad", np.array([[0, 1, 2, 3]]))]),
    "triangle": meshio.Mesh(cube[:4], [("triangle", np.array([[0, 1, 2], [0, 2, 3]]))]),
}
with tempfile.TemporaryDirectory() as scratch:
    for name, mesh in meshes.items():
        for suffix, prefix, options in [("ascii.msh", b"g", dict(file_format="gmsh", binary=False)),
                                        ("binary.msh", b"g", dict(file_format="gmsh", binary=True)),
                                        ("inp", b"a", dict(file_format="abaqus"))]:
            path = os.path.join(scratch, "mesh." + suffix.split(".")[-1])
            mesh.write(path, **options)
            with open(path, "rb") as f, open(os.path.join(folder, f"seed_{name}_{suffix}"), "wb") as out:
                out.write(prefix + f.read())
# Sets, generated sets, continuation lines and a part, as Abaqus/CAE writes them.
with open(os.path.join(folder, "seed_sets.inp"), "w") as out:
    out.write("a*Heading\n*Part, name=P\n*Node\n 1, 0., 0., 0.\n 2, 1., 0., 0.\n 3, 1., 1., 0.\n 4, 0., 1., 0.\n"
              " 5, 0., 0., 1.\n 6, 1., 0., 1.\n 7, 1., 1., 1.\n 8, 0., 1., 1.\n*Element, type=C3D8R, elset=BLOCK\n"
              "1, 1, 2, 3, 4,\n 5, 6, 7, 8\n*Elset, elset=ALL, generate\n 1, 1, 1\n*Elset, elset=BOTH\nALL, BLOCK\n"
              "*Nset, nset=FACE\n 1, 4, 5, 8\n*Nset, nset=EVERY, generate\n 1, 8, 1\n*Nset, nset=JOINED\nFACE, EVERY\n"
              "*End Part\n*Instance, name=I, part=P\n*End Instance\n")
# A Gmsh hexahedron with a physical volume and a physical surface on its face x = 0 (a node set).
with open(os.path.join(folder, "seed_face_group.msh"), "w") as out:
    out.write('g$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 10 "face"\n3 1 "solid"\n$EndPhysicalNames\n'
              "$Entities\n0 0 1 1\n1 0 0 0 0 1 1 1 10 0\n1 0 0 0 1 1 1 1 1 0\n$EndEntities\n$Nodes\n1 8 1 8\n3 1 0 8\n"
              + "".join(f"{i + 1}\n" for i in range(8)) + "".join(f"{x:g} {y:g} {z:g}\n" for x, y, z in cube)
              + "$EndNodes\n$Elements\n2 2 1 2\n2 1 3 1\n1 1 4 8 5\n3 1 5 1\n2 1 2 3 4 5 6 7 8\n$EndElements\n")
