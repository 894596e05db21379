// Mesh input (geometry/mesh.hpp): element centroids and volumes against closed forms, and Exodus II meshes
// written here with libexodusii (no checked-in files) read as bodies: a HEX8 box gives the built-in box's
// points, volumes and motion; SPHERE elements give their nodes and volume attributes; bad meshes are refused
// at the deck's `file` entry.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <exodusII.h>

#include "peridot/core/error.hpp"
#include "peridot/deck/deck.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/geometry/mesh.hpp"
#include "peridot/solvers/simulation.hpp"

namespace fs = std::filesystem;
using namespace peridot;

namespace {

std::vector<Vec3> affine(const std::vector<Vec3>& reference) {
  // x → A x + b with det A = 2.5 (a shear, a stretch and a tilt)
  std::vector<Vec3> out;
  for (const Vec3& p : reference)
    out.push_back({2 * p.x + 0.3 * p.y + 0.1 * p.z + 1, 0.2 * p.x + 1.5 * p.y - 0.4 * p.z - 2, 0.1 * p.y + 0.8 * p.z + 3});
  return out;
}
constexpr double affine_det = 2 * (1.5 * 0.8 + 0.4 * 0.1) - 0.3 * (0.2 * 0.8) + 0.1 * (0.2 * 0.1);
Vec3 affine_point(Vec3 p) { return affine({p})[0]; }

const std::vector<Vec3> unit_hex = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const std::vector<Vec3> unit_wedge = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
const std::vector<Vec3> unit_tet = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

void expect_near(Vec3 a, Vec3 b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

}  // namespace

TEST(MeshElements, AffineSolidsHaveTheirExactVolumeAndCentroid) {
  const ElementMeasure hex = measure_element(ElementShape::hex8, affine(unit_hex));
  EXPECT_TRUE(hex.valid);
  EXPECT_NEAR(hex.measure, affine_det, 1e-14);
  expect_near(hex.centroid, affine_point({0.5, 0.5, 0.5}), 1e-14);
  const ElementMeasure wedge = measure_element(ElementShape::wedge6, affine(unit_wedge));
  EXPECT_TRUE(wedge.valid);
  EXPECT_NEAR(wedge.measure, affine_det / 2, 1e-14);
  expect_near(wedge.centroid, affine_point({1.0 / 3, 1.0 / 3, 0.5}), 1e-14);
  const ElementMeasure tet = measure_element(ElementShape::tet4, affine(unit_tet));
  EXPECT_TRUE(tet.valid);
  EXPECT_NEAR(tet.measure, affine_det / 6, 1e-14);
  expect_near(tet.centroid, affine_point({0.25, 0.25, 0.25}), 1e-14);
}

TEST(MeshElements, FrustumHexIsIntegratedExactly) {
  // A square frustum, side a at z = 0 and b at z = h (planar faces: the trilinear map is the frustum itself):
  // V = h (a² + ab + b²)/3, centroid height h (a² + 2ab + 3b²) / (4 (a² + ab + b²)).
  const double a = 2, b = 0.5, h = 1.5;
  std::vector<Vec3> corners;
  for (int level = 0; level < 2; ++level) {
    const double s = level == 0 ? a : b, z = level * h;
    for (Vec3 c : {Vec3{-1, -1, 0}, Vec3{1, -1, 0}, Vec3{1, 1, 0}, Vec3{-1, 1, 0}}) corners.push_back({c.x * s / 2, c.y * s / 2, z});
  }
  const ElementMeasure m = measure_element(ElementShape::hex8, corners);
  EXPECT_TRUE(m.valid);
  EXPECT_NEAR(m.measure, h * (a * a + a * b + b * b) / 3, 1e-14);
  expect_near(m.centroid, {0, 0, h * (a * a + 2 * a * b + 3 * b * b) / (4 * (a * a + a * b + b * b))}, 1e-14);
}

TEST(MeshElements, PlaneElementsAndTheirOrientation) {
  const std::vector<Vec3> quad = {{0, 0, 0}, {3, 0, 0}, {2, 1, 0}, {0, 1, 0}};  // a trapezoid, area 2.5
  const ElementMeasure q = measure_element(ElementShape::quad4, quad);
  EXPECT_TRUE(q.valid);
  EXPECT_NEAR(q.measure, 2.5, 1e-14);
  const double x_bar = (2 * 1.0 + 0.5 * (2 + 1.0 / 3)) / 2.5;  // rectangle [0,2]×[0,1] plus triangle (2,0)(3,0)(2,1)
  EXPECT_NEAR(q.centroid.x, x_bar, 1e-14);
  EXPECT_NEAR(q.centroid.y, (2 * 0.5 + 0.5 * (1.0 / 3)) / 2.5, 1e-14);
  const ElementMeasure t = measure_element(ElementShape::tri3, {{{0, 0, 0}, {2, 0, 0}, {0, 3, 0}}});
  EXPECT_TRUE(t.valid);
  EXPECT_NEAR(t.measure, 3, 1e-14);
  const ElementMeasure clockwise = measure_element(ElementShape::quad4, {{quad[0], quad[3], quad[2], quad[1]}});
  EXPECT_FALSE(clockwise.valid);
}

TEST(MeshElements, InvertedAndDegenerateElementsAreNotValid) {
  std::vector<Vec3> flipped = unit_hex;  // top and bottom faces swapped: inside out
  std::rotate(flipped.begin(), flipped.begin() + 4, flipped.end());
  EXPECT_FALSE(measure_element(ElementShape::hex8, flipped).valid);
  std::vector<Vec3> collapsed = unit_hex;  // the top face pulled down onto the bottom one
  for (int i = 4; i < 8; ++i) collapsed[i].z = 0;
  EXPECT_FALSE(measure_element(ElementShape::hex8, collapsed).valid);
  EXPECT_FALSE(measure_element(ElementShape::tet4, {{unit_tet[0], unit_tet[2], unit_tet[1], unit_tet[3]}}).valid);
  std::vector<Vec3> bow_tie = unit_hex;  // two top corners crossed: the Jacobian changes sign inside
  std::swap(bow_tie[6], bow_tie[7]);
  EXPECT_FALSE(measure_element(ElementShape::hex8, bow_tie).valid);
}

namespace {

struct HexBox {
  Vec3 lo;
  double h;     ///< element edge
  int n[3];     ///< elements per direction
  int split_x;  ///< elements with i < split_x go to block "left", the others to "right" (0: one block "box")
};

/// The box's nodes and each block's elements (0-based corner nodes in Exodus order), one block or two, and the
/// nodes of its face x = lo.x (written as a node set "left_face" or a Gmsh physical surface of that name).
struct BoxMesh {
  std::vector<Vec3> nodes;
  std::vector<std::string> names;
  std::vector<std::vector<std::array<int, 8>>> blocks;
  std::vector<int> left_face;  ///< 0-based nodes with i = 0
  std::vector<std::array<int, 4>> left_quads;  ///< the faces of the elements with i = 0 on x = lo.x
};

BoxMesh box_mesh(const HexBox& box, int invert = -1) {
  BoxMesh m;
  const int nx = box.n[0] + 1, ny = box.n[1] + 1, nz = box.n[2] + 1;
  auto node = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (i == 0) m.left_face.push_back(node(i, j, k));
        m.nodes.push_back({box.lo.x + i * box.h, box.lo.y + j * box.h, box.lo.z + k * box.h});
      }
  m.names = box.split_x > 0 ? std::vector<std::string>{"left", "right"} : std::vector<std::string>{"box"};
  m.blocks.resize(m.names.size());
  for (int k = 0; k < box.n[2]; ++k)
    for (int j = 0; j < box.n[1]; ++j)
      for (int i = 0; i < box.n[0]; ++i) {
        std::array<int, 8> c = {node(i, j, k),     node(i + 1, j, k),     node(i + 1, j + 1, k),     node(i, j + 1, k),
                                node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        auto& block = m.blocks[box.split_x > 0 && i >= box.split_x ? 1 : 0];
        if (i == 0) m.left_quads.push_back({c[0], c[3], c[7], c[4]});
        if (static_cast<int>(block.size()) == invert) std::rotate(c.begin(), c.begin() + 4, c.end());
        block.push_back(c);
      }
  return m;
}

void check(int status) { ASSERT_GE(status, 0) << "libexodusii status " << status; }

/// The box as Exodus II, with libexodusii. `topology` makes bad meshes. With `sets`, a node set "left_face" and a
/// side set "right_face" of the elements of the last block's last column (side 2, the face x = max).
void write_exodus(const std::string& path, const BoxMesh& m, const char* topology = "HEX8", bool sets = false) {
  int word = sizeof(double), io_word = sizeof(double);
  const int exoid = ex_create(path.c_str(), EX_CLOBBER, &word, &io_word);
  ASSERT_GE(exoid, 0);
  const int nodes = static_cast<int>(m.nodes.size());
  int elements = 0;
  for (const auto& block : m.blocks) elements += static_cast<int>(block.size());
  check(ex_put_init(exoid, "hex box", 3, nodes, elements, static_cast<int>(m.blocks.size()), sets ? 1 : 0, sets ? 1 : 0));
  std::vector<double> x, y, z;
  for (const Vec3& p : m.nodes) x.push_back(p.x), y.push_back(p.y), z.push_back(p.z);
  check(ex_put_coord(exoid, x.data(), y.data(), z.data()));
  std::vector<std::string> names = m.names;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    std::vector<int> conn;
    for (const auto& element : m.blocks[b])
      for (int id : element) conn.push_back(id + 1);
    check(ex_put_block(exoid, EX_ELEM_BLOCK, static_cast<int>(b) + 1, topology, static_cast<int>(m.blocks[b].size()), 8, 0, 0, 0));
    check(ex_put_conn(exoid, EX_ELEM_BLOCK, static_cast<int>(b) + 1, conn.data(), nullptr, nullptr));
  }
  std::vector<char*> pointers;
  for (std::string& name : names) pointers.push_back(name.data());
  check(ex_put_names(exoid, EX_ELEM_BLOCK, pointers.data()));
  if (sets) {
    std::vector<int> face;
    for (int node : m.left_face) face.push_back(node + 1);
    check(ex_put_set_param(exoid, EX_NODE_SET, 1, static_cast<int>(face.size()), 0));
    check(ex_put_set(exoid, EX_NODE_SET, 1, face.data(), nullptr));
    char left[] = "left_face";
    char* left_name[] = {left};
    check(ex_put_names(exoid, EX_NODE_SET, left_name));
    // The elements with the largest x centroid: the last column, numbered in block order from 1.
    std::vector<int> side_elements, sides;
    int number = 0;
    double right = -1e300;
    for (const auto& block : m.blocks)
      for (const auto& element : block) right = std::max(right, m.nodes[element[1]].x);
    for (const auto& block : m.blocks)
      for (const auto& element : block) {
        ++number;
        if (m.nodes[element[1]].x == right) side_elements.push_back(number), sides.push_back(2);
      }
    check(ex_put_set_param(exoid, EX_SIDE_SET, 1, static_cast<int>(side_elements.size()), 0));
    check(ex_put_set(exoid, EX_SIDE_SET, 1, side_elements.data(), sides.data()));
    char right_face[] = "right_face";
    char* right_name[] = {right_face};
    check(ex_put_names(exoid, EX_SIDE_SET, right_name));
  }
  check(ex_close(exoid));
}

void write_hex_box(const std::string& path, const HexBox& box, const char* topology = "HEX8", int invert = -1) {
  write_exodus(path, box_mesh(box, invert), topology);
}

/// The box as an Abaqus input file: nodes and elements numbered from 1, one *ELEMENT section per block
/// (elset = its name in capitals), and an element set of everything.
void write_abaqus(const std::string& path, const BoxMesh& m) {
  std::ofstream out(path);
  out << "*Heading\n** a box of C3D8R elements, written by mesh_test\n*Node\n";
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    out << i + 1 << ", " << m.nodes[i].x << ", " << m.nodes[i].y << ", " << m.nodes[i].z << "\n";
  int number = 0;
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    std::string name = m.names[b];
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
    out << "*Element, type=C3D8R, elset=" << name << "\n";
    for (const auto& element : m.blocks[b]) {
      out << ++number;
      for (int id : element) out << ", " << id + 1;
      out << "\n";
    }
  }
  out << "*Elset, elset=ALL, generate\n 1, " << number << ", 1\n";
  // The face x = lo.x as a node set, in two *Nset sections of the same name (the second grows the first).
  for (std::size_t k = 0; k < m.left_face.size(); ++k)
    out << (k == 0 ? "*Nset, nset=Left_Face\n" : k == m.left_face.size() / 2 ? "\n*Nset, nset=LEFT_FACE\n" : k % 8 == 0 ? ",\n" : ", ")
        << m.left_face[k] + 1;
  out << "\n*End Step\n";
}

