// Rigid walls with contact: symmetry (correspondence/mirror_bonds.hpp): the near-wall correspondence points
// are bonded to the mirror images of their neighbours while the body presses on the wall.
//  - A body pressed onto the plane moves exactly as the upper half of the whole body made of it and its
//    mirror image, thrown at itself (the symmetric problem the plane stands for), and the wall's force is
//    the force the lower half exerts on the upper one.
//  - Under a prescribed homogeneous compression F is exact at every point and the points next to the plane
//    are loaded as interior points are (no net force away from the lateral faces), where a penalty wall
//    leaves them a surface force.
//  - A cube thrown at the wall bounces, the mirror bonds are released as it leaves, the momentum it gains is
//    the impulse of the wall force and its energy balances.
//  - Decks the mirror bonds cannot model are refused with the wall's position.
// Reference numbers measured with this code are in the comments next to each tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/deck/deck.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {
namespace {

// Hypoelastic aluminium with hourglass springs and dashpots, so that every term of the gather crosses the
// plane.
const char* material = R"(materials:
  al: {model: correspondence, density: 2700, youngs_modulus: 68.9 GPa, poisson_ratio: 0.333,
       constitutive_law: hypoelastic, hourglass_coefficient: 0.02, hourglass_viscosity: 0.05}
)";

Problem deck(const std::string& box, const std::string& rest) {
  const std::string text = fmt::format(R"(discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
{}bodies:
  block: {{material: al, shape: {{box: {}}}}}
{}
)",
                                       material, box, rest);
  return parse_deck(text, "symmetry.yaml", ".");
}

using Key = std::tuple<long, long, long>;
Key lattice_key(Vec3 x) {
  return {std::lround(x.x * 1e4), std::lround(x.y * 1e4), std::lround(x.z * 1e4)};
}

TEST(SymmetryWall, HalfBodyOnThePlaneMovesAsTheWholeBodyThrownAtItsMirrorImage) {
  // Whole body: z in [−6, 6] mm, the halves thrown at each other at 20 m/s (and both sliding at 3 m/s along x,
  // which the frictionless plane must not resist). Half body: z in [0, 6] mm on the plane z = 0.
  const std::string solver = "solver: {num_steps: 40, time_step: 2e-8}";
  Simulation whole(deck("{min: [0, 0, -0.006], max: [0.008, 0.006, 0.006]}",
                        "initial_conditions:\n  - {velocity: {x: \"3\", y: \"0\", z: \"z > 0 ? -20 : 20\"}}\n" + solver));
  Simulation half(deck("{min: [0, 0, 0], max: [0.008, 0.006, 0.006]}",
                       "initial_conditions:\n  - {velocity: {x: \"3\", y: \"0\", z: \"-20\"}}\n"
                       "rigid_walls:\n  - {name: anvil, point: [0, 0, 0], normal: [0, 0, 1], contact: symmetry}\n" + solver));
  whole.initialize();
  half.initialize();
  const Discretization& dw = whole.discretization();
  const Discretization& dh = half.discretization();
  std::map<Key, std::size_t> in_whole;
  for (std::size_t i = 0; i < dw.num_points(); ++i) in_whole[lattice_key(dw.x.get(i))] = i;
  double worst_u = 0, largest_u = 0, worst_force = 0, largest_force = 0;
  for (int step = 0; step < 40; ++step) {
    whole.step();
    half.step();
    ASSERT_TRUE(half.correspondence().symmetry_wall_active(0)) << "released at step " << step + 1;
    // The force on the upper half from the lower one: Σ f V over the upper half (its own bonds cancel).
    Vec3 across;
    for (std::size_t i = 0; i < dw.num_points(); ++i)
      if (dw.x(i, 2) > 0)
        for (int d = 0; d < 3; ++d) across[d] += whole.state().force(i, d) * dw.volume[i];
    const Vec3 on_wall = half.totals().rigid_force[0];
    worst_force = std::max(worst_force, norm(on_wall + across));
    largest_force = std::max(largest_force, norm(across));
    for (std::size_t i = 0; i < dh.num_points(); ++i) {
      const std::size_t j = in_whole.at(lattice_key(dh.x.get(i)));
      worst_u = std::max(worst_u, norm(half.state().u.get(i) - whole.state().u.get(j)));
      largest_u = std::max(largest_u, norm(whole.state().u.get(j)));
    }
  }
  fmt::print("measured: worst |u_half − u_whole| = {:.3g} m (largest |u| {:.3g} m); worst |F_wall + F_across| = {:.3g} N "
             "(largest {:.4g} N)\n", worst_u, largest_u, worst_force, largest_force);
  // The two runs differ only in the order of the bond sums. Measured: 9.6e-20 m on 1.5e-5 m, and 8.6e-11 N on
  // 16.7 kN.
  EXPECT_LT(worst_u, 1e-12 * largest_u);
  EXPECT_LT(worst_force, 1e-12 * largest_force);
  EXPECT_GT(largest_force, 1e3);  // it did press on the plane
}

