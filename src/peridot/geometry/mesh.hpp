#pragma once
// Meshes as a source of points (bodies.<name>.mesh). A format's reader fills a Mesh: nodes and element blocks.
// mesh_points() turns the elements of a body's block into points, each at its element's centroid with the
// element's volume (area × thickness in 2D), both integrated over the isoparametric map by Gauss quadrature,
// which is exact for these elements; a SPHERE element is its node with its volume attribute.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "peridot/core/error.hpp"
#include "peridot/core/vec3.hpp"
#include "peridot/deck/problem.hpp"

namespace peridot {

enum class ElementShape { sphere, tri3, quad4, tet4, wedge6, hex8 };

int corner_count(ElementShape shape);  ///< nodes per element: 1, 3, 4, 4, 6, 8
int element_dimension(ElementShape shape);  ///< 0 for a sphere, else 2 or 3
const char* element_name(ElementShape shape);  ///< "SPHERE", "TRI3", "QUAD4", "TET4", "WEDGE6", "HEX8"

struct MeshBlock {
  std::string name;  ///< the block's name, or block_<id> when the file gives none
  ElementShape shape = ElementShape::hex8;
  std::vector<std::int64_t> connectivity;  ///< 0-based node indices, corner_count(shape) per element
  std::vector<double> sphere_volume;       ///< SPHERE blocks: each element's volume
  std::size_t size() const { return connectivity.size() / static_cast<std::size_t>(corner_count(shape)); }
};

/// A named group of elements across blocks (an Abaqus element set, a Gmsh physical group), by their index in
/// the order of the blocks.
struct MeshElementSet {
  std::string name;
  std::vector<std::size_t> elements;
};

/// A named group of nodes (an Exodus node set, an Abaqus *NSET, the nodes of a Gmsh physical group of a lower
/// dimension than the elements: a boundary surface or curve), by node index.
struct MeshNodeSet {
  std::string name;
  std::vector<std::size_t> nodes;
};

struct Mesh {
  std::string file;
  int dimension = 3;        ///< of the node coordinates
  std::vector<Vec3> nodes;  ///< unscaled, as in the file
  std::vector<MeshBlock> blocks;
  std::vector<MeshElementSet> element_sets;
  std::vector<MeshNodeSet> node_sets;
  std::vector<MeshElementSet> side_sets;  ///< Exodus side sets: the elements whose sides they list
};

/// An element's centroid and measure (volume of a solid, area of a 2D element). `valid` is false when the
/// Jacobian of the map from the reference element is not positive at some quadrature point: an element
/// inverted (its nodes in the wrong order) or degenerate (collapsed faces or edges).
struct ElementMeasure {
  Vec3 centroid;
  double measure = 0;
  bool valid = false;
};
ElementMeasure measure_element(ElementShape shape, std::span<const Vec3> corners);

struct MeshPoints {
  std::vector<Vec3> x;
  std::vector<double> volume;
  std::vector<std::size_t> element;  ///< each point's element, by its index in the order of the blocks
};

/// The points of a body that a named set of its mesh selects, by index into MeshPoints (increasing).
struct MeshPointSet {
  std::string name;
  std::vector<std::size_t> points;
};

/// Every node set, side set and element set of the mesh as sets of the body's points: an element set or side set
/// selects the points of its elements; a node set the points of the elements with at least one node in it (for
/// SPHERE elements, the points at its nodes), the rule Peridigm applies to node sets of meshes it converts. A set
/// may select none of this body's points (it lies in another block).
std::vector<MeshPointSet> mesh_point_sets(const Mesh& mesh, const MeshPoints& points);

/// The mesh file of a spec, by its format's reader (below).
Mesh read_mesh(const MeshSpec& spec);

/// The points of a body's mesh: of its block or element set, or of every block. `cross_section` is the 2D
/// thickness (1 in 3D). Throws InputError at spec.pos for an unknown block, an element type that does not fit
/// the deck's dimension, or an inverted or degenerate element (named by block and number).
MeshPoints mesh_points(const Mesh& mesh, const MeshSpec& spec, int dimension, double cross_section, const std::string& body);

/// Names compared without case (Abaqus names, Exodus topologies and attributes): in capitals.
std::string upper_case(std::string text);

/// The readers, one file each: Exodus II through libexodusii (mesh_exodus.cpp), Abaqus input (mesh_abaqus.cpp),
/// Gmsh 4.1, ASCII or binary (mesh_gmsh.cpp). They throw InputError: at `pos`, or at the mesh file's line
/// for a problem in a text file.
Mesh read_exodus_mesh(const std::string& path, const SourcePos& pos);
Mesh read_abaqus_mesh(const std::string& path, const SourcePos& pos);
Mesh read_gmsh_mesh(const std::string& path, const SourcePos& pos);

}  // namespace peridot