/// The box as a Gmsh 4.1 file, ASCII or binary: a volume entity and a physical group per block, all nodes in
/// one block, and the quadrangles of the face x = lo.x on a boundary surface, its own physical group "left_face"
/// (a node set).
void write_gmsh(const std::string& path, const BoxMesh& m, bool binary) {
  std::ofstream out(path, std::ios::binary);
  auto size = [&](std::uint64_t v) {
    if (binary) out.write(reinterpret_cast<const char*>(&v), sizeof v);
    else out << v << ' ';
  };
  auto integer = [&](std::int32_t v) {
    if (binary) out.write(reinterpret_cast<const char*>(&v), sizeof v);
    else out << v << ' ';
  };
  auto number = [&](double v) {
    if (binary) out.write(reinterpret_cast<const char*>(&v), sizeof v);
    else out << v << ' ';
  };
  auto end_line = [&]() {
    if (!binary) out << "\n";
  };
  out << "$MeshFormat\n4.1 " << (binary ? 1 : 0) << " 8\n";
  if (binary) integer(1);
  out << "\n$EndMeshFormat\n$PhysicalNames\n" << m.blocks.size() + 1 << "\n2 10 \"left_face\"\n";
  for (std::size_t b = 0; b < m.blocks.size(); ++b) out << "3 " << b + 1 << " \"" << m.names[b] << "\"\n";
  out << "$EndPhysicalNames\n$Entities\n";
  size(0), size(0), size(1), size(m.blocks.size()), end_line();
  integer(1);  // the boundary surface, physical group 10
  for (int i = 0; i < 6; ++i) number(0);
  size(1), integer(10), size(0), end_line();
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    integer(static_cast<std::int32_t>(b) + 1);
    for (int i = 0; i < 6; ++i) number(0);
    size(1), integer(static_cast<std::int32_t>(b) + 1), size(0), end_line();
  }
  out << (binary ? "\n" : "") << "$EndEntities\n$Nodes\n";
  const std::uint64_t n = m.nodes.size();
  size(1), size(n), size(1), size(n), end_line();
  integer(3), integer(1), integer(0), size(n), end_line();
  for (std::uint64_t i = 0; i < n; ++i) size(i + 1), end_line();
  for (const Vec3& p : m.nodes) number(p.x), number(p.y), number(p.z), end_line();
  out << (binary ? "\n" : "") << "$EndNodes\n$Elements\n";
  std::uint64_t elements = m.left_quads.size();
  for (const auto& block : m.blocks) elements += block.size();
  size(m.blocks.size() + 1), size(elements), size(1), size(elements), end_line();
  std::uint64_t tag = 0;
  integer(2), integer(1), integer(3), size(m.left_quads.size()), end_line();  // the quadrangles of the face x = lo.x
  for (const auto& quad : m.left_quads) {
    size(++tag);
    for (int id : quad) size(static_cast<std::uint64_t>(id) + 1);
    end_line();
  }
  for (std::size_t b = 0; b < m.blocks.size(); ++b) {
    integer(3), integer(static_cast<std::int32_t>(b) + 1), integer(5), size(m.blocks[b].size()), end_line();
    for (const auto& element : m.blocks[b]) {
      size(++tag);
      for (int id : element) size(static_cast<std::uint64_t>(id) + 1);
      end_line();
    }
  }
  out << (binary ? "\n" : "") << "$EndElements\n";
}

