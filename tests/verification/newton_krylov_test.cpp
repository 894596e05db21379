// The implicit solver (solvers/newton_krylov.hpp): the static problems of dynamic relaxation give the same
// equilibria (an LPS bar against the uniaxial solution, an elastic-plastic notched plate whose crack grows
// between equilibria); Newton converges quadratically; both Jacobians reach the same answer; the same bits on
// one and two threads; failures name the load step, the iteration, the residual and the likely cause; the deck
// refuses what a static solution cannot have.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <string>

#include "peridot/deck/deck.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/solvers/dynamic_relaxation.hpp"
#include "peridot/solvers/newton_krylov.hpp"
#include "peridot/solvers/simulation.hpp"
#include "support/static_problems.hpp"

namespace peridot {
namespace {

using namespace testing;

const NewtonKrylov& newton(const Simulation& sim) { return dynamic_cast<const NewtonKrylov&>(sim.integrator()); }

TEST(NewtonKrylov, BarReachesTheEquilibriumOfDynamicRelaxation) {
  const int nx = 40, n = 11;
  const auto implicit = solve(bar_problem(nx, n, 1, "lps", 1, "implicit"));
  const auto relaxed = solve(bar_problem(nx, n, 1));
  EXPECT_LE(newton(*implicit).residual(), 1e-9);
  const auto [axial, lateral] = bar_strains(*implicit, nx, n);
  EXPECT_NEAR(axial, strain, 0.015 * strain);
  EXPECT_NEAR(-lateral / axial, nu, 0.01 * nu);
  // Both solvers stop at a relative force residual of 1e-9; the displacements then agree to about the
  // residual times the condition of the bar's stiffness.
  const double difference = relative_difference(*implicit, *relaxed);
  EXPECT_LT(difference, 1e-6);
  std::cout << "implicit: " << newton(*implicit).iterations() << " Newton iterations, "
            << newton(*implicit).linear_iterations() << " Krylov iterations; relaxation: "
            << dynamic_cast<const DynamicRelaxation&>(relaxed->integrator()).iterations()
            << " iterations; relative difference " << difference << "\n";
}

/// The bar stretched by 2 % in one load step (lateral: the grips' lateral displacement factor), solved to a
/// relative residual of 1e-12.
Problem stretched_bar(const std::string& model, const std::string& lateral) {
  Problem p = bar_problem(24, 7, 1, model, 1, "implicit");
  for (BoundaryConditionSpec& bc : p.boundary_conditions)
    bc.value.text.replace(0, bc.value.text.find(' '), bc.component == 0 ? "0.02" : lateral);
  p.solver.parameters.set_number("tolerance", 1e-12);
  return p;
}

/// The Newton residuals reach 1e-12 within 6 iterations, and once below 1e-2 each is at most 100 times the
/// square of the one before (at least once).
void expect_quadratic(const std::vector<double>& r) {
  ASSERT_GE(r.size(), 3u);
  std::cout << "relative residuals:";
  for (double x : r) std::cout << " " << x;
  std::cout << "\n";
  EXPECT_LE(r.back(), 1e-12);
  EXPECT_LE(r.size(), 7u);
  int quadratic = 0;
  for (std::size_t k = 1; k + 1 < r.size(); ++k)
    if (r[k] < 1e-2 && r[k + 1] > 1e-13) {
      EXPECT_LT(r[k + 1], 100 * r[k] * r[k]) << "iteration " << k + 1;
      ++quadratic;
    }
  EXPECT_GE(quadratic, 1);
}

TEST(NewtonKrylov, ConvergesQuadratically) {
  // Stretched by 2 % in one load step, the bar's bonds rotate and stretch enough that the response is
  // clearly nonlinear; once the iterate is close, each residual is at most a constant times the square of the
  // one before (the constant measured here is about 3; the finite-difference Jacobian and the linear
  // tolerance 1e-6 bound the gain per iteration at about 1e-6 too).
  Problem p = stretched_bar("lps", "-0.006");
  p.solver.parameters.set_number("linear_tolerance", 1e-10);
  expect_quadratic(newton(*solve(p)).newton_residuals());
}

TEST(NewtonKrylov, BondTangentJacobianReachesTheSameEquilibrium) {
  Problem p = bar_problem(16, 7, 1, "lps", 1, "implicit");
  const auto matrix_free = solve(p);
  p.solver.parameters.set_text("jacobian", "bond_tangent");
  p.solver.parameters.set_integer("max_iterations", 200);
  const auto bond_tangent = solve(p);
  EXPECT_LT(relative_difference(*matrix_free, *bond_tangent), 1e-6);
  // The modified Newton method converges linearly: more outer iterations, each cheaper.
  EXPECT_GT(newton(*bond_tangent).iterations(), newton(*matrix_free).iterations());
}

// For pmb the assembled bond tangent is the exact Jacobian (axial springs c0 ω G V/ξ and the geometric stiffness
// of forces that turn with their bonds): used as the Jacobian (jacobian: bond_tangent), Newton then converges
// quadratically on a bar stretched by 2 % (measured: 1, 4.0e-2, 6.9e-5, 2.3e-10, 2.2e-15), as with the
// matrix-free Jacobian; without the geometric part it converged linearly (a factor of about 0.03 per iteration,
// eight iterations to 4e-14).
TEST(NewtonKrylov, BondTangentIsPmbsExactJacobian) {
  Problem p = stretched_bar("pmb", "-0.005");
  p.solver.parameters.set_text("jacobian", "bond_tangent");
  p.solver.parameters.set_number("linear_tolerance", 1e-12);
  expect_quadratic(newton(*solve(p)).newton_residuals());
}

// lps's exact tangent (jacobian: exact, solvers/family_tangent.hpp: the bond blocks and the dilatation's coupling
// of every pair of a family) is the Jacobian: Newton converges quadratically with the assembled matrix alone
// (measured 1, 3.8e-2, 6.4e-5, 2.1e-10, 2.0e-15 here, as the matrix-free Jacobian), where the pmb-like bond
// tangent converges linearly.
TEST(NewtonKrylov, ExactTangentIsLpssJacobian) {
  Problem p = stretched_bar("lps", "-0.006");
  p.solver.parameters.set_text("jacobian", "exact");
  p.solver.parameters.set_number("linear_tolerance", 1e-12);
  expect_quadratic(newton(*solve(p)).newton_residuals());
}

TEST(NewtonKrylov, AssembledJacobiansReachTheEquilibriumOfTheMatrixFreeOne) {
  Problem p = bar_problem(12, 5, 1, "lps", 1, "implicit");
  const auto matrix_free = solve(p);
  for (const char* jacobian : {"exact", "finite_difference"}) {
    p.solver.parameters.set_text("jacobian", jacobian);
    const auto assembled = solve(p);
    EXPECT_LE(newton(*assembled).residual(), 1e-9) << jacobian;
    EXPECT_LT(relative_difference(*matrix_free, *assembled), 1e-6) << jacobian;
    EXPECT_LE(newton(*assembled).iterations(), newton(*matrix_free).iterations() + 1) << jacobian;
  }
}

TEST(NewtonKrylov, DeckRefusesTheExactTangentOfAModelWithoutOne) {
  const std::string deck = R"(discretization: {dimension: 2, plane: stress, spacing: 1 mm, horizon_factor: 3.015}
materials:
  alloy: {model: lps_plastic, yield_stress: 60 MPa, density: 2440, youngs_modulus: 72 GPa, poisson_ratio: 0.22}
bodies:
  plate: {material: alloy, shape: {box: {min: [0, 0], max: [0.015, 0.015]}}}
solver: {type: implicit, jacobian: exact}
)";
  std::string message = testing::deck_refusal(deck);
  EXPECT_NE(message.find("deck.yaml:6:36: error: solver.jacobian: jacobian: exact is the closed-form tangent of pmb "
                         "and lps, and material 'alloy' is lps_plastic; use finite_difference"),
            std::string::npos)
      << message;
}

/// The elastic-plastic notched plate of the relaxation tests (lps_plastic, bonds breaking between equilibria)
/// with this solver type.
Problem notched_plate(const std::string& type) {
  const std::string deck = R"(discretization: {dimension: 2, plane: stress, thickness: 1 mm, spacing: 1 mm, horizon_factor: 3.015}
materials:
  alloy: {model: lps_plastic, yield_stress: 60 MPa, hardening_modulus: 1 GPa, density: 2440, youngs_modulus: 72 GPa,
          poisson_ratio: 0.22, damage: {critical_stretch: 0.0015}}
bodies:
  plate: {material: alloy, shape: {box: {min: [0, 0], max: [0.015, 0.015]}}}
precracks:
  - segment: {from: [0, 0.0075], to: [0.005, 0.0075]}
node_sets:
  top: {shape: {box: {min: [-1, 0.0125], max: [1, 1]}}}
  bottom: {shape: {box: {min: [-1, -1], max: [1, 0.0025]}}}
no_fail: [top, bottom]
boundary_conditions:
  - {node_set: top, displacement: {x: "0", y: "6e-6"}}
  - {node_set: bottom, displacement: {x: "0", y: "-6e-6"}}
solver: {type: TYPE, load_steps: 3, tolerance: 1e-9}
output: {progress: false}
)";
  std::string text = deck;
  text.replace(text.find("TYPE"), 4, type);
  return parse_deck(text, "deck.yaml", ".");
}