TEST(SymmetryWall, HomogeneousCompressionLoadsThePointsNextToThePlaneAsInteriorPoints) {
  // Uniaxial strain at 1000 /s prescribed on every point of a 20 × 20 × 10 mm slab for 50 steps (ε = −0.5 %,
  // elastic): σ is uniform. The force on a point reads its partners' K too, so the points more than two
  // horizons from the free faces, with the mirror images, have whole families whose members have whole
  // families: the net force on them must vanish.
  const std::string rest =
      "node_sets:\n  all: {shape: {box: {min: [-1, -1, -1], max: [1, 1, 1]}}}\n"
      "boundary_conditions:\n  - {node_set: all, velocity: {x: \"0\", y: \"0\", z: \"-1000*z\"}}\n"
      "solver: {num_steps: 50, time_step: 1e-7}\n";
  const std::string box = "{min: [0, 0, 0], max: [0.02, 0.02, 0.01]}";
  auto run = [&](const std::string& wall) {
    auto sim = std::make_unique<Simulation>(deck(box, rest + "rigid_walls:\n  - " + wall + "\n"));
    sim->initialize();
    for (int k = 0; k < 50; ++k) sim->step();
    sim->prepare_outputs(true, true);
    return sim;
  };
  const auto symmetric = run("{name: anvil, point: [0, 0, 0], normal: [0, 0, 1], contact: symmetry}");
  const auto penalty = run("{name: anvil, point: [0, 0, 0.0005], normal: [0, 0, 1]}");
  const Discretization& disc = symmetric->discretization();
  const double F_zz = 1 - 50 * 1e-7 * 1000;  // the prescribed displacement is exact: u_z = −ε̇ t z
  double worst_F = 0, worst_force = 0, penalty_force = 0, sigma = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    const State& s = symmetric->state();
    const char* names[9] = {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"};
    for (int c = 0; c < 9; ++c) {
      const double expected = c == 0 || c == 4 ? 1.0 : c == 8 ? F_zz : 0.0;
      worst_F = std::max(worst_F, std::abs(s.point_outputs.at(std::string("deformation_gradient_") + names[c])[i] - expected));
    }
    sigma = std::max(sigma, std::abs(s.point_outputs.at("cauchy_stress_zz")[i]));
    const double x = disc.x(i, 0), y = disc.x(i, 1), z = disc.x(i, 2);
    const bool interior_column = std::min({x, 0.02 - x, y, 0.02 - y}) > 2 * 3.015e-3;
    if (!interior_column || z > 0.01 - 2 * 3.015e-3) continue;  // the layers within a horizon of the plane
    worst_force = std::max(worst_force, norm(s.force.get(i)));
    penalty_force = std::max(penalty_force, norm(penalty->state().force.get(i)));
  }
  // A force density of the scale of the stress over the spacing: σ/Δx.
  const double scale = sigma / 1e-3;
  fmt::print("measured: worst |F − F_exact| = {:.3g}; |σ_zz| = {:.4g} Pa; largest |f| next to the plane, away from the "
             "sides: {:.3g} N/m³ with the symmetry plane, {:.3g} with the penalty wall (σ/Δx = {:.3g})\n",
             worst_F, sigma, worst_force, penalty_force, scale);
  // Measured: F exact to 2.1e-15; |f| 2.4e-3 N/m³ (5e-15 σ/Δx: round-off) with the plane, 0.97 σ/Δx with the
  // penalty wall.
  EXPECT_LT(worst_F, 1e-12);
  EXPECT_GT(sigma, 1e8);
  EXPECT_LT(worst_force, 1e-9 * scale);
  EXPECT_GT(penalty_force, 0.1 * scale);
  EXPECT_LT(symmetric->totals().rigid_force[0].z, 0.0);  // the slab presses on the wall
}

