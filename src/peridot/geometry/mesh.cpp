#include "peridot/geometry/mesh.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace peridot {

int corner_count(ElementShape shape) {
  switch (shape) {
    case ElementShape::sphere: return 1;
    case ElementShape::tri3: return 3;
    case ElementShape::quad4: return 4;
    case ElementShape::tet4: return 4;
    case ElementShape::wedge6: return 6;
    case ElementShape::hex8: return 8;
  }
  return 0;
}

int element_dimension(ElementShape shape) {
  switch (shape) {
    case ElementShape::sphere: return 0;
    case ElementShape::tri3:
    case ElementShape::quad4: return 2;
    default: return 3;
  }
}

const char* element_name(ElementShape shape) {
  switch (shape) {
    case ElementShape::sphere: return "SPHERE";
    case ElementShape::tri3: return "TRI3";
    case ElementShape::quad4: return "QUAD4";
    case ElementShape::tet4: return "TET4";
    case ElementShape::wedge6: return "WEDGE6";
    case ElementShape::hex8: return "HEX8";
  }
  return "?";
}

namespace {

struct QuadraturePoint {
  std::array<double, 3> xi;  ///< reference coordinates
  double weight;
};

double det3(Vec3 a, Vec3 b, Vec3 c) { return dot(a, cross(b, c)); }

/// Shape functions and their reference derivatives of the element at xi: N[i], dN[i][k] = ∂N_i/∂ξ_k.
/// Node order as Exodus II (and Abaqus, Gmsh) number the corners: a hexahedron's bottom face
/// counter-clockwise seen from above, then its top face; a wedge's bottom triangle, then its top one.
void shape_functions(ElementShape shape, const std::array<double, 3>& xi, std::array<double, 8>& N,
                     std::array<std::array<double, 3>, 8>& dN) {
  const double r = xi[0], s = xi[1], t = xi[2];
  switch (shape) {
    case ElementShape::hex8: {
      static constexpr int sign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                         {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
      for (int i = 0; i < 8; ++i) {
        const double a = 1 + sign[i][0] * r, b = 1 + sign[i][1] * s, c = 1 + sign[i][2] * t;
        N[i] = a * b * c / 8;
        dN[i] = {sign[i][0] * b * c / 8, sign[i][1] * a * c / 8, sign[i][2] * a * b / 8};
      }
      return;
    }
    case ElementShape::wedge6: {  // triangle coordinates (r, s) times the line coordinate t ∈ [-1, 1]
      const double L[3] = {1 - r - s, r, s};
      const double dL[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
      for (int i = 0; i < 3; ++i)
        for (int level = 0; level < 2; ++level) {
          const double h = level == 0 ? (1 - t) / 2 : (1 + t) / 2, dh = level == 0 ? -0.5 : 0.5;
          N[i + 3 * level] = L[i] * h;
          dN[i + 3 * level] = {dL[i][0] * h, dL[i][1] * h, L[i] * dh};
        }
      return;
    }
    case ElementShape::quad4: {
      static constexpr int sign[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (int i = 0; i < 4; ++i) {
        const double a = 1 + sign[i][0] * r, b = 1 + sign[i][1] * s;
        N[i] = a * b / 4;
        dN[i] = {sign[i][0] * b / 4, sign[i][1] * a / 4, 0};
      }
      return;
    }
    default: return;  // simplices and spheres are measured in closed form
  }
}

/// Rules exact for the centroid's integrand x det J: degree 3 along each hexahedron or quadrilateral axis
/// (2 Gauss points), degree 2 on the wedge's triangle (3 points) times degree 3 along its axis.
std::vector<QuadraturePoint> quadrature(ElementShape shape) {
  const double g = 1 / std::sqrt(3.0);
  std::vector<QuadraturePoint> points;
  switch (shape) {
    case ElementShape::hex8:
      for (double t : {-g, g})
        for (double s : {-g, g})
          for (double r : {-g, g}) points.push_back({{r, s, t}, 1.0});
      break;
    case ElementShape::wedge6:
      for (double t : {-g, g})
        for (const auto& [r, s] : {std::array<double, 2>{1.0 / 6, 1.0 / 6}, std::array<double, 2>{2.0 / 3, 1.0 / 6},
                                   std::array<double, 2>{1.0 / 6, 2.0 / 3}})
          points.push_back({{r, s, t}, 1.0 / 6});
      break;
    case ElementShape::quad4:
      for (double s : {-g, g})
        for (double r : {-g, g}) points.push_back({{r, s, 0}, 1.0});
      break;
    default: break;
  }
  return points;
}

ElementMeasure isoparametric(ElementShape shape, std::span<const Vec3> corners) {
  const int n = corner_count(shape);
  const bool solid = element_dimension(shape) == 3;
  ElementMeasure m;
  m.valid = true;
  Vec3 moment;
  std::array<double, 8> N{};
  std::array<std::array<double, 3>, 8> dN{};
  for (const QuadraturePoint& q : quadrature(shape)) {
    shape_functions(shape, q.xi, N, dN);
    Vec3 x, column[3];
    for (int i = 0; i < n; ++i) {
      x = x + N[i] * corners[i];
      for (int k = 0; k < 3; ++k) column[k] = column[k] + dN[i][k] * corners[i];
    }
    const double J = solid ? det3(column[0], column[1], column[2]) : column[0].x * column[1].y - column[0].y * column[1].x;
    if (!(J > 0)) m.valid = false;
    m.measure += q.weight * J;
    moment = moment + (q.weight * J) * x;
  }
  m.centroid = (1 / m.measure) * moment;
  return m;
}

}  // namespace

ElementMeasure measure_element(ElementShape shape, std::span<const Vec3> corners) {
  ElementMeasure m;
  switch (shape) {
    case ElementShape::tet4: {
      m.measure = det3(corners[1] - corners[0], corners[2] - corners[0], corners[3] - corners[0]) / 6;
      m.centroid = 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
      m.valid = m.measure > 0;
      return m;
    }
    case ElementShape::tri3: {
      const Vec3 a = corners[1] - corners[0], b = corners[2] - corners[0];
      m.measure = (a.x * b.y - a.y * b.x) / 2;
      m.centroid = (1.0 / 3) * (corners[0] + corners[1] + corners[2]);
      m.valid = m.measure > 0;
      return m;
    }
    case ElementShape::sphere:
      m.centroid = corners[0];
      m.valid = true;
      return m;
    default: return isoparametric(shape, corners);
  }
}

std::string upper_case(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::toupper(c); });
  return text;
}

Mesh read_mesh(const MeshSpec& spec) {
  if (spec.format == "abaqus") return read_abaqus_mesh(spec.file, spec.pos);
  if (spec.format == "gmsh") return read_gmsh_mesh(spec.file, spec.pos);
  return read_exodus_mesh(spec.file, spec.pos);
}

MeshPoints mesh_points(const Mesh& mesh, const MeshSpec& spec, int dimension, double cross_section, const std::string& body) {
  const std::string where = fmt::format("bodies.{}.mesh ({})", body, spec.file);
  // The elements taken, as (block, element in block): a block by name, else an element set, else all.
  std::vector<std::pair<std::size_t, std::size_t>> taken;
  // Abaqus names compare without case (the reader has them in capitals).
  const std::string wanted = spec.format == "abaqus" ? upper_case(spec.block) : spec.block;
  std::vector<std::string> names;
  std::vector<std::size_t> first(mesh.blocks.size() + 1, 0);
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    first[b + 1] = first[b] + mesh.blocks[b].size();
    names.push_back(mesh.blocks[b].name);
    if (spec.block.empty() || mesh.blocks[b].name == wanted)
      for (std::size_t e = 0; e < mesh.blocks[b].size(); ++e) taken.emplace_back(b, e);
  }
  for (const MeshElementSet& set : mesh.element_sets) {
    names.push_back(set.name);
    if (spec.block.empty() || set.name != wanted || !taken.empty()) continue;
    for (std::size_t global : set.elements) {
      const auto b = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), global) - first.begin()) - 1;
      taken.emplace_back(b, global - first[b]);
    }
  }
  if (taken.empty())
    throw InputError(spec.pos, spec.block.empty() ? fmt::format("{}: the file has no element", where)
                                                  : fmt::format("{}: no element block or set '{}'; the file has {}", where,
                                                                spec.block, fmt::join(names, ", ")));
  if (dimension >= 2 && mesh.dimension < dimension)
    throw InputError(spec.pos, fmt::format("{}: a {}D mesh in a {}D deck", where, mesh.dimension, dimension));

  MeshPoints points;
  std::vector<Vec3> corners;
  for (const auto& [b, e] : taken) {
    const MeshBlock& block = mesh.blocks[b];
    const int element_dim = element_dimension(block.shape);
    if (element_dim != 0 && element_dim != dimension)
      throw InputError(spec.pos, fmt::format("{}: block '{}' holds {} elements, which have no place in a {}D deck{}",
                                             where, block.name, element_name(block.shape), dimension,
                                             dimension == 1 ? " (a bar reads SPHERE elements only)" : ""));
    if (dimension == 2 && element_dim == 2)
      for (int i = 0; i < corner_count(block.shape); ++i)
        if (mesh.nodes[block.connectivity[e * corner_count(block.shape) + i]].z != 0)
          throw InputError(spec.pos, fmt::format("{}: element {} of block '{}' lies off the plane z = 0", where, e + 1,
                                                 block.name));
    const int n = corner_count(block.shape);
    corners.clear();
    for (int i = 0; i < n; ++i) corners.push_back(spec.scale * mesh.nodes[block.connectivity[e * n + i]]);
    const ElementMeasure m = measure_element(block.shape, corners);
    const double volume = block.shape == ElementShape::sphere ? block.sphere_volume[e] * spec.scale * spec.scale * spec.scale
                                                              : m.measure * (dimension == 2 ? cross_section : 1.0);
    if (!m.valid || !(volume > 0) || !std::isfinite(volume))
      throw InputError(spec.pos, fmt::format("{}: element {} of block '{}' ({}) is {} (volume {:g})", where, e + 1,
                                             block.name, element_name(block.shape),
                                             block.shape == ElementShape::sphere
                                                 ? "given no positive volume"
                                                 : "inverted or degenerate: its Jacobian is not positive everywhere",
                                             volume));
    points.x.push_back(m.centroid);
    points.volume.push_back(volume);
    points.element.push_back(first[b] + e);
  }
  return points;
}

