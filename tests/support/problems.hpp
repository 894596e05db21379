#pragma once
#include <algorithm>
// Small problems built in code for the unit and verification tests (no deck file involved).
#include <cmath>
#include <string>

#include "peridot/deck/model_schema.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/deck/solver_schema.hpp"

namespace peridot::testing {

struct BlockSetup {
  int dimension = 3;
  PlaneKind plane = PlaneKind::none;
  std::string model = "lps";  ///< a registered model name
  InfluenceKind influence = InfluenceKind::constant;
  int cells[3] = {10, 10, 10};  ///< lattice points along x, y, z (z ignored in 2D, y and z in 1D)
  double spacing = 1e-3;        ///< m
  double horizon_factor = 3.015;
  double bulk_modulus = 160e9, shear_modulus = 79.3e9;  ///< LPS; PMB uses K and its implied ν
  double density = 7800;
  double jitter = 0;
  bool partial_volume = false;
  /// The model's own keys (SI); box_problem adds the schema's default of every key not given here.
  Parameters parameters;
};

/// `given` and the default of every other key of the model (as the deck parser does).
inline Parameters with_defaults(const std::string& model, const Parameters& given) {
  const ModelInfo* info = find_model(model);
  PERIDOT_REQUIRE(info, "unknown model " + model);
  return complete_parameters(info->keys, given);
}

/// A solver section of this type with every default filled in (add end_time or num_steps for explicit).
inline SolverSpec solver_spec(const std::string& type = "explicit") {
  const SolverInfo* info = find_solver(type);
  PERIDOT_REQUIRE(info, "unknown solver type " + type);
  SolverSpec spec;
  spec.type = type;
  spec.parameters = complete_parameters(info->keys, {});
  return spec;
}

/// Distance from point i to the nearest face of box_problem's box [0, n·Δx]^dim.
inline double depth(const Discretization& disc, const BlockSetup& s, std::size_t i) {
  double d = 1e300;
  for (int k = 0; k < disc.dimension; ++k) {
    const double x = disc.x(i, k);
    d = std::min({d, x, s.cells[k] * s.spacing - x});
  }
  return d;
}

/// A box of lattice points [0, n·Δx] with one material, no loads, a handful of steps.
inline Problem box_problem(const BlockSetup& s) {
  Problem p;
  p.deck_path = "<test>";
  p.dimension = s.dimension;
  p.plane = s.dimension == 2 ? (s.plane == PlaneKind::none ? PlaneKind::stress : s.plane) : PlaneKind::none;
  p.thickness = s.dimension == 2 ? s.spacing : 1;
  p.area = s.dimension == 1 ? s.spacing * s.spacing : 1;  // a point's volume is then Δx³ in every dimension
  p.spacing = s.spacing;
  p.jitter = s.jitter;
  p.partial_volume = s.partial_volume ? PartialVolumeKind::extended : PartialVolumeKind::none;

  MaterialSpec m;
  m.name = "solid";
  m.model = s.model;
  m.density = s.density;
  m.influence = s.influence;
  // A model calibrated for one influence function gets it, as the deck parser gives it.
  if (const ModelInfo* info = find_model(s.model); info && info->influence == "inverse_distance")
    m.influence = InfluenceKind::inverse_distance;
  double K = s.bulk_modulus, G = s.shear_modulus;
  if (s.model == "pmb") {
    // Bond-based: ν = 1/4 (3D, plane strain) or 1/3 (plane stress); G follows from K and ν.
    const double nu = p.plane == PlaneKind::stress ? 1.0 / 3.0 : 0.25;
    G = 3 * K * (1 - 2 * nu) / (2 * (1 + nu));
  }
  m.elastic = {K, G, 9 * K * G / (3 * K + G), (3 * K - 2 * G) / (2 * (3 * K + G))};
  m.parameters = with_defaults(s.model, s.parameters);
  p.materials.push_back(m);

  BodySpec b;
  b.name = "block";
  b.material = "solid";
  Shape box;
  box.kind = Shape::Kind::box;
  box.lo = {0, 0, 0};
  box.hi = {s.cells[0] * s.spacing, s.dimension >= 2 ? s.cells[1] * s.spacing : 0.0,
            s.dimension == 3 ? s.cells[2] * s.spacing : 0.0};
  b.shape = box;
  b.horizon = s.horizon_factor * s.spacing;
  p.bodies.push_back(b);

  p.solver = solver_spec();
  p.solver.parameters.set_integer("num_steps", 10);
  p.output.exodus_every = 0;
  p.output.history_every = 0;
  p.output.progress = false;
  return p;
}

inline Shape box_shape(Vec3 lo, Vec3 hi) {
  Shape s;
  s.kind = Shape::Kind::box;
  s.lo = lo;
  s.hi = hi;
  return s;
}

}  // namespace peridot::testing
