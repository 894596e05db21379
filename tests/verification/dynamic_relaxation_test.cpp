// Adaptive dynamic relaxation (solvers/dynamic_relaxation.hpp): a 3D LPS bar relaxes to the classical
// uniaxial solution; the stored energy equals the work of the supports; past the iteration limit the run
// stops naming the residual reached; the deck refuses what a static solution cannot have.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "peridot/deck/deck.hpp"
#include "peridot/solvers/dynamic_relaxation.hpp"
#include "peridot/solvers/simulation.hpp"
#include "support/problems.hpp"

namespace peridot {
namespace {

using testing::BlockSetup;

constexpr double E = 200e9, nu = 0.3, strain = 1e-3;

/// A bar along x, centred on the origin (n_x × n × n lattice points, n odd so that the planes y = 0 and
/// z = 0 hold points), gripped over a horizon at each end where u_x = ε x (the classical solution there, so
/// the grip's extent does not matter), free laterally but for u_y = 0 on y = 0 and u_z = 0 on z = 0
/// (symmetry planes that take out the rigid motions), relaxed in `load_steps` steps.
Problem bar_problem(int nx, int n, int load_steps) {
  BlockSetup s;
  s.model = ModelKind::lps;
  s.bulk_modulus = E / (3 * (1 - 2 * nu));
  s.shear_modulus = E / (2 * (1 + nu));
  s.spacing = 1.5e-3;
  s.cells[0] = nx;
  s.cells[1] = s.cells[2] = n;
  // δ = 3.015Δx with partial volumes: the lattice quadrature is within about 1 % of isotropic
  // (tests/verification/lps_patch_test.cpp).
  s.partial_volume = true;
  Problem p = testing::box_problem(s);
  const double L = nx * s.spacing, H = n * s.spacing, grip = 3 * s.spacing;
  p.bodies[0].shape->lo = {-L / 2, -H / 2, -H / 2};
  p.bodies[0].shape->hi = {L / 2, H / 2, H / 2};
  p.lattice_origin = {-L / 2, -H / 2, -H / 2};  // points at (i + ½)Δx from it: on y = 0 and z = 0 for odd n
  const double tiny = 1e-3 * s.spacing;
  p.node_sets = {{"left", {}, testing::box_shape({-1, -1, -1}, {-L / 2 + grip, 1, 1}), {}, ""},
                 {"right", {}, testing::box_shape({L / 2 - grip, -1, -1}, {1, 1, 1}), {}, ""},
                 {"y0", {}, testing::box_shape({-1, -tiny, -1}, {1, tiny, 1}), {}, ""},
                 {"z0", {}, testing::box_shape({-1, -1, -tiny}, {1, 1, tiny}), {}, ""}};
  const Expression linear{std::to_string(strain) + " * x", {}, false};
  using Kind = BoundaryConditionSpec::Kind;
  p.boundary_conditions = {{{}, Kind::displacement, "left", 0, linear},
                           {{}, Kind::displacement, "right", 0, linear},
                           {{}, Kind::displacement, "y0", 1, Expression{"0", {}, false}},
                           {{}, Kind::displacement, "z0", 2, Expression{"0", {}, false}}};
  p.solver = SolverSpec{};
  p.solver.kind = SolverKind::relaxation;
  p.solver.load_steps = load_steps;
  p.solver.tolerance = 1e-9;
  return p;
}

/// Least-squares slope of u_component against x_along over the points `select` accepts.
template <class Select>
double slope(const Simulation& sim, int along, int component, Select&& select) {
  const Discretization& disc = sim.discretization();
  double sx = 0, sy = 0, sxx = 0, sxy = 0, count = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    if (!select(disc.x.get(i))) continue;
    const double x = disc.x(i, along), y = sim.state().u(i, component);
    sx += x, sy += y, sxx += x * x, sxy += x * y, count += 1;
  }
  return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

TEST(DynamicRelaxation, BarRelaxesToTheUniaxialSolution) {
  const int nx = 40, n = 15;
  Simulation sim(bar_problem(nx, n, 1));
  sim.initialize();
  sim.step();
  const auto& relaxation = dynamic_cast<const DynamicRelaxation&>(sim.integrator());
  EXPECT_LE(relaxation.residual(), 1e-9);
  const double dx = 1.5e-3, L = nx * dx, H = n * dx, horizon = 3.015 * dx;
  // Away from the grips (the middle half) and, for the contraction, more than a horizon inside the
  // lateral surfaces, whose incomplete families make a boundary layer.
  auto middle = [&](Vec3 x) { return std::abs(x.x) < L / 4; };
  auto core = [&](Vec3 x) {
    return middle(x) && std::abs(x.z) < 1e-6 && std::abs(x.y) < H / 2 - horizon;
  };
  const double axial = slope(sim, 0, 0, middle);
  const double lateral = slope(sim, 1, 1, core);
  EXPECT_NEAR(axial, strain, 0.01 * strain);
  EXPECT_NEAR(-lateral / strain, nu, 0.01 * nu) << "lateral strain " << lateral;
}

TEST(DynamicRelaxation, StoredEnergyEqualsTheWorkOfTheSupports) {
  // Linear elastic and one load step: the trapezoidal work of the supports, ½ R·Δu, is exact.
  Simulation sim(bar_problem(16, 7, 1));
  sim.initialize();
  sim.step();
  const Totals t = sim.totals();
  EXPECT_GT(t.strain_energy, 0);
  EXPECT_NEAR(t.external_work, t.strain_energy, 1e-6 * t.strain_energy);
  // Two load steps give the same equilibrium as one (linear, no history), to the tolerance.
  Simulation twice(bar_problem(16, 7, 2));
  twice.initialize();
  twice.step();
  twice.step();
  double largest = 0, difference = 0;
  for (std::size_t i = 0; i < sim.discretization().num_points(); ++i)
    for (int d = 0; d < 3; ++d) {
      largest = std::max(largest, std::abs(sim.state().u(i, d)));
      difference = std::max(difference, std::abs(sim.state().u(i, d) - twice.state().u(i, d)));
    }
  EXPECT_LT(difference, 1e-6 * largest);
}

TEST(DynamicRelaxation, IterationLimitNamesTheResidualReached) {
  Problem p = bar_problem(16, 7, 1);
  p.solver.max_iterations = 5;
  Simulation sim(p);
  sim.initialize();
  try {
    sim.step();
    FAIL() << "no error past the iteration limit";
  } catch (const NumericalError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("did not converge in load step 1"), std::string::npos) << message;
    EXPECT_NE(message.find("relative force residual"), std::string::npos) << message;
    EXPECT_NE(message.find("after 5 iterations"), std::string::npos) << message;
  }
}

TEST(DynamicRelaxation, DeckRefusesVelocitiesAndMovingWalls) {
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
solver: {type: relaxation, load_steps: 4, num_steps: 3}
)";
  try {
    parse_deck(deck, "deck.yaml", ".");
    FAIL() << "deck accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("deck.yaml:8:5: error: initial_conditions: an initial velocity has no meaning"),
              std::string::npos) << message;
    EXPECT_NE(message.find("deck.yaml:10:5: error: boundary_conditions: a prescribed velocity"), std::string::npos)
        << message;
    EXPECT_NE(message.find("unknown key 'num_steps'"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace peridot
