// lps_plastic (Mitchell's elastic-plastic ordinary state-based model), checked against closed forms:
//  - a whole family driven along one deviatoric direction (the single-bond demo of Mitchell, with a
//    family instead of a lone bond): load beyond yield, unload, reverse, step by step against the exact
//    solution of the return map, with and without hardening, for ω = 1 and ω = δ/ξ;
//  - uniaxial stress of a material point (the centre of a block under a homogeneous deformation whose
//    lateral strain is iterated until the lateral stress vanishes): yield at σ_y, hardening slope
//    E_t = EH/(E + H), elastic unloading with E, permanent strain and ε̄p as in classical J2;
//  - a pure volumetric strain never yields;
//  - a bar pulled slowly through the whole solver (grips, damping, free lateral faces): elastic slope,
//    yield, hardening, elastic unloading and permanent strain as in classical J2;
//  - a random loading history never dissipates a negative amount, and the work done equals stored
//    energy plus plastic work (second law and energy balance of the integrator).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <fmt/format.h>

#include "support/homogeneous.hpp"

namespace peridot {
namespace {

using testing::HomogeneousBlock;
using testing::Mat3;

constexpr double yield_stress = 250e6;

// ---------------------------------------------------------------------------------------------------
// Single family along one deviatoric direction.
//
// Each neighbour j of the centre moves along its bond by e_j = f ê_j, ê_j = ξ_j (n_j·D n_j) with D =
// diag(1, −1, 0): the extension is exactly f ê_j, θ = 0 by the cubic symmetry of the family, so e^d = e.
// The return map keeps e^dp = g ê_j, and the problem becomes one-dimensional in the scalar s = α N (f − g),
// N² = Σ ω² ê² V (‖t^d‖ = |s|), with yield |s| ≤ kσ_Y. The plastic work per unit Δg is |s| M/N,
// M = Σ ω ê² V, so ε̄p = (kM/N) Σ|Δg| and σ_Y = σ_y + H ε̄p is linear hardening of s with modulus
// H_s = k² H M/N against g. Exact solution (E1 = αN, s_y = kσ_y):
//   loading to f1:          g = max(0, (E1 f − s_y)/(E1 + H_s))
//   reversing from f1:      elastic until f = g1 − s_Y1/E1, then g = (E1 f + s_y + 2H_s g1)/(E1 + H_s)
// Backward Euler is exact for linear hardening along a straight path, so every step matches to round-off.
struct FamilyCase {
  const char* name;
  InfluenceKind influence;
  double hardening_ratio;  // H/E
};

class LpsPlasticFamily : public ::testing::TestWithParam<FamilyCase> {};

TEST_P(LpsPlasticFamily, ReturnMapMatchesClosedFormOverLoadUnloadReverse) {
  testing::BlockSetup s = HomogeneousBlock::setup("lps_plastic");
  s.influence = GetParam().influence;
  s.parameters.set_number("yield_stress", yield_stress);
  const double E = 9 * s.bulk_modulus * s.shear_modulus / (3 * s.bulk_modulus + s.shear_modulus);
  s.parameters.set_number("hardening_modulus", GetParam().hardening_ratio * E);
  HomogeneousBlock block(s);
  const Discretization& disc = block.sim().discretization();
  const BondList& bonds = block.sim().bonds();
  const MaterialParams& p = block.params();
  const LpsPlastic::Params& plastic = block.model_params<LpsPlastic>();
  const std::size_t c = block.centre();
  const MaterialHistory& history = block.sim().state().history;

  // The pattern ê of every bond of the centre, N and M.
  std::vector<double> pattern;
  std::vector<Vec3> direction;
  double N2 = 0, M = 0, moment = 0;  // moment = Σ ω² ξ² V, the yield calibration's sum
  for (std::uint64_t b = bonds.offsets[c]; b < bonds.offsets[c + 1]; ++b) {
    const std::uint32_t j = bonds.neighbors[b];
    const Vec3 xi = disc.x.get(j) - disc.x.get(c);
    const double length = norm(xi);
    const Vec3 n = (1 / length) * xi;
    pattern.push_back(length * (n.x * n.x - n.y * n.y));
    direction.push_back(n);
    const double omega = influence(p.influence, length, p.horizon);
    const double V = bond_loop::neighbor_volume(block.sim().model(), c, j, length);
    N2 += omega * omega * pattern.back() * pattern.back() * V;
    M += omega * pattern.back() * pattern.back() * V;
    moment += omega * omega * length * length * V;
  }
  const double N = std::sqrt(N2), alpha = plastic.alpha_deviatoric * block.sim().model().inverse_weighted_volume[c];
  const double k = std::sqrt(plastic.yield_calibration * moment) * block.sim().model().inverse_weighted_volume[c];
  const double H = plastic.hardening_modulus;
  const double E1 = alpha * N, s_y = k * yield_stress, Hs = k * k * H * M / N;
  const double f_y = s_y / E1, f1 = 3 * f_y;

  // The path: 0 → f1 → −f1 → back to zero force state, in steps of f_y/10.
  std::vector<double> path;
  for (int i = 1; i <= 30; ++i) path.push_back(f1 * i / 30);
  for (int i = 1; i <= 60; ++i) path.push_back(f1 - 2 * f1 * i / 60);
  const double g1 = (E1 * f1 - s_y) / (E1 + Hs);
  const double reverse_yield = g1 - (s_y + Hs * g1) / E1;
  const double g2 = (E1 * -f1 + s_y + 2 * Hs * g1) / (E1 + Hs);
  for (int i = 1; i <= 20; ++i) path.push_back(-f1 + (g2 + f1) * i / 20);  // unload elastically to s = 0

  double accumulated = 0, previous_g = 0, expected_work = 0, work_error_bound = 0;
  for (std::size_t step = 0; step < path.size(); ++step) {
    const double f = path[step];
    double g = 0;
    if (step < 30) g = std::max(0.0, (E1 * f - s_y) / (E1 + Hs));
    else if (step < 90) g = f >= reverse_yield ? g1 : (E1 * f + s_y + 2 * Hs * g1) / (E1 + Hs);
    else g = g2;
    const double increment = k * M / N * std::abs(g - previous_g);  // Δε̄p
    accumulated += std::abs(g - previous_g);
    previous_g = g;
    const double plastic_strain = k * M / N * accumulated;
    // Exact plastic work σ_y ε̄p + Hε̄p²/2; the integrator's backward-Euler sum differs by H Σ Δε̄p²/2.
    expected_work = yield_stress * plastic_strain + 0.5 * H * plastic_strain * plastic_strain;
    work_error_bound += 0.5 * H * increment * increment;

    VectorField u(disc.num_points());
    for (std::uint64_t b = bonds.offsets[c]; b < bonds.offsets[c + 1]; ++b) {
      const std::size_t q = b - bonds.offsets[c];
      const Vec3 displacement = (f * pattern[q]) * direction[q];
      u.set(bonds.neighbors[b], displacement);
    }
    block.apply(u);
    ASSERT_NEAR(block.sim().state().dilatation[c], 0.0, 1e-12 * f_y) << "step " << step;
    block.commit();

    double worst = 0;
    for (std::uint64_t b = bonds.offsets[c]; b < bonds.offsets[c + 1]; ++b)
      worst = std::max(worst, std::abs(history.bond[0][b] - g * pattern[b - bonds.offsets[c]]));
    ASSERT_LT(worst, 1e-9 * f_y * s.spacing) << "step " << step << ", f/f_y = " << f / f_y;
    ASSERT_NEAR(history.plastic_strain[c], plastic_strain, 1e-9 * f_y + 1e-9 * plastic_strain) << "step " << step;
    ASSERT_NEAR(history.dissipation[c], expected_work, work_error_bound + 1e-9 * expected_work + 1e-6)
        << "step " << step;
  }
  // The path did what it says: yielded both ways and left a permanent plastic extension.
  EXPECT_GT(g1, 1.5 * f_y * (H == 0 ? 1 : 0.5));
  EXPECT_LT(g2, -0.3 * f_y);
}

const FamilyCase family_cases[] = {
    {"PerfectPlasticity", InfluenceKind::constant, 0.0},
    {"Hardening", InfluenceKind::constant, 0.2},
    {"HardeningInverseDistance", InfluenceKind::inverse_distance, 0.2},
};
INSTANTIATE_TEST_SUITE_P(Cases, LpsPlasticFamily, ::testing::ValuesIn(family_cases),
                         [](const auto& info) { return std::string(info.param.name); });

// ---------------------------------------------------------------------------------------------------
// Uniaxial stress of a material point.

struct UniaxialPoint {
  double strain, stress, plastic_strain;
};

/// Drives the centre through the axial strains given, iterating the lateral strain (secant) until the
/// lateral stress is below 1e-9 σ_y, committing each converged step.
std::vector<UniaxialPoint> drive_uniaxial(HomogeneousBlock& block, const std::vector<double>& strains, double nu) {
  std::vector<UniaxialPoint> out;
  double lateral = 0;
  for (double axial : strains) {
    auto lateral_stress = [&](double l) {
      block.deform(testing::diagonal(1 + axial, 1 + l, 1 + l));
      return block.stress()[1][1];
    };
    double a = lateral, b = lateral - nu * (axial - (out.empty() ? 0.0 : out.back().strain)) - 1e-7;
    double fa = lateral_stress(a), fb = lateral_stress(b);
    for (int iteration = 0; iteration < 50 && std::abs(fb) > 1e-9 * yield_stress; ++iteration) {
      const double next = b - fb * (b - a) / (fb - fa);
      a = b, fa = fb;
      b = next, fb = lateral_stress(b);
    }
    EXPECT_LT(std::abs(fb), 1e-9 * yield_stress) << "lateral stress did not converge at axial strain " << axial;
    lateral = b;
    lateral_stress(lateral);
    const double stress = block.stress()[0][0];
    block.commit();
    out.push_back({axial, stress, block.sim().state().history.plastic_strain[block.centre()]});
  }
  return out;
}

TEST(LpsPlasticUniaxial, YieldHardeningUnloadingAndPermanentStrain) {
  testing::BlockSetup s = HomogeneousBlock::setup("lps_plastic");
  s.parameters.set_number("yield_stress", yield_stress);
  const double K = s.bulk_modulus, G = s.shear_modulus;
  const double E = 9 * K * G / (3 * K + G), nu = (3 * K - 2 * G) / (2 * (3 * K + G));
  s.parameters.set_number("hardening_modulus", 0.2 * E);
  const double H = s.parameters.number("hardening_modulus"), tangent = E * H / (E + H), yield_strain = yield_stress / E;
  HomogeneousBlock block(s);

  std::vector<double> strains;
  const int load_steps = 40;
  const double max_strain = 4 * yield_strain;
  for (int i = 1; i <= load_steps; ++i) strains.push_back(max_strain * i / load_steps);
  for (int i = 1; i <= 20; ++i) strains.push_back(max_strain - 1.5 * yield_strain * i / 20);  // unload
  const std::vector<UniaxialPoint> curve = drive_uniaxial(block, strains, nu);

  // Classical J2 with linear isotropic hardening in uniaxial stress (small strain).
  auto classical = [&](double strain) {
    return strain <= yield_strain ? E * strain : yield_stress + tangent * (strain - yield_strain);
  };
  // Elastic slope and the stress along the whole loading branch.
  EXPECT_NEAR(curve[4].stress / curve[4].strain, E, 0.01 * E) << "Young's modulus of the material point";
  for (int i = 0; i < load_steps; ++i)
    EXPECT_NEAR(curve[i].stress, classical(curve[i].strain), 0.03 * yield_stress) << "strain " << curve[i].strain;
  // Yield: the first step with plastic strain, and the stress extrapolated back to where it began.
  int first_plastic = 0;
  while (curve[first_plastic].plastic_strain == 0) ++first_plastic;
  const double onset_stress = curve[first_plastic].stress - tangent * curve[first_plastic].plastic_strain * E / H;
  EXPECT_NEAR(onset_stress, yield_stress, 0.03 * yield_stress) << "yield stress";
  EXPECT_NEAR(curve[first_plastic - 1].strain, yield_strain, max_strain / load_steps + 0.03 * yield_strain);
  // Hardening slope between two plastic states.
  const UniaxialPoint& a = curve[load_steps / 2];
  const UniaxialPoint& b = curve[load_steps - 1];
  EXPECT_NEAR((b.stress - a.stress) / (b.strain - a.strain), tangent, 0.03 * tangent) << "hardening slope";
  // Equivalent plastic strain = axial plastic strain ε − σ/E.
  EXPECT_NEAR(b.plastic_strain, b.strain - b.stress / E, 0.03 * b.plastic_strain) << "equivalent plastic strain";
  // Unloading is elastic with E (no new plastic strain), and the permanent strain is ε_max − σ_max/E.
  const UniaxialPoint& top = curve[load_steps - 1];
  const UniaxialPoint& end = curve.back();
  EXPECT_EQ(end.plastic_strain, top.plastic_strain) << "unloading must be elastic";
  const double unloading_modulus = (top.stress - end.stress) / (top.strain - end.strain);
  EXPECT_NEAR(unloading_modulus, E, 0.01 * E) << "unloading modulus";
  const double permanent = end.strain - end.stress / unloading_modulus;  // strain at zero stress
  const double expected_permanent = max_strain - classical(max_strain) / E;
  EXPECT_NEAR(permanent, expected_permanent, 0.03 * expected_permanent) << "permanent strain";
  std::printf("uniaxial stress, E = %.4g GPa (classical %.4g), onset of yield %.4g MPa (σ_y %.4g), hardening slope "
              "%.4g GPa (E_t %.4g), unloading modulus %.4g GPa, permanent strain %.4g (classical %.4g)\n",
              curve[4].stress / curve[4].strain / 1e9, E / 1e9, onset_stress / 1e6, yield_stress / 1e6,
              (b.stress - a.stress) / (b.strain - a.strain) / 1e9, tangent / 1e9, unloading_modulus / 1e9, permanent,
              expected_permanent);
}

// ---------------------------------------------------------------------------------------------------

TEST(LpsPlasticVolumetric, PureVolumetricStrainNeverYields) {
  testing::BlockSetup s = HomogeneousBlock::setup("lps_plastic");
  s.parameters.set_number("yield_stress", yield_stress);
  HomogeneousBlock block(s);
  const MaterialHistory& history = block.sim().state().history;
  const double yield_strain = yield_stress / 200e9;
  // Expansion and compression far beyond the yield strain: e^d = e − θξ/3 vanishes for every family,
  // surface families included (θ uses the same family as m), so no point leaves the elastic range.
  for (double strain : {10 * yield_strain, 30 * yield_strain, -30 * yield_strain}) {
    block.deform(testing::diagonal(1 + strain, 1 + strain, 1 + strain));
    block.commit();
    for (std::size_t i = 0; i < history.plastic_strain.size(); ++i) {
      ASSERT_EQ(history.plastic_strain[i], 0.0) << "point " << i << " at volumetric strain " << strain;
      ASSERT_EQ(history.dissipation[i], 0.0) << "point " << i;
    }
  }
  const Mat3 P = block.stress();  // and the stress is a pressure
  EXPECT_NEAR(P[0][1], 0.0, 1e-9 * std::abs(P[0][0]));
  EXPECT_NEAR(P[0][0], P[1][1], 1e-9 * std::abs(P[0][0]));
}

// ---------------------------------------------------------------------------------------------------

/// A seeded random walk of the deformation gradient (stretches and shears, steps of about `step`
/// strain); returns, for the centre, the work Σ ½(t_n + t_{n+1})(e_{n+1} − e_n)V done on its bonds,
/// its stored energy and its dissipation at the end; checks every point's dissipation never decreases.
struct WorkBalance {
  double work, stored, dissipated;
};

WorkBalance random_history(int steps, double step) {
  testing::BlockSetup s = HomogeneousBlock::setup("lps_plastic");
  s.parameters.set_number("yield_stress", yield_stress);
  s.parameters.set_number("hardening_modulus", 20e9);
  HomogeneousBlock block(s);
  const std::size_t c = block.centre();
  const BondList& bonds = block.sim().bonds();
  const std::size_t family = bonds.offsets[c + 1] - bonds.offsets[c];
  std::vector<double> t_old(family, 0.0), e_old(family, 0.0);
  std::vector<double> before = block.sim().state().history.dissipation;
  Mat3 F = testing::diagonal(1, 1, 1);
  std::uint64_t seed = 2024;
  double work = 0;
  // The walk has a fixed seed, and the direction of each increment is drawn per substep so that halving
  // `step` with twice the steps follows nearly the same path.
  Mat3 direction{};
  for (int n = 0; n < steps; ++n) {
    if (n % (steps / 50) == 0)
      for (auto& row : direction)
        for (double& value : row) value = 2 * uniform01(seed) - 1;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) F[a][b] += step * direction[a][b];
    block.deform(F);
    block.commit();
    block.for_each_bond(c, [&](std::uint64_t b, double t, const bond_loop::BondGeometry<3>& g, double V) {
      const std::size_t q = b - bonds.offsets[c];
      work += 0.5 * (t_old[q] + t) * (g.e - e_old[q]) * V;
      t_old[q] = t;
      e_old[q] = g.e;
    });
    const std::vector<double>& now = block.sim().state().history.dissipation;
    for (std::size_t i = 0; i < now.size(); ++i) EXPECT_GE(now[i], before[i]) << "point " << i << " step " << n;
    before = now;
  }
  std::vector<double> W;
  const State& state = block.sim().state();
  compute_strain_energy_density(block.sim().model(), block.displacement(), state.dilatation, W, &state.history);
  return {work, W[c], state.history.dissipation[c]};
}

TEST(LpsPlasticDissipation, RandomLoadingNeverDissipatesNegativelyAndBalancesWork) {
  const WorkBalance coarse = random_history(100, 2e-4);
  const WorkBalance fine = random_history(200, 1e-4);
  ASSERT_GT(coarse.dissipated, 0.5 * coarse.stored) << "the walk should be well into the plastic range";
  const double coarse_error = std::abs(coarse.work - coarse.stored - coarse.dissipated);
  const double fine_error = std::abs(fine.work - fine.stored - fine.dissipated);
  // Work = stored energy + plastic work, to the order of the integrators (trapezoid for the work, backward
  // Euler for the return map): measured 0.98 % of the work at strain steps of 2e-4 and 0.36 % at 1e-4, so
  // the bounds are 1.5 % and 0.5 %, and the mismatch must shrink with the step.
  EXPECT_LT(coarse_error, 0.015 * coarse.work);
  EXPECT_LT(fine_error, 0.005 * fine.work);
  EXPECT_LT(fine_error, 0.7 * coarse_error);
  std::printf("random walk: work %.6g J/m^3, stored %.6g, plastic %.6g; mismatch %.3g (step 2e-4), %.3g (step 1e-4)\n",
              coarse.work, coarse.stored, coarse.dissipated, coarse_error / coarse.work, fine_error / fine.work);
}


// ---------------------------------------------------------------------------------------------------
// A bar pulled slowly through the whole solver: grips of two layers at each end, the right grip's axial
// displacement prescribed (loaded, then unloaded), lateral faces free, mass damping to stay quasi-static.
// Stress = the axial force the left half transmits to the right half, −Σ_{x_i > L/2} f_i V_i (the bonds
// within the right half cancel pairwise), over the cross-section: exact at every instant, free of the
// damping and inertia forces that the grip reaction includes. Strain = stretch of the gauge between two
// lattice planes near L/4 and 3L/4 (mean axial displacements); ε̄p = mean over the mid cross-section.
struct BarPoint {
  double strain, stress, plastic_strain;
};

std::vector<BarPoint> pull_bar(const testing::BlockSetup& s, double max_strain, double end_strain, int steps) {
  Problem problem = testing::box_problem(s);
  const double L = s.cells[0] * s.spacing, grip = 2 * s.spacing;
  NodeSetSpec left, right;
  left.name = "left";
  left.shape = testing::box_shape({-1, -1, -1}, {grip, 1, 1});
  right.name = "right";
  right.shape = testing::box_shape({L - grip, -1, -1}, {1, 1, 1});
  problem.node_sets = {left, right};
  const double dt = 0.8 * Simulation(problem).stable_time_step();
  problem.solver.parameters.set_number("time_step", dt);
  problem.solver.parameters.set_integer("num_steps", steps);
  // Axial grip displacement: up to max_strain over the first 3/4 of the run, then back to end_strain.
  const double T1 = 0.75 * steps * dt, T2 = steps * dt, span = L - grip;
  const std::string ramp = fmt::format("(t <= {0:.17g} ? t / {0:.17g} * {2:.17g} : {2:.17g} - (t - {0:.17g}) / {1:.17g} * {3:.17g})",
                                       T1, T2 - T1, max_strain * span, (max_strain - end_strain) * span);
  BoundaryConditionSpec hold, pull;
  hold.node_set = "left";
  hold.component = 0;
  hold.value = {"0", {}, false};
  pull.node_set = "right";
  pull.component = 0;
  pull.value = {ramp, {}, true};
  problem.boundary_conditions = {hold, pull};
  // Damping near the bar's first axial frequency π c/L, so that the loading stays quasi-static.
  const double E = 9 * s.bulk_modulus * s.shear_modulus / (3 * s.bulk_modulus + s.shear_modulus);
  problem.solver.parameters.set_number("damping", std::numbers::pi * std::sqrt(E / s.density) / L);
  Simulation sim(problem);
  sim.initialize();
  const Discretization& disc = sim.discretization();
  // Lattice planes x = (k + ½)Δx.
  auto plane = [&](double fraction) { return (std::floor(fraction * s.cells[0]) + 0.5) * s.spacing; };
  std::vector<std::size_t> near, far, middle;
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    if (std::abs(disc.x(i, 0) - plane(0.25)) < 0.25 * s.spacing) near.push_back(i);
    if (std::abs(disc.x(i, 0) - plane(0.75)) < 0.25 * s.spacing) far.push_back(i);
    if (std::abs(disc.x(i, 0) - plane(0.5)) < 0.25 * s.spacing) middle.push_back(i);
  }
  EXPECT_EQ(near.size(), static_cast<std::size_t>(s.cells[1] * s.cells[2]));
  auto mean = [&](const std::vector<std::size_t>& set, auto value) {
    double sum = 0;
    for (std::size_t i : set) sum += value(i);
    return sum / static_cast<double>(set.size());
  };
  const double gauge = plane(0.75) - plane(0.25);
  const double area = s.cells[1] * s.cells[2] * s.spacing * s.spacing;
  std::vector<BarPoint> out;
  const State& state = sim.state();
  for (int n = 1; n <= steps; ++n) {
    sim.step();
    if (n % 25 != 0) continue;
    double transmitted = 0;
    for (std::size_t i = 0; i < disc.num_points(); ++i)
      if (disc.x(i, 0) > 0.5 * L) transmitted -= state.force(i, 0) * disc.volume[i];
    const double strain = (mean(far, [&](std::size_t i) { return state.u(i, 0); }) -
                           mean(near, [&](std::size_t i) { return state.u(i, 0); })) / gauge;
    out.push_back({strain, transmitted / area, mean(middle, [&](std::size_t i) { return state.history.plastic_strain[i]; })});
  }
  return out;
}

