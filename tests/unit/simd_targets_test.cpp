// The bond loops compiled for each SIMD target this CPU runs (core/simd.hpp) against each other: every
// model's force on an irregular, displaced body agrees to round-off between targets, and each target gives
// the same bits with 1 and 2 threads.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "peridot/core/simd.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/solvers/simulation.hpp"
#include "support/problems.hpp"

namespace peridot {
namespace {

struct Case {
  std::string model;
  int dimension;
  InfluenceKind influence;
  double yield_stress = 1e12;  ///< lps_plastic: 1e12 stays elastic, 1e5 yields (asserted)
  int committed_steps = 0;     ///< steps committed before the force compared (history that is not zero)
};

std::vector<Case> cases() {
  std::vector<Case> list;
  for (InfluenceKind k : {InfluenceKind::constant, InfluenceKind::inverse_distance, InfluenceKind::gaussian})
    for (int dim : {2, 3}) list.push_back({"pmb", dim, k}), list.push_back({"lps", dim, k});
  for (const char* m : {"lps_plastic", "lps_viscoelastic", "thermoviscoelastic"}) list.push_back({m, 3, InfluenceKind::constant});
  // The inelastic models' vector loops read the history of the bond and of its partner bond, and their
  // return map: with history that is not zero, yielding, and every influence function.
  for (InfluenceKind k : {InfluenceKind::constant, InfluenceKind::inverse_distance, InfluenceKind::gaussian})
    for (int dim : {2, 3}) {
      list.push_back({"lps_plastic", dim, k, 1e5, 2});
      list.push_back({"lps_viscoelastic", dim, k, 1e12, 2});
    }
  list.push_back({"correspondence", 3, InfluenceKind::constant});  // hypoelastic law, hourglass control
  return list;
}

/// The force density after one evaluation at a random displacement of 1e-3 strain (after `committed_steps`
/// steps, growing by half each), with `threads` threads; then the dissipation density, if any.
std::vector<double> force_of(const Case& c, int threads) {
  testing::BlockSetup s;
  s.model = c.model;
  s.dimension = c.dimension;
  s.influence = c.influence;
  s.jitter = 0.1;
  if (c.dimension == 3) s.cells[0] = s.cells[1] = s.cells[2] = 8;
  else s.cells[0] = s.cells[1] = 14;
  s.parameters.set_number("yield_stress", c.yield_stress);  // each model takes the keys it has
  s.parameters.set_number("relaxing_fraction", 0.5);
  s.parameters.set_number("relaxation_time", 1e-5);
  if (c.model == "correspondence") s.parameters.set_text("constitutive_law", "hypoelastic");
  if (c.model == "thermoviscoelastic")
    s.parameters.set_number("prony_series[0].shear_modulus", 20e9), s.parameters.set_number("prony_series[0].relaxation_time", 1e-5);
  Simulation sim(testing::box_problem(s));
  std::uint64_t seed = 12345;
  VectorField& u = sim.state().u;
  for (std::size_t i = 0; i < sim.discretization().num_points(); ++i)
    for (int d = 0; d < c.dimension; ++d) u(i, d) = 1e-6 * (2 * uniform01(seed) - 1);
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  for (int step = 0; step < c.committed_steps; ++step) {
    sim.evaluate(1e-8, false);
    sim.commit(1e-8);
    for (std::size_t i = 0; i < sim.discretization().num_points(); ++i)
      for (int d = 0; d < c.dimension; ++d) u(i, d) *= 1.5;  // the next step deforms further
  }
  sim.evaluate(1e-8, false);
  omp_set_num_threads(before);
  if (c.yield_stress < 1e12) {
    const std::vector<double>& plastic = sim.state().history.plastic_strain;
    EXPECT_GT(*std::max_element(plastic.begin(), plastic.end()), 0) << c.model << ": nothing yielded";
  }
  const VectorField& f = sim.state().force;
  std::vector<double> out(f.data(), f.data() + 3 * f.size());
  // The committed steps' dissipation per point after the force (the commit loops are vectorised too),
  // scaled to the force's size so that one tolerance covers both.
  const std::vector<double>& dissipation = sim.state().history.dissipation;
  double force_scale = 0, dissipation_scale = 0;
  for (double v : out) force_scale = std::max(force_scale, std::abs(v));
  for (double v : dissipation) dissipation_scale = std::max(dissipation_scale, std::abs(v));
  if (dissipation_scale > 0)
    for (double v : dissipation) out.push_back(v * force_scale / dissipation_scale);
  return out;
}

std::string name_of(const Case& c) {
  return c.model + " " + std::to_string(c.dimension) + "D influence " + std::to_string(static_cast<int>(c.influence)) +
         (c.committed_steps > 0 ? " after " + std::to_string(c.committed_steps) + " steps" : "") +
         (c.yield_stress < 1e12 ? " yielding" : "");
}

TEST(SimdTargets, EveryModelsForceAgreesBetweenTargetsAndIsThreadIndependent) {
  const std::vector<std::string>& targets = simd::available_targets();
  ASSERT_FALSE(targets.empty());
  for (const Case& c : cases()) {
    std::vector<double> reference;
    double worst = 0;
    for (const std::string& target : targets) {
      simd::force_target(target);
      ASSERT_EQ(simd::active_target(), target);
      const std::vector<double> one = force_of(c, 1), two = force_of(c, 2);
      EXPECT_EQ(one, two) << name_of(c) << ": target " << target << " depends on the thread count";
      if (reference.empty()) {
        reference = one;
        continue;
      }
      double scale = 0;
      for (double v : reference) scale = std::max(scale, std::abs(v));
      ASSERT_GT(scale, 0) << name_of(c);
      for (std::size_t k = 0; k < one.size(); ++k) worst = std::max(worst, std::abs(one[k] - reference[k]) / scale);
    }
    // The targets differ at round-off only (the AVX-512 loops take |ξ| and |Y| from a 1/√x estimate).
    EXPECT_LT(worst, 1e-11) << name_of(c) << ": targets " << targets.front() << " and the others differ";
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", worst);
    RecordProperty(name_of(c), text);
  }
  simd::force_target("");
}

TEST(SimdTargets, AnUnknownTargetIsRefusedWithTheAvailableOnes) {
  try {
    simd::force_target("avx4096");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(simd::available_targets().front()), std::string::npos) << e.what();
  }
  EXPECT_EQ(simd::active_target(), simd::available_targets().front());
}

}  // namespace
}  // namespace peridot