/// SPHERE elements at given points with attributes (radius, volume), unnamed as Sierra writes them.
void write_spheres(const std::string& path, const std::vector<Vec3>& points, const std::vector<double>& volumes) {
  int word = sizeof(double), io_word = sizeof(double);
  const int exoid = ex_create(path.c_str(), EX_CLOBBER, &word, &io_word);
  ASSERT_GE(exoid, 0);
  const int n = static_cast<int>(points.size());
  check(ex_put_init(exoid, "spheres", 3, n, n, 1, 0, 0));
  std::vector<double> x, y, z, attributes;
  std::vector<int> conn;
  for (int i = 0; i < n; ++i) {
    x.push_back(points[i].x), y.push_back(points[i].y), z.push_back(points[i].z);
    conn.push_back(i + 1);
    attributes.push_back(std::cbrt(volumes[i]));  // a radius of some sort: not what is read
    attributes.push_back(volumes[i]);
  }
  check(ex_put_coord(exoid, x.data(), y.data(), z.data()));
  check(ex_put_block(exoid, EX_ELEM_BLOCK, 7, "SPHERE", n, 1, 0, 0, 2));
  check(ex_put_conn(exoid, EX_ELEM_BLOCK, 7, conn.data(), nullptr, nullptr));
  check(ex_put_attr(exoid, EX_ELEM_BLOCK, 7, attributes.data()));
  check(ex_close(exoid));
}

