// Contact (contact/short_range.hpp, contact/rigid_body.hpp): two blocks that collide bounce apart with the
// momentum conserved to round-off and the energy closing; the faces of a crack do not pass through each
// other; a bond broken under compression gives its pair no energy; contact that touches nothing changes
// no bit; a free rigid sphere exchanges momentum with a block
// exactly; each rigid shape pushes a point out along its surface normal with κ h. The opt-in barrier
// (contact.barrier_fraction) changes no bit where no pair enters it, stores the potential of its force, and
// keeps apart the pairs of a hard impact that the linear force lets meet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "peridot/deck/deck.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {
namespace {

/// Two 5 mm glass cubes, 4 mm apart (beyond a horizon, so never bonded), closing at 2 v.
std::string two_cubes(const std::string& extra, double v = 20) {
  return fmt::format(R"(discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
materials:
  glass: {{model: pmb, density: 2440, youngs_modulus: 72 GPa, damage: {{critical_stretch: 0.01}}}}
bodies:
  left: {{material: glass, shape: {{box: {{min: [0, 0, 0], max: [5 mm, 5 mm, 5 mm]}}}}}}
  right: {{material: glass, shape: {{box: {{min: [9 mm, 0.4 mm, 0], max: [14 mm, 5.4 mm, 5 mm]}}}}}}
node_sets:
  l: {{shape: {{box: {{min: [-1, -1, -1], max: [7 mm, 1, 1]}}}}}}
  r: {{shape: {{box: {{min: [7 mm, -1, -1], max: [1, 1, 1]}}}}}}
initial_conditions:
  - {{node_set: l, velocity: {{x: "{}"}}}}
  - {{node_set: r, velocity: {{x: "{}"}}}}
{}
solver: {{end_time: 300 us}}
)",
                     v, -v, extra);
}

/// Smallest distance between a point of the left cube and one of the right cube (m).
double closest_approach(const Simulation& sim) {
  const Discretization& disc = sim.discretization();
  const State& s = sim.state();
  double closest = INFINITY;
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    for (std::size_t j = 0; j < disc.num_points(); ++j) {
      if (disc.block[i] != 0 || disc.block[j] != 1) continue;
      const Vec3 d = disc.x.get(j) + s.u.get(j) - disc.x.get(i) - s.u.get(i);
      closest = std::min(closest, norm(d));
    }
  return closest;
}

TEST(ShortRangeContact, CollidingCubesBounceApartConservingMomentumAndEnergy) {
  Simulation sim(parse_deck(two_cubes("contact: {}"), "cubes.yaml", "."));
  sim.initialize();
  const Totals start = sim.totals();
  const double p_one = 0.5 * start.kinetic_energy / 20 * 2;  // m v of one cube: KE0 = 2 · ½ m v²
  double closest = INFINITY, worst_balance = 0, peak_contact = 0;
  while (sim.state().step < sim.total_steps()) {
    sim.step();
    if (sim.state().step % 10) continue;
    closest = std::min(closest, closest_approach(sim));
    const Totals t = sim.totals();
    EXPECT_LT(norm(t.momentum), 1e-13 * p_one) << "at step " << sim.state().step;
    // What the contact forces did is in external_work: it is minus the change of the stored contact energy.
    worst_balance = std::max(worst_balance, std::abs(t.kinetic_energy + t.strain_energy - t.external_work - start.kinetic_energy));
    peak_contact = std::max(peak_contact, t.contact_energy);
  }
  const Totals end = sim.totals();
  // Left cube's momentum after the bounce: it moves back.
  const Discretization& disc = sim.discretization();
  double left_momentum = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    if (disc.block[i] == 0) left_momentum += 2440 * disc.volume[i] * sim.state().v(i, 0);
  fmt::print("measured: closest approach {:.3g} mm, left cube's momentum {:.4g} of its initial, worst |KE + W − work − KE0| = "
             "{:.3g} of KE0, peak contact energy {:.3g} of KE0, fragments {}, pair list builds {}\n",
             closest * 1e3, left_momentum / p_one, worst_balance / start.kinetic_energy, peak_contact / start.kinetic_energy,
             end.fragments, sim.short_range()->builds());
  EXPECT_LT(left_momentum, -0.5 * p_one);  // it came back (the rest rings in the cubes)
  EXPECT_EQ(end.fragments, 2u);
  EXPECT_GT(closest, 0.5e-3);  // never closer than half a spacing (contact at d = 1.35 Δx)
  EXPECT_LT(worst_balance, 0.01 * start.kinetic_energy);
  EXPECT_GT(peak_contact, 0.05 * start.kinetic_energy);  // the contact took the impact
  EXPECT_EQ(end.max_damage, 0.0);
}

