// Tractions carried by a layer of points (deck `tractions`), and the fictitious boundary layers of Madenci &
// Oterkus: a plate extended by a constrained layer of depth δ beyond its left edge and a one-row traction layer
// beyond its right edge, in equilibrium (relaxation), stretches by σ/E in its middle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "peridot/deck/deck.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {
namespace {

// A 2D plane-stress LPS plate [0, 40] × [0, 12] mm (Δx = 1 mm, δ = 3.015Δx) with the surface correction, and its
// fictitious layers: x < 0 (three rows, held in x; one point held in y) and x > 40 mm (one row, the traction).
std::string plate_deck(const std::string& traction) {
  return R"(discretization: {dimension: 2, plane: stress, thickness: 1 mm, spacing: 1 mm, horizon_factor: 3.015}
materials:
  steel: {model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3, surface_correction: true}
bodies:
  plate: {material: steel, shape: {box: {min: [-0.003, 0], max: [0.041, 0.012]}}}
node_sets:
  held: {shape: {box: {min: [-1, -1], max: [0, 1]}}}
  pin: {shape: {box: {min: [-1, 0.0055], max: [0, 0.0065]}}}
  loaded: {shape: {box: {min: [0.04, -1], max: [1, 1]}}}
boundary_conditions:
  - {node_set: held, displacement: {x: "0"}}
  - {node_set: pin, displacement: {y: "0"}}
tractions:
  - )" + traction + R"(
solver: {type: relaxation, load_steps: 1, ramp: false, tolerance: 1e-9}
output: {progress: false}
)";
}

TEST(Tractions, ParseWithTheSpacingAsDefaultDepthAndRoundTrip) {
  const Problem p = parse_deck(plate_deck(R"({node_set: loaded, x: "10e6"})"), "<test>", ".");
  ASSERT_EQ(p.tractions.size(), 1u);
  EXPECT_EQ(p.tractions[0].node_set, "loaded");
  EXPECT_DOUBLE_EQ(p.tractions[0].depth, 1e-3);
  EXPECT_TRUE(p.tractions[0].component[0]);
  EXPECT_FALSE(p.tractions[0].component[1]);
  const Problem again = parse_deck(resolved_deck_yaml(p), "<resolved>", ".");
  ASSERT_EQ(again.tractions.size(), 1u);
  EXPECT_DOUBLE_EQ(again.tractions[0].depth, 1e-3);
  EXPECT_EQ(again.tractions[0].component[0]->text, p.tractions[0].component[0]->text);
  const Problem deeper = parse_deck(plate_deck(R"({node_set: loaded, depth: 2 mm, y: "1e6 * t"})"), "<test>", ".");
  EXPECT_DOUBLE_EQ(deeper.tractions[0].depth, 2e-3);
  EXPECT_TRUE(deeper.tractions[0].component[1]->depends_on_time);
}

TEST(Tractions, RefuseALayerWithoutNodeSetOrComponents) {
  EXPECT_THROW(parse_deck(plate_deck(R"({x: "1"})"), "<test>", "."), InputError);
  EXPECT_THROW(parse_deck(plate_deck(R"({node_set: loaded})"), "<test>", "."), InputError);
  EXPECT_THROW(parse_deck(plate_deck(R"({node_set: loaded, depth: -1 mm, x: "1"})"), "<test>", "."), InputError);
}

// Each point of the layer gets t/d, so the layer carries t times the area of the loaded surface.
TEST(Tractions, LayerCarriesTractionTimesArea) {
  const double sigma = 10e6;
  Simulation sim(parse_deck(plate_deck(R"({node_set: loaded, x: "10e6"})"), "<test>", "."));
  sim.apply_initial_state();
  const Discretization& disc = sim.discretization();
  double force = 0;
  int layer = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    if (disc.x(i, 0) > 0.04) {
      EXPECT_DOUBLE_EQ(sim.state().body_force(i, 0), sigma / 1e-3);
      force += sim.state().body_force(i, 0) * disc.volume[i];
      ++layer;
    }
  EXPECT_EQ(layer, 12);
  EXPECT_NEAR(force, sigma * 0.012 * 1e-3, 1e-9 * sigma * 0.012 * 1e-3);  // σ × W × h
}

// Equilibrium with the layers: the held layer's reaction balances the traction's resultant σ W h, and the strain of
// the plate's middle third is σ/E (plane stress) within 3 %: lps's deviatoric sum keeps the lattice's anisotropy
// (at δ = 3.015Δx a plate in tension is 2–3 % stiff; docs/algorithms.md §13, §15).
TEST(Tractions, FictitiousLayersCarryTheLoadAndStretchThePlateBySigmaOverE) {
  const double sigma = 10e6, E = 200e9, resultant = sigma * 0.012 * 1e-3;
  Simulation sim(parse_deck(plate_deck(R"({node_set: loaded, x: "10e6"})"), "<test>", "."));
  sim.initialize();
  while (sim.state().step < sim.total_steps()) sim.step();
  const Discretization& disc = sim.discretization();
  for (const NodeSet& set : sim.node_sets())
    if (set.name == "held") EXPECT_NEAR(sim.reaction(set.name).x, -resultant, 1e-4 * resultant);
  // The least-squares slope of u_x against x over the points with 13 mm < x < 27 mm.
  double n = 0, sx = 0, su = 0, sxx = 0, sxu = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    const double x = disc.x(i, 0), u = sim.state().u(i, 0);
    if (x < 0.013 || x > 0.027) continue;
    n += 1, sx += x, su += u, sxx += x * x, sxu += x * u;
  }
  const double strain = (n * sxu - sx * su) / (n * sxx - sx * sx);
  std::printf("plate with fictitious layers: mid strain / (σ/E) = %.4f\n", strain * E / sigma);
  EXPECT_NEAR(strain, sigma / E, 0.03 * sigma / E);
}

}  // namespace
}  // namespace peridot