fs::path scratch(const std::string& name) {
  const fs::path folder = fs::temp_directory_path() / "peridot_mesh_test";
  fs::create_directories(folder);
  return folder / name;
}

std::string deck(const std::string& bodies, const std::string& extra = "") {
  return "discretization: {dimension: 3, spacing: 1 mm, horizon_factor: 3.015}\n"
         "materials:\n"
         "  aluminium: {model: lps, density: 2700, youngs_modulus: 70 GPa, poisson_ratio: 0.3}\n"
         "  steel: {model: pmb, density: 7800, youngs_modulus: 200 GPa}\n"
         "bodies:\n" +
         bodies +
         "initial_conditions:\n"
         "  - {velocity: {x: \"10 * (x - 0.004) / 0.004\", z: \"3 * sin(1000 * y)\"}}\n"
         "solver: {num_steps: 30}\n" +
         extra + "output: {progress: false}\n";
}

std::string mesh_deck(const fs::path& mesh, const std::string& extra_mesh_keys = "") {
  return deck("  left: {material: aluminium, mesh: {file: " + mesh.filename().string() + ", block: left" + extra_mesh_keys +
              "}}\n  right: {material: steel, mesh: {file: " + mesh.filename().string() + ", block: right" +
              extra_mesh_keys + "}}\n");
}