TEST(ShortRangeContact, ContactThatTouchesNothingChangesNoBit) {
  // The cubes, closing slowly, do not meet within 30 µs: contact on or off, the same bits.
  auto run = [](const std::string& contact) {
    std::string deck = two_cubes(contact, 1);
    deck.replace(deck.find("300 us"), 6, "30 us");
    Simulation sim(parse_deck(deck, "cubes.yaml", "."));
    sim.initialize();
    while (sim.state().step < sim.total_steps()) sim.step();
    return std::vector<double>(sim.state().u.data(), sim.state().u.data() + 3 * sim.discretization().num_points());
  };
  EXPECT_EQ(run(""), run("contact: {}"));
}

TEST(ShortRangeContact, CrackFacesPushedTogetherDoNotPassThrough) {
  // One bar cut through by a precrack at x = 5 mm, its halves thrown at each other: within one body, the
  // faces (1 Δx apart at rest, so d = 0.9 Δx) repel; without contact they pass through each other.
  auto deepest = [](const std::string& contact) {
    const std::string deck = fmt::format(R"(discretization: {{dimension: 2, plane: stress, spacing: 0.5 mm, horizon_factor: 3.015}}
materials:
  pmma: {{model: pmb, density: 1190, youngs_modulus: 3 GPa, damage: {{critical_stretch: 0.05}}}}
bodies:
  bar: {{material: pmma, shape: {{box: {{min: [0, 0], max: [10 mm, 3 mm]}}}}}}
precracks:
  - segment: {{from: [5 mm, -1 mm], to: [5 mm, 4 mm]}}
initial_conditions:
  - velocity: {{x: "x < 0.005 ? 30 : -30"}}
{}
solver: {{end_time: 40 us}}
)",
                                         contact);
    Simulation sim(parse_deck(deck, "crack.yaml", "."));
    sim.initialize();
    const Discretization& disc = sim.discretization();
    double overlap = -INFINITY;  // how far a point of one half has gone past the other half's face
    while (sim.state().step < sim.total_steps()) {
      sim.step();
      double left_front = -INFINITY, right_front = INFINITY;
      for (std::size_t i = 0; i < disc.num_points(); ++i) {
        const double y = disc.x(i, 0) + sim.state().u(i, 0);
        if (disc.x(i, 0) < 0.005) left_front = std::max(left_front, y);
        else right_front = std::min(right_front, y);
      }
      overlap = std::max(overlap, left_front - right_front);
    }
    return overlap;
  };
  const double without = deepest(""), with = deepest("contact: {}");
  fmt::print("measured: the halves overlap by {:.3g} mm without contact, {:.3g} mm with it\n", without * 1e3, with * 1e3);
  EXPECT_GT(without, 0.5e-3);
  EXPECT_LT(with, -0.25e-3);  // the faces stay more than half a spacing apart
}

TEST(ShortRangeContact, BondBrokenUnderCompressionResistsOnlyFurtherApproach) {
  // Two points 1 mm apart (contact distance d = 0.9 mm), their bond broken while they are 0.6 mm apart (a point
  // failing in a crushed region): the pair must not push at 0.6 mm, which would hand it ½ k (d − r)² of energy
  // out of nothing; it resists approach from there, and once the points have been d apart the full d holds.
  Simulation sim(parse_deck(R"(discretization: {dimension: 3, spacing: 1 mm, horizon_factor: 1.5}
materials:
  steel: {model: pmb, density: 7800, youngs_modulus: 200 GPa, damage: {critical_stretch: 0.5}}
bodies:
  pair: {material: steel, shape: {box: {min: [0, 0, 0], max: [2 mm, 1 mm, 1 mm]}}}
contact: {}
solver: {end_time: 1 us}
)",
                            "pair.yaml", "."));
  sim.initialize();
  ASSERT_EQ(sim.discretization().num_points(), 2u);
  auto& broken = const_cast<BondList&>(sim.bonds()).broken;  // what a failing point does to its bonds
  auto push_at = [&](double gap) {  // force density on the left point along +x (< 0: pushed away) at this gap
    sim.state().u(1, 0) = gap - 1e-3;
    sim.evaluate(sim.time_step(), false);
    return sim.contact_force()(0, 0);
  };
  ASSERT_EQ(push_at(0.6e-3), 0.0);  // bonded: no contact
  std::fill(broken.begin(), broken.end(), std::uint8_t{1});
  EXPECT_EQ(push_at(0.6e-3), 0.0);      // broken at 0.6 mm: touching there, not pushing
  const double closer = push_at(0.5e-3);
  EXPECT_LT(closer, 0.0);               // pushed closer: it resists
  EXPECT_EQ(push_at(0.6e-3), 0.0);      // back where it broke
  EXPECT_EQ(push_at(0.8e-3), 0.0);
  EXPECT_EQ(push_at(1.0e-3), 0.0);      // apart beyond d
  const double again = push_at(0.6e-3);  // now the full d = 0.9 mm: the linear penalty at 0.3 mm against 0.1 mm
  fmt::print("measured: force density {:.4g} N/m³ at 0.5 mm after the break at 0.6 mm, {:.4g} at 0.6 mm after opening\n",
             closer, again);
  EXPECT_NEAR(again / closer, 3.0, 1e-12);
}

