// Energy-based bond failure (damage/energy_failure.hpp, docs/algorithms.md §14): the count N_c against a
// brute-force count of the bonds crossing one crack cell and the continuum limit; a PMB bond stretched
// monotonically breaks at the closed-form stretch; compression never breaks; a viscoelastic bond cycled at a
// constant amplitude accumulates work and breaks in a later cycle; the same bits for 1 and 2 threads.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "peridot/damage/energy_failure.hpp"
#include "peridot/solvers/simulation.hpp"
#include "support/problems.hpp"

namespace peridot {
namespace {

// ---- the count ------------------------------------------------------------------------------------------

/// ½ on the edge of [−½, ½], 1 inside, 0 outside (crossing point t in lattice units).
double edge_weight(double t) {
  const double eps = 1e-9;
  if (std::abs(t) < 0.5 - eps) return 1;
  if (std::abs(std::abs(t) - 0.5) <= eps) return 0.5;
  return 0;
}

/// Every pair of lattice points (unit spacing, rows at y = k + ½ so that the crack plane y = 0 lies midway
/// between two rows, columns at integer x so that the cell's ends x = ±½ lie midway between two columns),
/// one above and one below the plane, within m (the neighbour search's allowance), whose segment crosses the
/// cell [−½, ½] (× [−½, ½] in 3D), weighted ½ through an edge (¼ through a corner).
double brute_force_crossings(int dimension, double m) {
  const double cutoff = m * (1 + 1e-10);
  const int r = static_cast<int>(std::ceil(m)) + 1;
  double sum = 0;
  for (int ka = 0; ka <= r; ++ka)          // row above: y = ka + ½
    for (int kb = 0; kb <= r; ++kb)        // row below: y = −(kb + ½)
      for (int xa = -r; xa <= r; ++xa)
        for (int xb = -r; xb <= r; ++xb)
          for (int za = (dimension == 3 ? -r : 0); za <= (dimension == 3 ? r : 0); ++za)
            for (int zb = (dimension == 3 ? -r : 0); zb <= (dimension == 3 ? r : 0); ++zb) {
              const double ya = ka + 0.5, yb = -(kb + 0.5);
              const double dx = xb - xa, dy = yb - ya, dz = zb - za;
              if (dx * dx + dy * dy + dz * dz > cutoff * cutoff) continue;
              const double f = ya / (ya - yb);  // where the segment meets y = 0
              sum += edge_weight(xa + f * dx) * (dimension == 3 ? edge_weight(za + f * dz) : 1.0);
            }
  return sum;
}

TEST(CrackCrossings, TwoDimensionsThreeSpacingsIs18BondsAnd36Micropotentials) {
  EXPECT_EQ(crack_crossing_bonds(2, 3.0), 18);
  EXPECT_EQ(crack_micropotentials(2, 3.0), 36);  // Madenci & Oterkus (2017) say 34 (docs/algorithms.md §14)
  EXPECT_EQ(brute_force_crossings(2, 3.0), 18);
  EXPECT_EQ(crack_crossing_bonds(2, 3.015), 18);  // the usual 3.015: the same family
  EXPECT_EQ(crack_crossing_bonds(3, 3.0), 70);
  EXPECT_EQ(crack_micropotentials(3, 3.0), 140);
}

// A bar: the bonds crossing a point between two lattice points, 1 + 2 + … + m of them (m = ⌊δ/Δx⌋).
TEST(CrackCrossings, OneDimensionIsTheTriangularNumber) {
  EXPECT_EQ(crack_crossing_bonds(1, 3.0), 6);
  EXPECT_EQ(crack_crossing_bonds(1, 3.015), 6);
  EXPECT_EQ(crack_micropotentials(1, 3.0), 12);
  EXPECT_EQ(crack_crossing_bonds(1, 1.0), 1);
  EXPECT_EQ(crack_crossing_bonds(1, 10.0), 55);
}

TEST(CrackCrossings, MatchBruteForceForOtherHorizons) {
  for (double m : {1.0, 1.5, 2.0, 2.5, 3.015, 4.0, 5.0, 6.3}) {
    SCOPED_TRACE(m);
    EXPECT_DOUBLE_EQ(crack_crossing_bonds(2, m), brute_force_crossings(2, m));
  }
  for (double m : {1.0, 1.5, 2.0, 3.0, 4.0}) {
    SCOPED_TRACE(m);
    EXPECT_DOUBLE_EQ(crack_crossing_bonds(3, m), brute_force_crossings(3, m));
  }
}

TEST(CrackCrossings, ApproachTheContinuumLimit) {
  // Bonds crossing a unit area of a continuum of unit density: 2δ³/3 per unit length (2D), πδ⁴/4 per unit
  // area (3D). The lattice count's relative error stays below 0.2/m (not monotonically: it oscillates as
  // lattice shells enter the family).
  for (double m : {10.0, 20.0, 40.0, 80.0, 160.0})
    EXPECT_LT(std::abs(crack_crossing_bonds(2, m) / (2 * m * m * m / 3) - 1), 0.2 / m) << m;
  for (double m : {5.0, 10.0, 20.0, 40.0})
    EXPECT_LT(std::abs(crack_crossing_bonds(3, m) / (std::numbers::pi * std::pow(m, 4) / 4) - 1), 0.2 / m) << m;
}

// ---- one bond -------------------------------------------------------------------------------------------

constexpr double spacing = 1e-3, volume = spacing * spacing * spacing;

/// Two points Δx apart along x (δ = 1.5 Δx: one bond each way) of `model`, energy criterion with Gc.
struct TwoPoints {
  std::filesystem::path file;
  Problem problem;