const std::string built_in_bodies =
    "  left: {material: aluminium, shape: {box: {min: [0, 0, 0], max: [0.005, 0.004, 0.003]}}}\n"
    "  right: {material: steel, shape: {box: {min: [0.005, 0, 0], max: [0.008, 0.004, 0.003]}}}\n";

/// Each point's block, position, volume and final displacement, in an order that does not depend on the input.
std::vector<std::array<double, 8>> run(const Problem& problem) {
  Simulation sim(problem);
  sim.initialize();
  while (sim.state().step < sim.total_steps()) sim.step();
  const Discretization& d = sim.discretization();
  std::vector<std::array<double, 8>> rows;
  for (std::size_t i = 0; i < d.num_points(); ++i)
    rows.push_back({static_cast<double>(d.block[i]), d.x(i, 0), d.x(i, 1), d.x(i, 2), d.volume[i], sim.state().u(i, 0),
                    sim.state().u(i, 1), sim.state().u(i, 2)});
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    for (int k = 0; k < 4; ++k)
      if (std::abs(a[k] - b[k]) > 1e-9) return a[k] < b[k];
    return false;
  });
  return rows;
}

}  // namespace

// The must-show of mesh input: the same box as Exodus HEX8, Gmsh (ASCII and binary) and Abaqus, each in
// millimetres, gives the built-in box's points, volumes and motion.
TEST(MeshInput, EveryFormatGivesTheBuiltInBoxsPointsVolumesAndMotion) {
  const BoxMesh box = box_mesh({{0, 0, 0}, 1, {8, 4, 3}, 5});
  write_exodus(scratch("box.e").string(), box);
  write_gmsh(scratch("box_ascii.msh").string(), box, false);
  write_gmsh(scratch("box_binary.msh").string(), box, true);
  write_abaqus(scratch("box.inp").string(), box);
  const auto b = run(parse_deck(deck(built_in_bodies), "box.yaml", "."));
  ASSERT_EQ(b.size(), 96u);
  for (const char* file : {"box.e", "box_ascii.msh", "box_binary.msh", "box.inp"}) {
    SCOPED_TRACE(file);
    const auto a = run(parse_deck(mesh_deck(scratch(file), ", scale: 1e-3"), "mesh.yaml", scratch(file).parent_path().string()));
    ASSERT_EQ(a.size(), b.size());
    double volume_a = 0, volume_b = 0, largest_u = 0, largest_difference = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i][0], b[i][0]) << i;
      for (int k = 1; k <= 3; ++k) EXPECT_NEAR(a[i][k], b[i][k], 1e-17) << i;  // round-off of 8 mm
      EXPECT_NEAR(a[i][4], b[i][4], 1e-23) << i;                              // of 1 mm³
      volume_a += a[i][4], volume_b += b[i][4];
      for (int k = 5; k < 8; ++k) {
        largest_u = std::max(largest_u, std::abs(b[i][k]));
        largest_difference = std::max(largest_difference, std::abs(a[i][k] - b[i][k]));
      }
    }
    EXPECT_NEAR(volume_a, 96e-9, 1e-21);
    EXPECT_NEAR(volume_a, volume_b, 1e-21);
    EXPECT_GT(largest_u, 1e-7);                       // the run moved
    EXPECT_LT(largest_difference, 1e-9 * largest_u);  // the same motion to round-off
  }
}

TEST(MeshInput, ElementSetsAndPhysicalGroupsSelectLikeBlocks) {
  const BoxMesh box = box_mesh({{0, 0, 0}, 1, {8, 4, 3}, 5});
  write_gmsh(scratch("sets.msh").string(), box, false);
  write_abaqus(scratch("sets.inp").string(), box);
  const std::string folder = scratch("sets.inp").parent_path().string();
  for (const auto& [file, block, count] : std::vector<std::tuple<std::string, std::string, std::size_t>>{
           {"sets.msh", "left", 60}, {"sets.msh", "right", 36}, {"sets.msh", "entity_2", 36}, {"sets.msh", "", 96},
           {"sets.inp", "left", 60}, {"sets.inp", "RIGHT", 36}, {"sets.inp", "all", 96}, {"sets.inp", "", 96}}) {
    SCOPED_TRACE(file + " " + block);
    const std::string keys = block.empty() ? "" : ", block: " + block;
    const Problem p = parse_deck(deck("  box: {material: steel, mesh: {file: " + file + keys + "}}\n"), "mesh.yaml", folder);
    EXPECT_EQ(discretize(p).num_points(), count);
  }
}