TEST(RigidBody, FreeSphereAndBlockExchangeMomentumExactly) {
  const std::string deck = R"(discretization: {dimension: 3, spacing: 1 mm, horizon_factor: 3.015}
materials:
  al: {model: pmb, density: 2700, youngs_modulus: 70 GPa}
bodies:
  block: {material: al, shape: {box: {min: [0, 0, 0], max: [6 mm, 6 mm, 4 mm]}}}
rigid_bodies:
  - name: ball
    sphere: {center: [3 mm, 3 mm, 6 mm], radius: 2 mm}
    mass: 2 g
    velocity: [0, 0, -20]
solver: {end_time: 60 us}
)";
  Simulation sim(parse_deck(deck, "ball.yaml", "."));
  sim.initialize();
  const RigidBody& ball = sim.rigid_bodies()[0];
  const double p0 = 0.002 * 20;
  double peak = 0;
  while (sim.state().step < sim.total_steps()) {
    sim.step();
    const Totals t = sim.totals();
    const Vec3 total = t.momentum + 0.002 * ball.velocity;
    EXPECT_LT(std::abs(total.z + p0), 1e-12 * p0) << "at step " << sim.state().step;
    EXPECT_LT(std::abs(total.x) + std::abs(total.y), 1e-12 * p0);
    peak = std::max(peak, ball.force.z);
  }
  fmt::print("measured: ball velocity {:.4g} m/s after the impact (from −20), peak force {:.4g} N\n", ball.velocity.z, peak);
  EXPECT_GT(ball.velocity.z, -15.0);  // the block slowed it
  EXPECT_GT(peak, 0.0);
  EXPECT_EQ(sim.totals().rigid_force[0].z, ball.force.z);  // the history's force is the one that moved it
}

TEST(RigidBody, EachShapePushesAPointOutAlongItsNormal) {
  // A 5 × 5 × 5 block at rest; each shape overlaps one corner point by a known depth h: its force density
  // is κ h n with κ = 0.5 · 2π c δ², n the outward normal of the nearest face.
  struct Case {
    std::string body;
    Vec3 normal;
    double depth;
  };
  // The corner point (0.5, 0.5, 0.5) mm; the next points are 1 mm away, out of every shape.
  const Case cases[] = {
      {"sphere: {center: [-0.3 mm, 0.5 mm, 0.5 mm], radius: 1 mm}", {1, 0, 0}, 0.2e-3},
      {"cylinder: {center: [0.5 mm, 0.5 mm, -2 mm], axis: [0, 0, 1], length: 2.7 mm, radius: 0.4 mm}", {0, 0, 1}, 0.2e-3},
      {"cylinder: {center: [-0.2 mm, 0.5 mm, -1 mm], axis: [0, 0, 1], length: 2 mm, radius: 0.8 mm}", {1, 0, 0}, 0.1e-3},
      {"box: {min: [-1 mm, -1 mm, -1 mm], max: [0.6 mm, 0.65 mm, 0.7 mm]}", {1, 0, 0}, 0.1e-3},
      {"plane: {point: [0.8 mm, 0.8 mm, 0.8 mm], normal: [1, 1, 1]}", {1 / std::sqrt(3.0), 1 / std::sqrt(3.0), 1 / std::sqrt(3.0)},
       0.3e-3 * std::sqrt(3.0)},
  };
  for (const Case& c : cases) {
    const std::string deck = fmt::format(R"(discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
materials:
  al: {{model: pmb, density: 2700, youngs_modulus: 70 GPa}}
bodies:
  block: {{material: al, shape: {{box: {{min: [0, 0, 0], max: [5 mm, 5 mm, 5 mm]}}}}}}
rigid_bodies:
  - {{name: tool, {}}}
solver: {{num_steps: 1}}
)",
                                         c.body);
    Simulation sim(parse_deck(deck, "shape.yaml", "."));
    sim.initialize();
    const MaterialParams& p = sim.model().params[0];
    const double kappa = 0.5 * 2 * std::numbers::pi * p.stable_micromodulus * p.horizon * p.horizon;
    const Discretization& disc = sim.discretization();
    std::size_t touched = 0;
    for (std::size_t i = 0; i < disc.num_points(); ++i) {
      const Vec3 b = sim.contact_force().get(i);
      if (norm(b) == 0) continue;
      ++touched;
      EXPECT_NEAR(disc.x(i, 0), 0.5e-3, 1e-12) << c.body;
      EXPECT_NEAR(disc.x(i, 1), 0.5e-3, 1e-12) << c.body;
      EXPECT_NEAR(disc.x(i, 2), 0.5e-3, 1e-12) << c.body;
      for (int d = 0; d < 3; ++d) EXPECT_NEAR(b[d], kappa * c.depth * c.normal[d], 1e-9 * kappa * c.depth) << c.body;
    }
    EXPECT_EQ(touched, 1u) << c.body;
  }
}

}  // namespace
}  // namespace peridot

