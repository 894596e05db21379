// libFuzzer harness of the text and binary mesh readers (geometry/mesh_gmsh.cpp, mesh_abaqus.cpp): the first
// byte picks the format ('g' Gmsh, anything else Abaqus), the rest is the file. A mesh may be refused
// (InputError) or read into points; anything else (a crash, a sanitizer report, another exception, a hang)
// is a bug. Exodus files are read by libexodusii and netCDF, not by code of ours, and are left out.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "peridot/core/error.hpp"
#include "peridot/geometry/mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool gmsh = data[0] == 'g';
  peridot::MeshSpec spec;
  spec.format = gmsh ? "gmsh" : "abaqus";
  spec.file = "/tmp/peridot-mesh-fuzz-" + std::to_string(getpid()) + (gmsh ? ".msh" : ".inp");
  {
    std::ofstream out(spec.file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const peridot::Mesh mesh = peridot::read_mesh(spec);
    for (int dimension : {3, 2}) {
      try {
        const peridot::MeshPoints points = peridot::mesh_points(mesh, spec, dimension, 1e-3, "fuzz");
        (void)peridot::mesh_point_sets(mesh, points);  // node, side and element sets as points
      } catch (const peridot::InputError&) {
        // refused with a position: what a bad mesh should get
      }
    }
  } catch (const peridot::InputError&) {
    // an unreadable file, refused the same way
  }
  return 0;
}