std::vector<MeshPointSet> mesh_point_sets(const Mesh& mesh, const MeshPoints& points) {
  std::size_t element_count = 0;
  for (const MeshBlock& block : mesh.blocks) element_count += block.size();
  // point_of[element]: the body's point made of that element, or none.
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> point_of(element_count, none);
  for (std::size_t k = 0; k < points.element.size(); ++k) point_of[points.element[k]] = k;
  auto finish = [](std::vector<std::size_t>& selected) {
    std::sort(selected.begin(), selected.end());
    selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
  };
  std::vector<MeshPointSet> sets;
  for (const auto* group : {&mesh.element_sets, &mesh.side_sets})
    for (const MeshElementSet& set : *group) {
      MeshPointSet out{set.name, {}};
      for (std::size_t element : set.elements)
        if (element < element_count && point_of[element] != none) out.points.push_back(point_of[element]);
      finish(out.points);
      sets.push_back(std::move(out));
    }
  if (mesh.node_sets.empty()) return sets;
  std::vector<char> in_set(mesh.nodes.size());
  for (const MeshNodeSet& set : mesh.node_sets) {
    std::fill(in_set.begin(), in_set.end(), 0);
    for (std::size_t node : set.nodes)
      if (node < in_set.size()) in_set[node] = 1;
    MeshPointSet out{set.name, {}};
    std::size_t global = 0;
    for (const MeshBlock& block : mesh.blocks) {
      const auto n = static_cast<std::size_t>(corner_count(block.shape));
      for (std::size_t e = 0; e < block.size(); ++e, ++global) {
        if (point_of[global] == none) continue;
        for (std::size_t i = 0; i < n; ++i)
          if (in_set[static_cast<std::size_t>(block.connectivity[e * n + i])]) {
            out.points.push_back(point_of[global]);
            break;
          }
      }
    }
    finish(out.points);
    sets.push_back(std::move(out));
  }
  return sets;
}

}  // namespace peridot