namespace peridot {
namespace {

TEST(ShortRangeContact, FrictionOfASlidingBlockIsMuTimesTheNormalForce) {
  // A block pressed by a body force onto a held slab (a precrack cuts every bond between them) slides at 2 m/s:
  // with friction the tangential contact force on it is μ times the normal one, against the sliding. The block's
  // points are two spacings above the slab's, so that every pair between them has the contact distance 1.35 Δx
  // (pairs that start closer than 1.5 Δx keep 0.9 of their reference distance, and sliding by a spacing would
  // bring such a pair closer than its own: a bump), and it starts displaced down to just touch.
  auto deck = [](const std::string& friction) {
    return fmt::format(R"(discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
materials:
  steel: {{model: pmb, density: 7800, youngs_modulus: 200 GPa}}
bodies:
  slab: {{material: steel, shape: {{box: {{min: [0, 0, 0], max: [12 mm, 8 mm, 3 mm]}}}}}}
  block: {{material: steel, shape: {{box: {{min: [2 mm, 2 mm, 4 mm], max: [6 mm, 6 mm, 7 mm]}}}}}}
precracks:
  - rectangle: {{origin: [-1 mm, -1 mm, 3.5 mm], edge1: [14 mm, 0, 0], edge2: [0, 10 mm, 0]}}
node_sets:
  base: {{shape: {{box: {{min: [-1, -1, -1], max: [1, 1, 1 mm]}}}}}}
  top: {{shape: {{box: {{min: [-1, -1, 3 mm], max: [1, 1, 1]}}}}}}
initial_conditions:
  - {{node_set: top, velocity: {{x: "2"}}}}
  - {{node_set: top, displacement: {{z: "-0.00065"}}}}
boundary_conditions:
  - {{node_set: base, displacement: {{x: "0", y: "0", z: "0"}}}}
body_forces:
  - {{node_set: top, z: "-2e9"}}
contact: {{{}}}
solver: {{end_time: 40 us}}
)",
                       friction);
  };
  auto slide = [&](const std::string& friction, double& ratio, double& speed) {
    Simulation sim(parse_deck(deck(friction), "slide.yaml", "."));
    sim.initialize();
    const Discretization& disc = sim.discretization();
    auto block_speed = [&] {
      double momentum = 0, mass = 0;
      for (std::size_t i = 0; i < disc.num_points(); ++i)
        if (disc.block[i] == 1) momentum += disc.volume[i] * sim.state().v(i, 0), mass += disc.volume[i];
      return momentum / mass;
    };
    double tangential = 0, normal = 0;
    while (sim.state().step < sim.total_steps()) {
      sim.step();
      if (block_speed() < 0.5) continue;  // while it slides (once stopped, friction holds it with less than μ)
      const Totals t = sim.totals();
      tangential += t.body_contact_force[1].x;
      normal += t.body_contact_force[1].z;
    }
    ratio = tangential / normal;
    speed = block_speed();
  };
  double ratio_with, speed_with, ratio_without, speed_without;
  slide("friction: [{bodies: [slab, block], coefficient: 0.3}]", ratio_with, speed_with);
  slide("", ratio_without, speed_without);
  fmt::print("measured: tangential / normal contact force on the block {:.4f} with μ = 0.3, {:.2g} without; its speed "
             "after 40 µs {:.4g} m/s with friction, {:.4g} m/s without (from 2)\n",
             ratio_with, ratio_without, speed_with, speed_without);
  // Against the sliding (+x): −μ. Measured −0.287 with μ = 0.3 and +0.031 without friction: the two lattices
  // of points pressed together push each other sideways a little as they pass (an egg-crate surface).
  EXPECT_NEAR(ratio_with, -0.3, 0.03);
  EXPECT_NEAR(ratio_without, 0.0, 0.05);
  EXPECT_LT(speed_with, speed_without - 0.1);
}

/// Runs two_cubes(contact, v) for its first `steps` steps: the closest approach of the cubes, the largest
/// |external work + stored contact energy| (the contact's work is minus its stored energy when the stored
/// energy is the force's potential; no support does work here), each relative to the initial kinetic energy,
/// and the final displacements.
struct Impact {
  double closest = INFINITY, worst_potential = 0;
  std::vector<double> u;
};
Impact impact(const std::string& contact, double v, bool damage, std::uint64_t steps) {
  std::string deck = two_cubes(contact, v);
  if (!damage) deck.replace(deck.find(", damage: {critical_stretch: 0.01}"), 34, "");
  Simulation sim(parse_deck(deck, "cubes.yaml", "."));
  sim.initialize();
  const double start = sim.totals().kinetic_energy;
  Impact r;
  while (sim.state().step < steps) {
    sim.step();
    r.closest = std::min(r.closest, closest_approach(sim));
    const Totals t = sim.totals();
    r.worst_potential = std::max(r.worst_potential, std::abs(t.external_work + t.contact_energy) / start);
  }
  r.u.assign(sim.state().u.data(), sim.state().u.data() + 3 * sim.discretization().num_points());
  return r;
}

TEST(ContactBarrier, PairsThatStayOutsideItSeeTheLinearForceBitForBit) {
  // At 2 × 100 m/s with soft contact the cubes come no closer than 0.73 mm, outside r_c = 0.5 × 1.35 mm.
  const Impact linear = impact("contact: {stiffness_factor: 0.5}", 100, true, 400);
  const Impact barrier = impact("contact: {stiffness_factor: 0.5, barrier_fraction: 0.5}", 100, true, 400);
  ASSERT_GT(linear.closest, 0.5 * 1.35e-3);
  EXPECT_EQ(linear.u, barrier.u);
}

TEST(ContactBarrier, StoredEnergyIsThePotentialOfTheForce) {
  // Elastic cubes, no damage, a barrier at 0.8 d (1.08 mm) that the pairs enter (they come within 0.73 mm):
  // the work the contact forces did is minus the energy stored, through the barrier and out again, to the
  // time-integration error of the linear law (measured: the same with b = 0).
  for (double fraction : {0.0, 0.8}) {
    const Impact r = impact(fmt::format("contact: {{stiffness_factor: 0.5, barrier_fraction: {}}}", fraction), 100, false, 400);
    fmt::print("measured: barrier {}: closest {:.3g} mm, worst |work + stored| {:.3g} of KE0\n", fraction, r.closest * 1e3,
               r.worst_potential);
    if (fraction > 0) EXPECT_LT(r.closest, fraction * 1.35e-3);
    EXPECT_LT(r.worst_potential, 2e-3);
  }
}

TEST(ContactBarrier, KeepsApartPairsThatTheLinearForceLetsMeet) {
  // 2 × 300 m/s of glass on glass with soft contact: the linear force lets surface points meet (a pair at
  // 1 µm), the barrier keeps every pair 70 times farther apart.
  const Impact linear = impact("contact: {stiffness_factor: 0.5}", 300, true, 400);
  const Impact barrier = impact("contact: {stiffness_factor: 0.5, barrier_fraction: 0.5}", 300, true, 400);
  fmt::print("measured: closest approach linear {:.3g} mm, barrier 0.5 {:.3g} mm\n", linear.closest * 1e3, barrier.closest * 1e3);
  EXPECT_LT(linear.closest, 0.01e-3);
  EXPECT_GT(barrier.closest, 0.05e-3);
}

}  // namespace
}  // namespace peridot
