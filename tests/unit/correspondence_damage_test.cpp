// Johnson–Cook damage in the correspondence model (correspondence/johnson_cook_damage.hpp):
//  - the J2 law accumulates it too: D = εp/εf at the triaxiality of uniaxial tension;
//  - influence-function coupling, in a double-notched bar pulled apart (tests/regression/decks/jc_damage_small.yaml):
//    at every output a bond is broken exactly when an end has failed (D = 1, neither end protected by no_fail),
//    a failed point has lost every bond and carries no stress, broken bonds never heal, and the bar breaks;
//  - the same bar cut free with a non-uniform initial velocity: linear momentum is conserved to round-off while
//    bonds break, and kinetic + elastic + dissipated (plastic work and the elastic energy released by failed
//    points) + hourglass work stays the initial kinetic energy;
//  - local-stress coupling: no bond breaks, and a point at D = 1 carries no stress;
//  - the deck: a critical-stretch `damage` on a correspondence material is refused and points to
//    johnson_cook_damage; johnson_cook_damage on the hypoelastic law is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "peridot/correspondence/j2_viscoplastic.hpp"
#include "peridot/correspondence/material_point_driver.hpp"
#include "peridot/deck/deck.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {
namespace {

using namespace correspondence;

std::string small_bar() {
  std::ifstream in(std::string(PERIDOT_SOURCE_DIR) + "/tests/regression/decks/jc_damage_small.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string deck = text.str();
  EXPECT_FALSE(deck.empty());
  return std::regex_replace(deck, std::regex(R"(output:[\s\S]*$)"), "output: {progress: false}\n");
}

TEST(JohnsonCookDamage, TheJ2LawAccumulatesItToo) {
  J2Viscoplastic law = J2Viscoplastic::aluminium_6061_t6();
  law.rate_exponent = std::numeric_limits<double>::infinity();  // εf has no rate term here (D4 = 0) either way
  law.damage = {.enabled = true, .d1 = -0.77, .d2 = 1.45, .d3 = -0.47, .d4 = 0, .d5 = 0};
  UniaxialStressOptions options;
  options.true_strain_rate = 1.0;
  options.dt = 1e-4;
  options.num_steps = 6000;
  const auto samples = run_uniaxial_stress(law, options);
  const double failure = law.damage.failure_strain(1.0 / 3, 0, 0);
  double worst = 0;
  for (const auto& s : samples)
    if (s.history.damage < 1) worst = std::max(worst, std::abs(s.history.damage - s.history.equivalent_plastic_strain / failure));
  std::printf("J2 with JC damage, uniaxial tension: εf %.4f, |D − εp/εf| ≤ %.2e, final εp %.4f, D %.4f\n", failure,
              worst, samples.back().history.equivalent_plastic_strain, samples.back().history.damage);
  EXPECT_LT(worst, 1e-9);
  EXPECT_EQ(samples.back().history.damage, 1.0);  // εp ≈ 0.6 > εf ≈ 0.47: capped at 1
}

/// Runs `deck` to its end, calling check(sim) after every `every` steps (outputs gathered).
template <class Check>
void run_checking(Simulation& sim, int every, Check check) {
  sim.initialize();
  while (sim.state().step < sim.total_steps()) {
    sim.step();
    if (sim.state().step % every == 0 || sim.state().step == sim.total_steps()) {
      sim.prepare_outputs(true, true);
      check(sim);
    }
  }
}

TEST(JohnsonCookDamage, BondsBreakExactlyAtFailedPointsAndTheBarBreaks) {
  Simulation sim(parse_deck(small_bar(), "jc.yaml", "."));
  const BondList& bonds = sim.bonds();
  const std::vector<std::uint8_t>& no_fail = sim.model().no_fail;
  std::vector<std::uint8_t> was_broken(bonds.num_bonds(), 0);
  std::size_t mismatches = 0, healed = 0, stressed_failures = 0, failed = 0;
  run_checking(sim, 50, [&](Simulation& s) {
    const State& state = s.state();
    const std::vector<double>& D = state.point_outputs.at("material_damage");
    const std::vector<double>& vm = state.point_outputs.at("von_mises_stress");
    failed = 0;
    for (std::size_t i = 0; i < s.num_owned(); ++i) {
      const bool failed_i = D[i] >= 1 && !no_fail[i];
      failed += failed_i;
      if (failed_i && (vm[i] != 0 || state.damage[i] != 1)) ++stressed_failures;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::size_t j = bonds.neighbors[b];
        const bool protect = no_fail[i] || no_fail[j];
        const bool should = !protect && std::max(D[i], D[j]) >= 1;
        mismatches += (bonds.broken[b] != 0) != should;
        healed += was_broken[b] && !bonds.broken[b];
        was_broken[b] = bonds.broken[b];
      }
    }
  });
  const Totals t = sim.totals();
  std::printf("JC damage bar: %zu failed points, broken fraction %.4f, %zu fragments; bond/damage mismatches %zu, "
              "healed %zu, failed points with stress or bonds %zu\n",
              failed, t.broken_fraction, t.fragments, mismatches, healed, stressed_failures);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(healed, 0u);
  EXPECT_EQ(stressed_failures, 0u);
  EXPECT_GT(failed, 20u);  // the net section (6 × 4 × … points) has failed through
  EXPECT_GT(t.broken_fraction, 0.03);
}

TEST(JohnsonCookDamage, MomentumIsConservedAndEnergyBalancesWhileBondsBreak) {
  std::string deck = small_bar();
  // Cut free: no grips, no supports; its halves thrown apart at ±150 m/s, off-centre so that p ≠ 0.
  deck = std::regex_replace(deck, std::regex(R"(no_fail:.*\n)"), "");
  deck = std::regex_replace(deck, std::regex(R"(boundary_conditions:\n(  - .*\n)+)"),
                            "initial_conditions:\n  - {velocity: {x: \"7 + (x > 0 ? 150 : -150)\", y: \"-3 + 400*z\"}}\n");
  Simulation sim(parse_deck(deck, "jc_free.yaml", "."));
  sim.initialize();
  const Totals start = sim.totals();
  double worst_momentum = 0, worst_energy = 0;
  const double scale = std::sqrt(start.momentum.x * start.momentum.x + start.momentum.y * start.momentum.y);
  run_checking(sim, 50, [&](Simulation& s) {
    const Totals t = s.output_totals();
    for (int d = 0; d < 3; ++d) worst_momentum = std::max(worst_momentum, std::abs(t.momentum[d] - start.momentum[d]) / scale);
    const double balance = t.kinetic_energy + t.strain_energy + t.dissipated_energy + t.hourglass_work;
    worst_energy = std::max(worst_energy, std::abs(balance / start.kinetic_energy - 1));
  });
  const Totals end = sim.totals();
  std::printf("JC damage, free bar: broken fraction %.4f, dissipated %.3f of the initial kinetic energy; "
              "|Δp|/|p0| ≤ %.2e, energy balance within %.2e of it\n",
              end.broken_fraction, end.dissipated_energy / start.kinetic_energy, worst_momentum, worst_energy);
  EXPECT_GT(end.broken_fraction, 0.01);
  EXPECT_LT(worst_momentum, 1e-12);
  EXPECT_LT(worst_energy, 0.02);
}

TEST(JohnsonCookDamage, LocalStressCouplingBreaksNoBondAndAFailedPointCarriesNoStress) {
  std::string deck = small_bar();
  deck = std::regex_replace(deck, std::regex(R"(d5: 1.6\})"), "d5: 1.6, coupling: local_stress}");
  Simulation sim(parse_deck(deck, "jc_local.yaml", "."));
  std::size_t failed = 0, stressed = 0;
  run_checking(sim, 100, [&](Simulation& s) {
    const State& state = s.state();
    const std::vector<double>& D = state.point_outputs.at("material_damage");
    const std::vector<double>& vm = state.point_outputs.at("von_mises_stress");
    failed = 0;
    for (std::size_t i = 0; i < s.num_owned(); ++i)
      if (D[i] >= 1) failed += 1, stressed += vm[i] != 0;
  });
  const Totals t = sim.totals();
  std::printf("JC damage, local stress: %zu points at D = 1, broken fraction %g\n", failed, t.broken_fraction);
  EXPECT_GT(failed, 0u);
  EXPECT_EQ(stressed, 0u);
  EXPECT_EQ(t.broken_fraction, 0.0);
}

TEST(JohnsonCookDamage, DeckRefusesBondDamageOnCorrespondenceAndDamageOnTheHypoelasticLaw) {
  auto errors_of = [](const std::string& deck) {
    std::string all;
    try {
      Simulation sim(parse_deck(deck, "bad.yaml", "."));
    } catch (const InputError& e) {
      for (const Diagnostic& d : e.diagnostics()) all += d.str() + "\n";
    }
    return all;
  };
  std::string deck = small_bar();
  std::string stretch = std::regex_replace(deck, std::regex(R"(    johnson_cook_damage:.*\n)"),
                                           "    damage: {critical_stretch: 0.01}\n");
  std::string message = errors_of(stretch);
  EXPECT_NE(message.find("johnson_cook_damage"), std::string::npos) << message;
  EXPECT_NE(message.find("bad.yaml:"), std::string::npos) << message;
  std::string hypoelastic = std::regex_replace(deck, std::regex(R"(constitutive_law: johnson_cook)"), "constitutive_law: hypoelastic");
  message = errors_of(hypoelastic);
  EXPECT_NE(message.find("johnson_cook_damage is a parameter of constitutive_law: j2_viscoplastic, not of hypoelastic"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace peridot