  TwoPoints(const std::string& model, double fracture_energy, Parameters parameters = {}) {
    file = std::filesystem::temp_directory_path() /
           ("peridot_energy_two_points_" + std::to_string(::getpid()) + "_" + model + ".txt");
    std::ofstream(file) << "0 0 0 " << volume << "\n" << spacing << " 0 0 " << volume << "\n";
    testing::BlockSetup s;
    s.model = model;
    s.parameters = parameters;
    problem = testing::box_problem(s);
    problem.bodies[0].shape.reset();
    problem.bodies[0].points_file = file.string();
    problem.bodies[0].horizon = 1.5 * spacing;
    problem.materials[0].damage.enabled = true;
    problem.materials[0].damage.fracture_energy = fracture_energy;
    problem.materials[0].damage.criterion = DamageCriterion::energy;
  }
  ~TwoPoints() { std::filesystem::remove(file); }
};

/// Sets the bond's stretch to s (the two points move apart symmetrically along x).
void set_stretch(Simulation& sim, double s) {
  sim.state().u(0, 0) = -0.5 * s * spacing;
  sim.state().u(1, 0) = 0.5 * s * spacing;
}

TEST(EnergyFailure, PmbBondBreaksWhereItsWorkReachesTheThreshold) {
  const double Gc = 50;
  TwoPoints setup("pmb", Gc);
  Simulation sim(setup.problem);
  sim.initialize();
  const EnergyFailure* energy = sim.energy_failure();
  ASSERT_NE(energy, nullptr);
  // m = 1.5 in 3D: n = (0,0,1), (±1,0,1), (0,±1,1): 5 crossing bonds, N_c = 10; τ = 2 Gc Δx² / N_c.
  EXPECT_EQ(energy->micropotentials(0), 10);
  const double tau = 2 * Gc * spacing * spacing / 10;
  EXPECT_DOUBLE_EQ(energy->threshold(0), tau);
  // PMB: t_ij = t_ji = ½ c e/ξ, so W = ∫ c e/ξ de = ½ c s² ξ and the bond breaks at
  // ½ c s_c² ξ V_i V_j = τ, s_c = √(2τ / (c ξ V²)), c = 18K/(πδ⁴).
  const double c = 18 * setup.problem.materials[0].elastic.bulk_modulus / (std::numbers::pi * std::pow(1.5 * spacing, 4));
  const double s_c = std::sqrt(2 * tau / (c * spacing * volume * volume));
  const double ds = s_c / 40.5;  // s_c between two steps: 40 steps below, the 41st above
  int broke_at = -1;
  for (int n = 1; n <= 60 && broke_at < 0; ++n) {
    set_stretch(sim, n * ds);
    sim.evaluate(1e-9, true);  // the check before the forces sees the work of the steps committed so far
    if (sim.bonds().broken[0]) {
      broke_at = n;
      break;
    }
    sim.commit(1e-9);
    const double s = n * ds;
    EXPECT_NEAR(energy->work()[0], 0.5 * c * s * s * spacing, 1e-9 * c * s * s * spacing) << n;  // exact
    EXPECT_EQ(energy->work()[0], energy->work()[1]);  // both directions, the same bits
  }
  // Step 41 took W over τ at its commit; step 42's check breaks both directions before its forces.
  EXPECT_EQ(broke_at, 42);
  EXPECT_TRUE(sim.bonds().broken[1]);
  EXPECT_EQ(sim.state().force(0, 0), 0);  // the broken bond carried no force in step 42
}

TEST(EnergyFailure, BreakBondsAtEquilibriumCountsTheStepSoFar) {
  // Simulation::break_bonds (dynamic relaxation, after an evaluation) adds the step's work to the committed
  // work: the bond breaks in the step whose stretch first reaches s_c.
  const double Gc = 50;
  TwoPoints setup("pmb", Gc);
  Simulation sim(setup.problem);
  sim.initialize();
  const double tau = sim.energy_failure()->threshold(0);
  const double c = 18 * setup.problem.materials[0].elastic.bulk_modulus / (std::numbers::pi * std::pow(1.5 * spacing, 4));
  const double s_c = std::sqrt(2 * tau / (c * spacing * volume * volume));
  const double ds = s_c / 40.5;
  int broke_at = -1;
  for (int n = 1; n <= 60; ++n) {
    set_stretch(sim, n * ds);
    sim.evaluate(0.0, false);
    if (sim.break_bonds() > 0) {
      broke_at = n;
      break;
    }
    sim.commit(0.0);
  }
  EXPECT_EQ(broke_at, 41);
  EXPECT_TRUE(sim.bonds().broken[0] && sim.bonds().broken[1]);
}

TEST(EnergyFailure, CompressionNeverBreaks) {
  TwoPoints setup("pmb", 1e-3);  // a tiny Gc: any tension would break the bond at once
  Simulation sim(setup.problem);
  sim.initialize();
  for (int n = 1; n <= 50; ++n) {
    set_stretch(sim, -1e-3 * n);
    sim.evaluate(1e-9, true);
    sim.commit(1e-9);
  }
  EXPECT_GT(sim.energy_failure()->work()[0] * volume * volume, 100 * sim.energy_failure()->threshold(0));
  EXPECT_FALSE(sim.bonds().broken[0]);
  EXPECT_EQ(sim.break_bonds(), 0u);
  set_stretch(sim, 1e-6);  // back in tension: the work stored in compression came back on the way
  sim.evaluate(1e-9, true);
  sim.commit(1e-9);
  sim.evaluate(1e-9, true);
  EXPECT_TRUE(sim.bonds().broken[0]);
}

/// A 2D plate of lps_viscoelastic sheared cyclically, u_x = γ(t) (y − y_c), γ a triangle 0 → γ_a → 0 per cycle
/// (20 steps of Δt = τ_b/10): the largest work of any bond at the end of each cycle and at the peak of the
/// first, and the cycle in which a bond first broke (0: none). Pure shear has no dilatation: the bonds' work is
/// deviatoric, where the model relaxes.
struct Cycles {
  std::vector<double> work_after;
  double peak_first = 0;
  int broke_in = 0;
};

Cycles shear_cycles(double relaxing_fraction, double Gc, int cycles) {
  testing::BlockSetup s;
  s.dimension = 2;
  s.model = "lps_viscoelastic";
  s.cells[0] = s.cells[1] = 10;
  s.parameters.set_number("relaxing_fraction", relaxing_fraction);
  s.parameters.set_number("relaxation_time", 10e-6);
  Problem p = testing::box_problem(s);
  p.materials[0].damage.enabled = true;
  p.materials[0].damage.fracture_energy = Gc;
  p.materials[0].damage.criterion = DamageCriterion::energy;
  Simulation sim(p);
  sim.initialize();
  const Discretization& disc = sim.discretization();
  const double dt = 1e-6, amplitude = 2e-3, centre = 5 * s.spacing;
  auto largest = [&] {
    const std::vector<double>& w = sim.energy_failure()->work();
    return *std::max_element(w.begin(), w.end());
  };
  auto any_broken = [&] { return std::count(sim.bonds().broken.begin(), sim.bonds().broken.end(), 1) > 0; };
  Cycles result;
  for (int k = 1; k <= cycles && result.broke_in == 0; ++k) {
    for (int n = 1; n <= 20; ++n) {
      const double gamma = amplitude * (n <= 10 ? n / 10.0 : (20 - n) / 10.0);
      for (std::size_t i = 0; i < disc.num_points(); ++i) sim.state().u(i, 0) = gamma * (disc.x(i, 1) - centre);
      sim.evaluate(dt, true);
      if (any_broken()) {
        result.broke_in = k;
        break;
      }
      sim.commit(dt);
      if (k == 1) result.peak_first = std::max(result.peak_first, largest());
    }
    result.work_after.push_back(largest());
  }
  return result;
}

TEST(EnergyFailure, ViscoelasticBondsAccumulateWorkUnderCyclesAndBreakLater) {
  // Nothing relaxes: each cycle gives its work back. Relaxing: each cycle dissipates, the work grows cycle
  // after cycle at the same amplitude, and a threshold above the first cycle's peak is reached in a later
  // cycle (a stretch criterion would break in the first cycle or never).
  const Cycles elastic = shear_cycles(0.0, 1e9, 3);
  for (double w : elastic.work_after) EXPECT_LT(std::abs(w), 1e-9 * elastic.peak_first);
  const Cycles relaxing = shear_cycles(0.6, 1e9, 6);
  ASSERT_GT(relaxing.work_after[0], 1e-3 * relaxing.peak_first);
  for (std::size_t k = 1; k < relaxing.work_after.size(); ++k) EXPECT_GT(relaxing.work_after[k], relaxing.work_after[k - 1]);
  // A threshold half as much again as the first cycle's peak, which the peaks of later cycles (the work
  // dissipated before them plus about one peak) reach: τ = 2 Gc A_c / N_c = target V², A_c = Δx h, N_c = 36,
  // V = Δx² h.
  const double h = spacing, V = spacing * spacing * h;
  const double target = 1.5 * relaxing.peak_first;
  const double Gc = target * V * V * 36 / (2 * spacing * h);
  const Cycles breaking = shear_cycles(0.6, Gc, 10);
  EXPECT_GE(breaking.broke_in, 2);
  EXPECT_LE(breaking.broke_in, 7);
  std::printf("work after each cycle / first peak:");
  for (double w : relaxing.work_after) std::printf(" %.4f", w / relaxing.peak_first);
  std::printf("; breaks in cycle %d\n", breaking.broke_in);
}

TEST(EnergyFailure, SameBitsForOneAndTwoThreads) {
  // A 2D LPS plate pulled apart by its end rows (prescribed u), energy criterion: work and broken flags.
  auto run = [](int threads) {
    omp_set_num_threads(threads);
    testing::BlockSetup s;
    s.dimension = 2;
    s.cells[0] = 24, s.cells[1] = 12;
    Problem p = testing::box_problem(s);
    p.materials[0].damage.enabled = true;
    p.materials[0].damage.fracture_energy = 200;
    p.materials[0].damage.criterion = DamageCriterion::energy;
    Simulation sim(p);
    sim.initialize();
    const Discretization& disc = sim.discretization();
    for (int n = 1; n <= 30; ++n) {
      for (std::size_t i = 0; i < disc.num_points(); ++i) {
        const double x = disc.x(i, 0), y = disc.x(i, 1);
        sim.state().u(i, 0) = 2e-4 * n * 1e-3 * std::sin(x / 7e-3) * (1 + y / 1e-2);
        sim.state().u(i, 1) = 1e-4 * n * 1e-3 * x / 2.4e-2;
      }
      sim.evaluate(1e-8, true);
      sim.commit(1e-8);
    }
    return std::make_pair(sim.energy_failure()->work(), sim.bonds().broken);
  };
  const auto one = run(1), two = run(2);
  omp_set_num_threads(1);
  std::size_t broken = 0;
  for (std::uint8_t b : one.second) broken += b;
  EXPECT_GT(broken, 0u);
  EXPECT_LT(broken, one.second.size());
  EXPECT_EQ(one.second, two.second);
  ASSERT_EQ(one.first.size(), two.first.size());
  EXPECT_EQ(0, std::memcmp(one.first.data(), two.first.data(), one.first.size() * sizeof(double)));
}

}  // namespace
}  // namespace peridot