// Node sets of meshes: an element belongs to a node set's points when any of its nodes is in the set (the face
// x = 0 selects the first column of elements), a side set or element set selects its elements; the same box in
// each format selects the same points as a node set by shape, from both bodies or only the listed one.
TEST(MeshNodeSets, MeshSetsSelectThePointsOfTheirElementsInEveryFormat) {
  const BoxMesh box = box_mesh({{0, 0, 0}, 1, {8, 4, 3}, 5});
  write_exodus(scratch("ns.e").string(), box, "HEX8", true);
  write_gmsh(scratch("ns_ascii.msh").string(), box, false);
  write_gmsh(scratch("ns_binary.msh").string(), box, true);
  write_abaqus(scratch("ns.inp").string(), box);
  const std::string folder = scratch("ns.e").parent_path().string();
  auto sets_of = [&](const std::string& file, const std::string& node_sets) {
    const Problem p = parse_deck(mesh_deck(scratch(file), ", scale: 1e-3") + "node_sets:\n" + node_sets, "mesh.yaml", folder);
    Simulation sim(p);
    // Each set's points by position (to 1e-9 m: the formats' centroids agree to round-off), sorted.
    std::map<std::string, std::vector<std::array<long, 3>>> out;
    for (const NodeSet& set : sim.node_sets())
      for (std::uint32_t i : set.points) {
        const Vec3 x = sim.discretization().x.get(i);
        out[set.name].push_back({std::lround(x.x * 1e9), std::lround(x.y * 1e9), std::lround(x.z * 1e9)});
      }
    for (auto& [name, points] : out) std::sort(points.begin(), points.end());
    return out;
  };
  const std::string by_shape =
      "  face: {shape: {box: {min: [-1, -1, -1], max: [0.001, 1, 1]}}}\n"
      "  far: {shape: {box: {min: [0.007, -1, -1], max: [1, 1, 1]}}}\n";
  const auto expected = sets_of("ns.e", by_shape);
  ASSERT_EQ(expected.at("face").size(), 12u);  // 4 × 3 elements in the column at x = 0
  for (const char* file : {"ns.e", "ns_ascii.msh", "ns_binary.msh", "ns.inp"}) {
    SCOPED_TRACE(file);
    const bool exodus = std::string(file) == "ns.e";
    const auto got = sets_of(file, "  face: {mesh_set: left_face}\n  face_of_left: {mesh_set: left_face, bodies: [left]}\n" +
                                       std::string(exodus ? "  far: {mesh_set: right_face}\n" : ""));
    EXPECT_EQ(got.at("face"), expected.at("face"));
    EXPECT_EQ(got.at("face_of_left"), expected.at("face"));
    if (exodus) {
      EXPECT_EQ(got.at("far"), expected.at("far"));
    }
  }
  // An element set (the Abaqus ALL, a Gmsh physical volume) is a node set of its points too.
  EXPECT_EQ(sets_of("ns.inp", "  everything: {mesh_set: all}\n").at("everything").size(), 96u);
  EXPECT_EQ(sets_of("ns_ascii.msh", "  lefts: {mesh_set: left}\n").at("lefts").size(), 60u);
}

TEST(MeshNodeSets, BadMeshSetsAreRefused) {
  const BoxMesh box = box_mesh({{0, 0, 0}, 1, {8, 4, 3}, 5});
  write_exodus(scratch("bad_ns.e").string(), box, "HEX8", true);
  const std::string folder = scratch("bad_ns.e").parent_path().string();
  auto error_of = [&](const std::string& text) -> std::string {
    try {
      Simulation sim(parse_deck(text, "mesh.yaml", folder));
    } catch (const InputError& e) {
      std::string all;
      for (const Diagnostic& d : e.diagnostics()) all += d.str() + "\n";
      return all;
    }
    return "no error";
  };
  const std::string bodies = mesh_deck(scratch("bad_ns.e"), ", scale: 1e-3");
  EXPECT_NE(error_of(bodies + "node_sets:\n  face: {mesh_set: left_fac}\n")
                .find("node_sets.face: the meshes of the bodies have no node, side or element set 'left_fac'; they have: "
                      "left_face, right_face"),
            std::string::npos);
  // The face x = 0 touches no element of the right body.
  EXPECT_NE(error_of(bodies + "node_sets:\n  face: {mesh_set: left_face, bodies: [right]}\n")
                .find("mesh.yaml:13:3: error: node_sets.face: mesh set 'left_face' selects no point of its bodies"),
            std::string::npos);
  EXPECT_NE(error_of(deck(built_in_bodies) + "node_sets:\n  face: {mesh_set: left_face}\n").find("no body is read from a mesh"),
            std::string::npos);
  // An Abaqus *NSET naming a node no *NODE gives: at the *NSET's line.
  {
    std::ofstream(scratch("bad_ns.inp")) << "*Node\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 0, 0, 1\n6, 1, 0, 1\n"
                                            "7, 1, 1, 1\n8, 0, 1, 1\n*Element, type=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 8\n"
                                            "*Nset, nset=grip\n1, 4, 99\n*Nset, nset=none\n";
    const std::string one = "  box: {material: steel, mesh: {file: bad_ns.inp, scale: 1e-3}}\n";
    const std::string message = error_of(deck(one));
    EXPECT_NE(message.find("bad_ns.inp:12:1: error: " + scratch("bad_ns.inp").string() +
                           ": node set 'GRIP' names node 99, which no *NODE gives"),
              std::string::npos)
        << message;
  }
  {
    std::ofstream(scratch("empty_ns.inp")) << "*Node\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 0, 0, 1\n"
                                              "6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n*Element, type=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 8\n"
                                              "*Nset, nset=none\n";
    const std::string message = error_of(deck("  box: {material: steel, mesh: {file: empty_ns.inp, scale: 1e-3}}\n"));
    EXPECT_NE(message.find("empty_ns.inp:12:1: error: "), std::string::npos) << message;
    EXPECT_NE(message.find("node set 'NONE' names no node"), std::string::npos) << message;
  }
}