TEST(NewtonKrylov, PlasticNotchedPlateBreaksTheBondsRelaxationBreaks) {
  // Plastic history committed once per load step, the trial return map inside every residual (and every
  // finite difference of the Jacobian), bonds breaking between equilibria until none does.
  const auto implicit = solve(notched_plate("implicit"));
  const auto relaxed = solve(notched_plate("relaxation"));
  const std::size_t broken = broken_bonds(*implicit);
  EXPECT_GT(broken, 100u);
  EXPECT_EQ(broken, broken_bonds(*relaxed));
  EXPECT_LT(relative_difference(*implicit, *relaxed), 1e-5);
  double plastic = 0, difference = 0;
  for (std::size_t i = 0; i < implicit->discretization().num_points(); ++i) {
    plastic = std::max(plastic, implicit->state().history.plastic_strain[i]);
    difference = std::max(difference, std::abs(implicit->state().history.plastic_strain[i] -
                                               relaxed->state().history.plastic_strain[i]));
  }
  EXPECT_GT(plastic, 0);
  EXPECT_LT(difference, 1e-5 * plastic);
  std::cout << broken << " broken bonds; largest plastic strain " << plastic << ", difference " << difference << "\n";
}

TEST(NewtonKrylov, SameBitsOnOneAndTwoThreads) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = solve(notched_plate("implicit"));
  omp_set_num_threads(2);
  const auto two = solve(notched_plate("implicit"));
  omp_set_num_threads(threads);
  const std::size_t values = 3 * one->discretization().num_points();
  EXPECT_EQ(std::memcmp(one->state().u.data(), two->state().u.data(), values * sizeof(double)), 0);
  EXPECT_EQ(one->bonds().broken, two->bonds().broken);
}