TEST(SymmetryWall, ThrownCubeBouncesAndTheMirrorBondsAreReleased) {
  Simulation sim(deck("{min: [0, 0, 0], max: [0.006, 0.006, 0.006]}",
                      "initial_conditions:\n  - {velocity: {x: \"1\", y: \"0\", z: \"-10\"}}\n"
                      "rigid_walls:\n  - {name: anvil, point: [0, 0, 0], normal: [0, 0, 1], contact: symmetry}\n"
                      "solver: {end_time: 8 us}"));
  sim.initialize();
  const Totals start = sim.totals();
  const double dt = sim.time_step();
  Vec3 impulse, previous = -1.0 * start.rigid_force[0];
  double released_at = -1, peak = 0;
  while (sim.state().step < sim.total_steps()) {
    sim.step();
    const Totals now = sim.totals();
    const Vec3 force = -1.0 * now.rigid_force[0];  // on the body
    impulse = impulse + (0.5 * dt) * (previous + force);
    previous = force;
    peak = std::max(peak, norm(force));
    if (released_at < 0 && !sim.correspondence().symmetry_wall_active(0)) released_at = sim.state().time;
  }
  const Totals end = sim.totals();
  const Vec3 change = end.momentum - start.momentum;
  const double p0 = norm(start.momentum);
  const double balance = end.kinetic_energy + end.strain_energy + end.dissipated_energy + end.hourglass_work;
  fmt::print("measured: released at {:.4g} s; restitution {:.4f}; |Δp − I| = {:.3g} (p0 = {:.4g}); peak force {:.4g} N; "
             "energy KE {:.5g} + elastic {:.5g} + hourglass {:.5g} − wall work {:.3g} vs KE0 {:.5g}\n",
             released_at, end.momentum.z / -start.momentum.z, norm(change - impulse), p0, peak, end.kinetic_energy,
             end.strain_energy, end.hourglass_work, end.external_work, start.kinetic_energy);
  // Measured: released at 2.46 µs, restitution 0.73, |Δp − I| = 1.1e-17 kg m/s; the balance closes to +0.18 %
  // of KE0, with 36 % of KE0 in the hourglass work: the dashpots (C_HV = 0.05) damp the waves the impact
  // leaves in this coarse cube.
  EXPECT_GT(released_at, 0.0);
  EXPECT_GT(end.momentum.z, 0.5 * -start.momentum.z);       // it bounced
  EXPECT_NEAR(end.momentum.x, start.momentum.x, 1e-12 * p0);  // frictionless
  EXPECT_LT(norm(change - impulse), 1e-12 * p0);
  EXPECT_EQ(end.rigid_force[0].z, 0.0);  // released, and not touching the penalty plane
  EXPECT_NEAR(balance - end.external_work, start.kinetic_energy, 1e-2 * start.kinetic_energy);
}

/// The message of the InputError the deck's set-up throws, which must point at the line `line` (its wall).
std::string refusal(const std::string& box, const std::string& wall, int line, const std::string& other_body = "") {
  std::string text = fmt::format(R"(discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
{}  steel: {{model: pmb, density: 7800, youngs_modulus: 200 GPa}}
bodies:
  block: {{material: al, shape: {{box: {}}}}}
{}rigid_walls:
  - {}
solver: {{num_steps: 1}}
)",
                                 material, box, other_body, wall);
  try {
    Simulation sim(parse_deck(text, "refused.yaml", "."));
  } catch (const InputError& e) {
    fmt::print("refused: {}\n", e.what());
    EXPECT_EQ(e.diagnostics().front().pos.line, line) << e.what();
    return e.what();
  }
  return "";
}

TEST(SymmetryWall, DecksItCannotModelAreRefusedAtTheWall) {
  const std::string cube = "{min: [0, 0, 0], max: [0.006, 0.006, 0.006]}";
  EXPECT_NE(refusal(cube, "{name: w, point: [0, 0, 0.0005], normal: [0, 0, 1], contact: symmetry}", 9)
                .find("is 0 m from the plane, not half its spacing (0.0005 m)"), std::string::npos);
  EXPECT_NE(refusal(cube, "{name: w, point: [0, 0, 0.001], normal: [0, 0, 1], contact: symmetry}", 9).find("is behind the plane"),
            std::string::npos);
  EXPECT_NE(refusal(cube, "{name: w, point: [0, 0, -0.01], normal: [0, 0, 1], contact: symmetry}", 9)
                .find("no correspondence point is within a horizon"), std::string::npos);
  EXPECT_NE(refusal(cube, "{name: w, point: [0, 0, 0], normal: [0, 0, 1], contact: symmetry}", 10,
                    "  plate: {material: steel, shape: {box: {min: [0.01, 0, 0], max: [0.02, 0.006, 0.006]}}}\n")
                .find("symmetry contact is built for correspondence bodies only"), std::string::npos);
  EXPECT_NE(refusal(cube, "{name: w, point: [0, 0, 0], normal: [0, 0, 1], contact: symmetry}\n"
                          "  - {name: v, point: [0, 0, 0], normal: [1, 0, 0], contact: symmetry}", 10)
                .find("within a horizon of two symmetry walls"), std::string::npos);
  // A moving symmetry wall is a deck error (its mirror images would move with it).
  try {
    parse_deck(fmt::format("discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}\n{}bodies:\n"
                           "  block: {{material: al, shape: {{box: {}}}}}\nrigid_walls:\n"
                           "  - {{name: w, point: [0, 0, 0], normal: [0, 0, 1], speed: 1, contact: symmetry}}\n"
                           "solver: {{num_steps: 1}}\n", material, cube),
               "moving.yaml", ".");
    ADD_FAILURE() << "a moving symmetry wall was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("must be at rest"), std::string::npos) << e.what();
    EXPECT_EQ(e.diagnostics().front().pos.line, 8);
  }
}

}  // namespace
}  // namespace peridot