TEST(ExodusMesh, EveryBlockWhenNoneIsNamedAndTheResolvedDeckKeepsTheMesh) {
  const fs::path mesh = scratch("one_block.e");
  write_hex_box(mesh.string(), {{0, 0, 0}, 0.001, {4, 3, 2}, 0});
  const Problem p = parse_deck(deck("  box: {material: steel, mesh: {file: one_block.e}}\n"), "mesh.yaml",
                               mesh.parent_path().string());
  ASSERT_TRUE(p.bodies[0].mesh);
  EXPECT_EQ(p.bodies[0].mesh->format, "exodus");
  EXPECT_EQ(p.bodies[0].mesh->file, mesh.string());
  const Discretization d = discretize(p);
  EXPECT_EQ(d.num_points(), 24u);
  const std::string resolved = resolved_deck_yaml(p);
  EXPECT_NE(resolved.find("mesh:"), std::string::npos) << resolved;
  const Problem again = parse_deck(resolved, "resolved.yaml", "/");
  EXPECT_EQ(discretize(again).num_points(), 24u);
}

TEST(ExodusMesh, SphereElementsAreTheirNodesWithTheirVolumes) {
  const fs::path mesh = scratch("spheres.e");
  const std::vector<Vec3> points = {{0, 0, 0}, {1e-3, 0, 0}, {0, 1e-3, 0}, {0, 0, 1.2e-3}};
  const std::vector<double> volumes = {1e-9, 2e-9, 0.5e-9, 1.5e-9};
  write_spheres(mesh.string(), points, volumes);
  const Problem p = parse_deck(deck("  cloud: {material: steel, mesh: {file: spheres.e}}\n"), "mesh.yaml",
                               mesh.parent_path().string());
  const Discretization d = discretize(p);
  ASSERT_EQ(d.num_points(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const std::size_t input = d.input_id[i];
    EXPECT_EQ(d.x.get(i).x, points[input].x);
    EXPECT_EQ(d.x.get(i).z, points[input].z);
    EXPECT_EQ(d.volume[i], volumes[input]);
  }
}

namespace {

void expect_refused(const std::string& text, const fs::path& folder, const std::string& message, int line = 6) {
  try {
    const Problem p = parse_deck(text, "mesh.yaml", folder.string());
    discretize(p);
    ADD_FAILURE() << "accepted; expected: " << message;
  } catch (const InputError& e) {
    const auto& all = e.diagnostics();
    const auto d = std::find_if(all.begin(), all.end(), [&](const Diagnostic& d) { return d.message.find(message) != std::string::npos; });
    ASSERT_NE(d, all.end()) << e.what();
    EXPECT_EQ(d->pos.file, "mesh.yaml");
    EXPECT_EQ(d->pos.line, line) << d->str();
  }
}

}  // namespace

TEST(ExodusMesh, BadMeshesAreRefusedAtTheDeckEntry) {
  const fs::path mesh = scratch("box_hex.e");
  write_hex_box(mesh.string(), {{0, 0, 0}, 1, {8, 4, 3}, 5});
  const fs::path folder = mesh.parent_path();
  expect_refused(deck("  left: {material: steel, mesh: {file: box_hex.e, block: middle}}\n"), folder,
                 "no element block or set 'middle'; the file has left, right");
  const fs::path inverted = scratch("inverted.e");
  write_hex_box(inverted.string(), {{0, 0, 0}, 1, {3, 3, 3}, 0}, "HEX8", 13);
  expect_refused(deck("  box: {material: steel, mesh: {file: inverted.e}}\n"), folder,
                 "element 14 of block 'box' (HEX8) is inverted or degenerate");
  const fs::path shell = scratch("shell.e");
  write_hex_box(shell.string(), {{0, 0, 0}, 1, {2, 2, 2}, 0}, "HEX20");
  expect_refused(deck("  box: {material: steel, mesh: {file: shell.e}}\n"), folder,
                 "has elements of type HEX20 with 8 nodes; supported are");
  expect_refused(deck("  box: {material: steel, mesh: {file: absent.e}}\n"), folder, "file not found");
  expect_refused(deck("  box: {material: steel, mesh: {file: /dev/zero, format: gmsh}}\n"), folder,
                 "not a regular file: /dev/zero");
  const fs::path text = scratch("not_a_mesh.e");
  { std::ofstream(text) << "hello\n"; }
  expect_refused(deck("  box: {material: steel, mesh: {file: not_a_mesh.e}}\n"), folder,
                 "cannot read '" + text.string() + "' as an Exodus II file");
  { std::ofstream(scratch("box.stl")) << "solid box\n"; }
  expect_refused(deck("  box: {material: steel, mesh: {file: box.stl}}\n"), folder,
                 "cannot tell the mesh format from the extension '.stl'");
  expect_refused(deck("  box: {material: steel, mesh: {file: box_hex.e, scale: 0}}\n"), folder, "scale");
}

namespace {

/// The InputError of reading a text mesh: at the mesh file's own line.
void expect_file_error(const std::string& file, const std::string& text, int line, const std::string& message) {
  const fs::path path = scratch(file);
  { std::ofstream(path, std::ios::binary) << text; }
  try {
    const Problem p = parse_deck(deck("  box: {material: steel, mesh: {file: " + file + "}}\n"), "mesh.yaml",
                                 path.parent_path().string());
    discretize(p);
    ADD_FAILURE() << "accepted; expected: " << message;
  } catch (const InputError& e) {
    const Diagnostic& d = e.diagnostics().at(0);
    EXPECT_EQ(d.pos.file, path.string()) << d.str();
    EXPECT_EQ(d.pos.line, line) << d.str();
    EXPECT_NE(d.message.find(message), std::string::npos) << d.str();
  }
}

}  // namespace

TEST(MeshInput, BadTextMeshesAreRefusedAtTheirLine) {
  const std::string nodes = "*Node\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n";
  expect_file_error("quadratic.inp", nodes + "*Element, type=C3D10, elset=E\n1, 1, 2, 3, 4\n", 6,
                    "element type 'C3D10' is not supported");
  expect_file_error("missing_node.inp", nodes + "*Element, type=C3D4, elset=E\n1, 1, 2, 3, 9\n", 7,
                    "block 'E' names node 9, which no *NODE gives");
  expect_file_error("letters.inp", "*Node\n1, 0, zero, 0\n", 2, "'zero' is not a number");
  expect_file_error("instance.inp", nodes + "*Instance, name=I, part=P\n 5., 0., 0.\n", 7, "an *INSTANCE moved or turned");
  expect_file_error("old.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n", 2, "Gmsh format 2.2; format 4.1 is read");
  expect_file_error("quadratic.msh",
                    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                    "$EndNodes\n$Elements\n1 1 1 1\n3 1 11 1\n1 1 2 3 4 1 2 3 4 1 2\n$EndElements\n",
                    17, "10-node tetrahedron elements (type 11) are not supported");
  expect_file_error("dangling.msh",
                    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                    "$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 5\n$EndElements\n",
                    17, "names node 5, which $Nodes does not give");
}

TEST(MeshInput, AbaqusSetNamedAgainGrowsAndTakesOtherSets) {
  const fs::path path = scratch("sets_again.inp");
  std::ofstream(path) << "*Node\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n5, 1, 1, 1\n"
                         "*Element, type=C3D4\n1, 1, 2, 3, 4\n2, 2, 3, 4, 5\n*Elset, elset=A\n1\n*Elset, elset=b\n2\n"
                         "*Elset, elset=A\nB\n";
  const Problem p = parse_deck(deck("  box: {material: steel, mesh: {file: sets_again.inp, block: a}}\n"), "mesh.yaml",
                               path.parent_path().string());
  EXPECT_EQ(discretize(p).num_points(), 2u);
}

TEST(MeshInput, TruncatedBinaryGmshIsRefused) {
  const BoxMesh box = box_mesh({{0, 0, 0}, 1, {2, 2, 2}, 0});
  const fs::path whole = scratch("whole.msh");
  write_gmsh(whole.string(), box, true);
  std::ifstream in(whole, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t cut : {bytes.size() / 3, bytes.size() / 2, bytes.size() - 20}) {
    SCOPED_TRACE(cut);
    { std::ofstream(scratch("cut.msh"), std::ios::binary) << bytes.substr(0, cut); }
    try {
      discretize(parse_deck(deck("  box: {material: steel, mesh: {file: cut.msh}}\n"), "mesh.yaml", whole.parent_path().string()));
      ADD_FAILURE() << "a truncated file was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cut.msh"), std::string::npos) << e.what();
    }
  }
}