// 30 × 10 × 10 points, δ = 3.015Δx, 3000 steps (about 70 s on one core): measured elastic slope 1.003 E,
// yield point (bilinear fit) 1.004 σ_y, hardening slope 1.015 E_t, unloading slope 1.007 E, zero-stress
// strain after unloading 0.5 % above the classical permanent strain.
TEST(LpsPlasticBar, QuasiStaticTensionThroughTheSolver) {
  testing::BlockSetup s;
  s.model = "lps_plastic";
  s.cells[0] = 30, s.cells[1] = s.cells[2] = 10;
  s.parameters.set_number("yield_stress", yield_stress);
  const double K = s.bulk_modulus, G = s.shear_modulus, E = 9 * K * G / (3 * K + G);
  s.parameters.set_number("hardening_modulus", 0.2 * E);
  const double H = s.parameters.number("hardening_modulus"), tangent = E * H / (E + H), yield_strain = yield_stress / E;
  const std::vector<BarPoint> curve = pull_bar(s, 4 * yield_strain, 2 * yield_strain, 3000);
  const std::size_t peak = std::max_element(curve.begin(), curve.end(), [](auto& a, auto& b) { return a.strain < b.strain; }) - curve.begin();
  auto slope = [&](std::size_t a, std::size_t b) { return (curve[b].stress - curve[a].stress) / (curve[b].strain - curve[a].strain); };
  auto at_strain = [&](double strain, std::size_t from, std::size_t to) {  // first sample at or beyond strain
    for (std::size_t k = from; k < to; ++k)
      if (curve[k].strain >= strain) return k;
    return to - 1;
  };
  // Elastic loading between 0.2 and 0.8 ε_y.
  EXPECT_NEAR(slope(at_strain(0.2 * yield_strain, 0, peak), at_strain(0.8 * yield_strain, 0, peak)), E, 0.02 * E)
      << "elastic slope";
  // Yield point: the intersection of the elastic line and the hardening line (bilinear fit), since surface
  // points of the section, whose families are one-sided, start to yield earlier (at 0.87 σ_y).
  const double elastic = slope(at_strain(0.2 * yield_strain, 0, peak), at_strain(0.8 * yield_strain, 0, peak));
  const std::size_t a = at_strain(2 * yield_strain, 0, peak);
  const double hardening = slope(a, peak);
  const double yield_point = elastic * (curve[a].stress - hardening * curve[a].strain) / (elastic - hardening);
  EXPECT_NEAR(yield_point, yield_stress, 0.03 * yield_stress) << "yield point of the bilinear fit";
  EXPECT_NEAR(hardening, tangent, 0.03 * tangent) << "hardening slope";
  std::size_t onset = 0;
  while (onset < peak && curve[onset].plastic_strain == 0) ++onset;
  EXPECT_GT(curve[onset].stress, 0.8 * yield_stress) << "first yield in the mid-section (a surface point)";
  // Plastic strain at the peak: ε − σ/E.
  const BarPoint& top = curve[peak];
  EXPECT_NEAR(top.plastic_strain, top.strain - top.stress / E, 0.03 * top.plastic_strain) << "plastic strain at the peak";
  // Unloading: elastic with E, and the strain at zero stress is the permanent strain of classical J2.
  const std::size_t early = std::min(peak + 2, curve.size() - 1), last = curve.size() - 1;
  EXPECT_NEAR(slope(early, last), E, 0.02 * E) << "unloading slope";
  EXPECT_EQ(curve[last].plastic_strain, curve[early].plastic_strain) << "unloading must stay elastic";
  const double zero_stress_strain = curve[last].strain - curve[last].stress / slope(early, last);
  const double classical_peak_stress = yield_stress + tangent * (top.strain - yield_strain);
  const double permanent = top.strain - classical_peak_stress / E;
  EXPECT_NEAR(zero_stress_strain, permanent, 0.03 * permanent) << "permanent strain";
  std::printf("bar: elastic slope %.4g E, yield point %.4g σ_y (first surface yield %.4g σ_y), hardening slope "
              "%.4g E_t, unloading %.4g E, permanent strain %.4g (classical %.4g)\n",
              elastic / E, yield_point / yield_stress, curve[onset].stress / yield_stress, hardening / tangent,
              slope(early, last) / E, zero_stress_strain, permanent);
}

}  // namespace
}  // namespace peridot