TEST(NewtonKrylov, IterationLimitNamesTheStepIterationAndResidual) {
  Problem p = bar_problem(16, 7, 1, "lps", 1, "implicit");
  p.solver.parameters.set_integer("max_iterations", 1);
  p.solver.parameters.set_number("tolerance", 1e-14);
  const std::string message = first_step_error(p);
  EXPECT_NE(message.find("Newton's method failed in load step 1 (time 1 s, load factor 1): no convergence in 1 "
                         "Newton iterations, relative force residual"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("use more load_steps"), std::string::npos) << message;
}

TEST(NewtonKrylov, LoadedPieceThatCameApartIsNamed) {
  // A bar cut in two and pulled at its free piece: the tangent is singular and no equilibrium exists; the
  // error names the loose piece, its load and where it is.
  const std::string message = first_step_error(pulled_bar(
      "1e6", "", "0.0301", "no_fail: [held]\nboundary_conditions:\n  - {node_set: held, displacement: {x: \"0\"}}", "",
      "max_iterations: 20", "implicit"));
  EXPECT_NE(message.find("Newton's method failed in load step 1"), std::string::npos) << message;
  EXPECT_NE(message.find("the body has come apart: 1 fragment without support carries a net load, the largest 1 N on "
                         "10 points (fragment of point 30 at (0.0305, 0, 0) m)"),
            std::string::npos)
      << message;
}

// The nonlocal volume constraint (bodies.<name>.volume_constraint): an affine displacement prescribed on a layer
// 2δ thick around an lps body is an equilibrium of every point of the body (each family and each neighbour's
// family full and symmetric), so the solution is that field inside, to the solver's tolerance, in 2D and 3D.
TEST(NewtonKrylov, VolumeConstraintHoldsAnAffineField) {
  for (const int dimension : {2, 3}) {
    const bool three = dimension == 3;
    const std::string deck =
        std::string("discretization: {dimension: ") + (three ? "3" : "2, plane: stress") +
        R"(, spacing: 1 mm, horizon_factor: 3.015}
materials:
  steel: {model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}
bodies:
  block: {material: steel, volume_constraint: 6.03 mm, shape: {box: {min: [0, 0, 0], max: [0.008, 0.006, )" +
        (three ? "0.004" : "0") + R"(]}}}
boundary_conditions:
  - {node_set: block_constraint, displacement: {x: "1e-3*x + 2e-4*y", y: "-3e-4*x + 5e-4*y")" +
        (three ? R"(, z: "1e-4*x - 2e-4*z")" : "") + R"(}}
solver: {type: implicit, load_steps: 1, tolerance: 1e-12}
output: {progress: false}
)";
    const auto sim = solve(parse_deck(deck, "deck.yaml", "."));
    const Discretization& disc = sim->discretization();
    std::size_t body = 0, layer = 0;
    double worst = 0, largest = 0;
    for (std::size_t i = 0; i < disc.num_points(); ++i) {
      const Vec3 x = disc.x.get(i), u = sim->state().u.get(i);
      const bool inside = x.x > 0 && x.x < 0.008 && x.y > 0 && x.y < 0.006 && (!three || (x.z > 0 && x.z < 0.004));
      ++(inside ? body : layer);
      if (!inside) continue;
      const Vec3 exact{1e-3 * x.x + 2e-4 * x.y, -3e-4 * x.x + 5e-4 * x.y, three ? 1e-4 * x.x - 2e-4 * x.z : 0.0};
      worst = std::max({worst, std::abs(u.x - exact.x), std::abs(u.y - exact.y), std::abs(u.z - exact.z)});
      largest = std::max({largest, std::abs(exact.x), std::abs(exact.y)});
    }
    EXPECT_EQ(body, three ? 192u : 48u);
    EXPECT_GT(layer, 4 * body) << "the layer, 6 spacings thick around the block";
    EXPECT_LT(worst, 1e-9 * largest) << dimension << "D: " << body << " points, " << layer << " in the layer";
    std::cout << dimension << "D: " << body << " points, " << layer << " in the layer, largest error " << worst / largest
              << " of max |u|\n";
  }
}

TEST(NewtonKrylov, DeckRefusesAVolumeConstraintWithoutAShapeOrUnderATakenName) {
  const std::string deck = R"(discretization: {dimension: 2, plane: stress, spacing: 1 mm, horizon_factor: 3.015}
materials:
  steel: {model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}
bodies:
  block: {material: steel, volume_constraint: 6 mm, shape: {box: {min: [0, 0], max: [0.008, 0.006]}}}
  read: {material: steel, volume_constraint: 6 mm, points_file: points.txt}
node_sets:
  block_constraint: {shape: {box: {min: [-1, -1], max: [0.001, 0.001]}}}
solver: {type: implicit}
)";
  std::string message = testing::deck_refusal(deck);
  EXPECT_NE(message.find("deck.yaml:6:27: error: bodies.read.volume_constraint: the layer is made on the lattice "
                         "around a shape, and this body has none"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("deck.yaml:8:3: error: node_sets.block_constraint: is the name of the volume-constraint layer "
                         "of body 'block'; rename this node set"),
            std::string::npos)
      << message;
  // Thinner than the spacing: no site in the layer, said where the body is.
  const Problem thin = parse_deck(R"(discretization: {dimension: 2, plane: stress, spacing: 1 mm, horizon_factor: 3.015}
materials:
  steel: {model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}
bodies:
  block: {material: steel, volume_constraint: 0.5 mm, shape: {box: {min: [0, 0], max: [0.008, 0.006]}}}
solver: {type: implicit}
)",
                                  "deck.yaml", ".");
  message.clear();
  try {
    discretize(thin);
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("deck.yaml:5:3: error: bodies.block.volume_constraint: the layer holds no lattice site"),
            std::string::npos)
      << message;
}

TEST(NewtonKrylov, FreeRigidMotionIsNamed) {
  // A plate held and pulled along x only: nothing holds it along y, its tangent is singular. Stopped after one
  // Newton iteration, the error names the motion the supports leave free (relaxation's too).
  for (const char* type : {"implicit", "relaxation"}) {
    const std::string deck = std::string(R"(discretization: {dimension: 2, plane: stress, spacing: 1 mm, horizon_factor: 3.015}
materials:
  steel: {model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}
bodies:
  plate: {material: steel, shape: {box: {min: [0, 0], max: [0.012, 0.006]}}}
node_sets:
  left: {shape: {box: {min: [-1, -1], max: [0.003, 1]}}}
  right: {shape: {box: {min: [0.009, -1], max: [1, 1]}}}
boundary_conditions:
  - {node_set: left, displacement: {x: "0"}}
  - {node_set: right, displacement: {x: "1e-5"}}
solver: {type: )") + type + R"(, load_steps: 1, tolerance: 1e-14, max_iterations: 1}
output: {progress: false}
)";
    const std::string message = first_step_error(parse_deck(deck, "deck.yaml", "."));
    EXPECT_NE(message.find("the supports do not hold every rigid motion, so the tangent is singular: 72 points "
                           "(fragment of point 0 at (0.0005, 0.0005, 0) m) are free to translate along y; prescribe "
                           "displacements that hold them"),
              std::string::npos)
        << type << ": " << message;
  }
}

TEST(NewtonKrylov, DeckRefusesVelocitiesAndMovingWalls) {
  const std::string message = testing::static_deck_refusal("solver: {type: implicit, load_steps: 4, preconditioner: amg}");
  EXPECT_NE(message.find("deck.yaml:9:5: error: initial_conditions: an initial velocity has no meaning for solver "
                         "type 'implicit'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("deck.yaml:11:5: error: boundary_conditions: a prescribed velocity"), std::string::npos)
      << message;
  EXPECT_NE(message.find("preconditioner"), std::string::npos) << message;
}

}  // namespace
}  // namespace peridot
