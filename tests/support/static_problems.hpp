#pragma once
// Static problems the quasi-static solvers' tests share (dynamic relaxation, Newton–Krylov): a 3D bar in
// uniaxial stress held by its grips, a 1D bar pulled at its end, and what the tests measure of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "peridot/deck/deck.hpp"
#include "peridot/solvers/simulation.hpp"
#include "support/displacement_fit.hpp"
#include "support/problems.hpp"

namespace peridot::testing {

constexpr double E = 200e9, nu = 0.3, strain = 1e-3;

/// What parse_deck says of a deck it refuses (its InputError's text); empty when it accepts the deck.
inline std::string deck_refusal(const std::string& deck) {
  try {
    parse_deck(deck, "deck.yaml", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

/// The errors of a deck with an initial velocity (line 9) and a prescribed velocity (line 11), which no static
/// solver accepts, and the given solver line (line 12); throws if the deck parses.
inline std::string static_deck_refusal(const std::string& solver_line) {
  const std::string deck = R"(discretization: {dimension: 2, plane: stress, spacing: 1 mm, horizon_factor: 3.015}
materials:
  steel: {model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}
bodies:
  plate: {material: steel, shape: {box: {min: [0, 0], max: [0.02, 0.01]}}}
node_sets:
  left: {shape: {box: {min: [-1, -1], max: [0.002, 1]}}}
initial_conditions:
  - {velocity: {x: "1"}}
boundary_conditions:
  - {node_set: left, velocity: {x: "0"}}
)" + solver_line + "\n";
  std::string message = deck_refusal(deck);
  if (message.empty()) throw std::runtime_error("deck accepted:\n" + deck);
  return message;
}

/// A bar along x, centred on the origin (n_x × n × n lattice points), gripped over a horizon at each end,
/// where the classical solution of uniaxial stress is imposed (u_x = ε x, u_y = −ν ε y, u_z = −ν ε z, so
/// that the grips' extent does not matter), free elsewhere, relaxed in `load_steps` steps.
inline Problem bar_problem(int nx, int n, int load_steps, std::string model = "lps", double shear_factor = 1,
                           const std::string& solver = "relaxation") {
  BlockSetup s;
  s.model = model;
  s.bulk_modulus = E / (3 * (1 - 2 * nu));
  s.shear_modulus = shear_factor * E / (2 * (1 + nu));
  s.spacing = 1.5e-3;
  s.cells[0] = nx;
  s.cells[1] = s.cells[2] = n;
  // δ = 3.015Δx with partial volumes: the lattice quadrature is within about 1 % of isotropic
  // (tests/verification/lps_patch_test.cpp).
  s.partial_volume = true;
  Problem p = box_problem(s);
  const double L = nx * s.spacing, H = n * s.spacing, grip = 3 * s.spacing;
  p.bodies[0].shape->lo = {-L / 2, -H / 2, -H / 2};
  p.bodies[0].shape->hi = {L / 2, H / 2, H / 2};
  p.lattice_origin = {-L / 2, -H / 2, -H / 2};  // points at (i + ½)Δx from it
  p.node_sets = {{"left", {}, box_shape({-1, -1, -1}, {-L / 2 + grip, 1, 1}), {}, "", ""},
                 {"right", {}, box_shape({L / 2 - grip, -1, -1}, {1, 1, 1}), {}, "", ""}};
  const std::string e = std::to_string(strain), contraction = std::to_string(-nu * strain);
  using Kind = BoundaryConditionSpec::Kind;
  for (const char* grip_set : {"left", "right"}) {
    p.boundary_conditions.push_back({{}, Kind::displacement, grip_set, 0, Expression{e + " * x", {}, false}});
    p.boundary_conditions.push_back({{}, Kind::displacement, grip_set, 1, Expression{contraction + " * y", {}, false}});
    p.boundary_conditions.push_back({{}, Kind::displacement, grip_set, 2, Expression{contraction + " * z", {}, false}});
  }
  p.solver = solver_spec(solver);
  p.solver.parameters.set_integer("load_steps", load_steps);
  p.solver.parameters.set_number("tolerance", 1e-9);
  return p;
}

/// The problem set up and run to its last load step.
inline std::unique_ptr<Simulation> solve(const Problem& p) {
  auto sim = std::make_unique<Simulation>(p);
  sim->initialize();
  while (sim->state().step < sim->total_steps()) sim->step();
  return sim;
}

/// Largest |u_a − u_b| over the largest |u_a|.
inline double relative_difference(const Simulation& a, const Simulation& b) {
  double largest = 0, difference = 0;
  for (std::size_t i = 0; i < a.discretization().num_points(); ++i)
    for (int d = 0; d < 3; ++d) {
      largest = std::max(largest, std::abs(a.state().u(i, d)));
      difference = std::max(difference, std::abs(a.state().u(i, d) - b.state().u(i, d)));
    }
  return difference / largest;
}

/// Strains of a bar_problem(nx, n, …) bar: the axial one over its middle half (away from the grips) and the
/// lateral one over the points of that half more than a horizon inside the lateral surfaces, whose
/// incomplete families make a boundary layer.
struct BarStrains {
  double axial, lateral;
};
inline BarStrains bar_strains(const Simulation& sim, int nx, int n) {
  const double dx = 1.5e-3, L = nx * dx, H = n * dx, horizon = 3.015 * dx;
  auto middle = [&](Vec3 x) { return std::abs(x.x) < L / 4; };
  auto core = [&](Vec3 x) { return middle(x) && std::abs(x.y) < H / 2 - horizon && std::abs(x.z) < H / 2 - horizon; };
  return {displacement_slope(sim, 0, 0, middle), displacement_slope(sim, 1, 1, core)};
}

/// The NumericalError the first load step throws; a test failure, and "", when it finds an equilibrium.
inline std::string first_step_error(const Problem& p) {
  Simulation sim(p);
  sim.initialize();
  try {
    sim.step();
  } catch (const NumericalError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the first load step found an equilibrium";
  return {};
}

/// A 40-point steel bar (1D pmb, Δx = 1 mm, A = 1 mm²) pulled by σ (Pa) on its last point; `damage` is the
/// material's own damage section (or empty), then come the deck's precracks, supports and further loads, and the
/// solver's keys (of solver type `solver_type`).
inline Problem pulled_bar(const std::string& sigma, const std::string& damage, const std::string& precrack_at, const std::string& supports,
                   const std::string& other_loads, const std::string& solver,
                   const std::string& solver_type = "relaxation") {
  return parse_deck(fmt::format(R"yaml(
discretization: {{dimension: 1, area: 1 mm^2, spacing: 1 mm, horizon_factor: 3}}
materials:
  steel: {{model: pmb, density: 7800, youngs_modulus: 200 GPa{damage}}}
bodies:
  bar: {{material: steel, shape: {{box: {{min: [0], max: [0.04]}}}}}}
precracks:
  - at: {precrack_at}
node_sets:
  held: {{shape: {{box: {{min: [-1], max: [0.001]}}}}}}
  pulled: {{shape: {{box: {{min: [0.039], max: [1]}}}}}}
{supports}
tractions:
  - {{node_set: pulled, x: "{sigma}"}}
{other_loads}
solver: {{type: {solver_type}, {solver}}}
output: {{progress: false}}
)yaml",
                                fmt::arg("damage", damage), fmt::arg("precrack_at", precrack_at),
                                fmt::arg("supports", supports), fmt::arg("other_loads", other_loads),
                                fmt::arg("sigma", sigma), fmt::arg("solver", solver),
                                fmt::arg("solver_type", solver_type)),
                    "deck.yaml", ".");
}

/// Broken bonds (directed) of a run.
inline std::size_t broken_bonds(const Simulation& sim) {
  const auto& broken = sim.bonds().broken;
  return static_cast<std::size_t>(std::count(broken.begin(), broken.end(), std::uint8_t{1}));
}

}  // namespace peridot::testing
