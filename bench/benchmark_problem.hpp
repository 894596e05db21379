// The benchmark block shared by the programs in bench/: a simple-cubic block of points, horizon 3.015
// spacings (122 bonds per interior point), E = 200 GPa, ν = 1/4, ρ = 7800, a smooth initial velocity field.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

#include "peridot/deck/model_schema.hpp"
#include "peridot/deck/solver_schema.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot::bench {

struct Options {
  std::string model = "pmb";
  int n[3] = {58, 58, 60};
  double spacing = 1e-3;
  int steps = 200;
  double dt = 0;  // 0: 0.8 × stable
  double v0 = 1e-3;
  double critical_stretch = 0;  // 0: no damage
  double yield_stress = 250e6;  // lps_plastic, correspondence j2
  std::string law = "j2";       // correspondence
  int dimension = 3;            // 2: plane stress, thickness Δx, the first two of --n
  std::string influence;        // empty: as LAMMPS (constant for pmb, 1/|ξ| otherwise)
  int threads = 1;
  bool lammps_failure_order = false;
  bool contact = false;
  std::string dump;
};

// The problem of bench/lammps/README.md: points at i·Δx (LAMMPS `lattice sc`), E = 200 GPa, ν = 1/4,
// ρ = 7800, v = v0 (sin(w_x x) + ½ sin(w_y y), sin(w_y y) + ½ sin(w_z z), sin(w_z z) + ½ sin(w_x x)),
// w_d = 2π/(n_d Δx).
inline Problem benchmark_problem(const Options& o) {
  Problem p;
  p.deck_path = "<bench>";
  p.dimension = o.dimension;
  if (o.dimension == 2) p.plane = PlaneKind::stress, p.thickness = o.spacing;
  p.spacing = o.spacing;
  p.lattice_origin = {-0.5 * o.spacing, -0.5 * o.spacing, -0.5 * o.spacing};
  p.partial_volume = PartialVolumeKind::horizon;  // LAMMPS PERI scales V_j this way
  const double E = 200e9, nu = 0.25, K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  MaterialSpec m;
  m.name = "steel";
  m.model = find_model(o.model) ? o.model : "pmb";
  Parameters& q = m.parameters;  // the keys of the chosen model (each model reads its own)
  if (m.model == "correspondence") {
    const bool j2 = o.law != "hypoelastic";
    q.set_text("constitutive_law", j2 ? "j2_viscoplastic" : "hypoelastic");
    q.set_number("hourglass_coefficient", 0.05);
    q.set_number("hourglass_viscosity", 0);
    q.set_number("bulk_viscosity_linear", 0);
    q.set_number("bulk_viscosity_quadratic", 0);
    if (j2) {
      q.set_number("yield_stress", o.yield_stress);
      q.set_number("hardening_exponent", 13.5);
      q.set_number("reference_plastic_strain", 0.001);
      q.set_number("rate_exponent", 44);
      q.set_number("reference_strain_rate", 1000);
    }
  } else {
    q.set_number("yield_stress", o.yield_stress);
    q.set_number("hardening_modulus", 1e9);
    q.set_number("relaxing_fraction", 0.5);
    q.set_number("relaxation_time", 1e-5);
  }
  // LAMMPS peri/lps weighs bonds by 1/|ξ| (the scale of ω cancels in LPS, so δ/|ξ| is the same model).
  m.influence = m.model == "pmb" ? InfluenceKind::constant : InfluenceKind::inverse_distance;
  if (o.influence == "constant") m.influence = InfluenceKind::constant;
  else if (o.influence == "inverse_distance") m.influence = InfluenceKind::inverse_distance;
  else if (o.influence == "gaussian") m.influence = InfluenceKind::gaussian;
  else if (!o.influence.empty()) {
    std::fprintf(stderr, "unknown influence %s\n", o.influence.c_str());
    std::exit(2);
  }
  m.density = 7800;
  m.elastic = {K, G, E, nu};
  if (o.critical_stretch > 0) {
    m.damage.enabled = true;
    m.damage.critical_stretch = o.critical_stretch;
  }
  p.materials = {m};
  if (o.contact) p.contact = ContactSpec{};
  BodySpec b;
  b.name = "block";
  b.material = "steel";
  Shape box;
  box.kind = Shape::Kind::box;
  box.lo = {-0.5 * o.spacing, -0.5 * o.spacing, -0.5 * o.spacing};
  box.hi = {(o.n[0] - 0.5) * o.spacing, (o.n[1] - 0.5) * o.spacing, (o.n[2] - 0.5) * o.spacing};
  if (o.dimension == 2) box.lo[2] = box.hi[2] = 0;
  b.shape = box;
  b.horizon = 3.015 * o.spacing;
  p.bodies = {b};
  const double w[3] = {2 * std::numbers::pi / (o.n[0] * o.spacing), 2 * std::numbers::pi / (o.n[1] * o.spacing),
                       2 * std::numbers::pi / (o.n[2] * o.spacing)};
  auto term = [&](const char* var, int d) { return "sin(" + std::to_string(w[d]) + "*" + var + ")"; };
  InitialConditionSpec ic;
  const std::string v0 = std::to_string(o.v0);
  ic.component[0] = Expression{v0 + "*(" + term("x", 0) + "+0.5*" + term("y", 1) + ")", {}, false};
  ic.component[1] = Expression{v0 + "*(" + term("y", 1) + "+0.5*" + term("z", 2) + ")", {}, false};
  ic.component[2] = Expression{v0 + "*(" + term("z", 2) + "+0.5*" + term("x", 0) + ")", {}, false};
  if (o.dimension == 2) ic.component[2] = Expression{"0", {}, false};
  p.initial_conditions = {ic};
  p.solver.parameters = complete_parameters(find_solver("explicit")->keys, {});  // the defaults a deck gets
  p.solver.parameters.set_integer("num_steps", o.steps);
  if (o.dt > 0) p.solver.parameters.set_number("time_step", o.dt);
  if (o.lammps_failure_order) p.solver.parameters.set_text("bond_failure", "after_force");
  p.output.progress = false;
  return p;
}

}  // namespace peridot::bench
