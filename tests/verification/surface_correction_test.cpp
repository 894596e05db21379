// The surface correction (energy method, solvers/surface_correction.hpp): the bond factors are the ellipsoid
// interpolation of the ends' mean factors g_d = W_classical / W_d, and the corrected points' energies under the
// three uniaxial strains come close to the classical ones where the uncorrected ones are far off. The bar wave
// speed (dynamics_test.cpp) and the model invariants with the correction (model_invariants_test.cpp) are elsewhere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>

#include "peridot/solvers/simulation.hpp"
#include "peridot/solvers/surface_correction.hpp"
#include "support/problems.hpp"

namespace peridot {
namespace {

using testing::BlockSetup;

BlockSetup plate(const std::string& model, int dimension, bool corrected) {
  BlockSetup s;
  s.model = model;
  s.dimension = dimension;
  s.plane = dimension == 2 ? PlaneKind::stress : PlaneKind::none;
  if (model == "pmb") s.shear_modulus = 0.6 * s.bulk_modulus;  // ν = 1/4 (3D); plane stress sets its own
  if (dimension == 2) s.cells[0] = 20, s.cells[1] = 14;
  else s.cells[0] = s.cells[1] = s.cells[2] = 9;
  s.parameters.set_boolean("surface_correction", corrected);
  return s;
}

/// W_d of every point under a uniaxial strain ε along d.
std::vector<double> uniaxial_energy(Simulation& sim, int d, double strain) {
  const Discretization& disc = sim.discretization();
  VectorField u(disc.num_points());
  for (std::size_t i = 0; i < disc.num_points(); ++i) u(i, d) = strain * disc.x(i, d);
  State& s = sim.state();
  std::vector<double> W;
  compute_dilatation(sim.model(), u, s.dilatation, false, &s.history);
  compute_strain_energy_density(sim.model(), u, s.dilatation, W, &s.history);
  return W;
}

struct Case {
  const char* name;
  const char* model;
  int dimension;
};

class SurfaceCorrection : public ::testing::TestWithParam<Case> {};

// G_ij = G_ji (the pair force stays central and equal and opposite), and the factors are the same for every bond
// of the same direction between points whose families are whole (more than 2δ from every surface: their factors,
// and their neighbours', come from identical families), while the bonds of the outer points differ.
TEST_P(SurfaceCorrection, FactorsAreSymmetricAndUniformInTheInterior) {
  const Case c = GetParam();
  BlockSetup s = plate(c.model, c.dimension, true);
  for (int d = 0; d < c.dimension; ++d) s.cells[d] = c.dimension == 2 ? 24 : 16;
  Simulation sim(testing::box_problem(s));
  const Discretization& disc = sim.discretization();
  const BondList& bonds = sim.bonds();
  const std::vector<double>& G = sim.model().bond_scale;
  ASSERT_EQ(G.size(), bonds.num_bonds());
  const double delta = s.horizon_factor * s.spacing, size = (s.cells[0] - 1) * s.spacing;
  auto deep = [&](std::size_t i) {
    for (int d = 0; d < c.dimension; ++d)
      if (disc.x(i, d) < 2 * delta || disc.x(i, d) > size - 2 * delta) return false;
    return true;
  };
  auto key = [&](std::size_t i, std::uint32_t j) {  // the bond's lattice offset
    long k = 0;
    for (int d = 0; d < 3; ++d) k = 16 * k + std::lround((disc.x(j, d) - disc.x(i, d)) / s.spacing) + 8;
    return k;
  };
  std::map<long, double> interior;
  double spread = 0, smallest = 1e300, largest = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      for (std::uint64_t r = bonds.offsets[j]; r < bonds.offsets[j + 1]; ++r)
        if (bonds.neighbors[r] == i) EXPECT_EQ(G[r], G[b]) << "bond " << i << " <-> " << j;
      smallest = std::min(smallest, G[b]), largest = std::max(largest, G[b]);
      if (!deep(i)) continue;
      const auto [it, inserted] = interior.emplace(key(i, j), G[b]);
      spread = std::max(spread, std::abs(G[b] / it->second - 1));
    }
  std::printf("%s: bond factors from %.4f to %.4f\n", c.name, smallest, largest);
  EXPECT_LT(spread, 1e-8);  // the sums of W in another order
  EXPECT_LT(smallest, 0.97);  // the outer bonds are corrected
}

// Under each uniaxial strain, the body's energy Σ W V (its stiffness) and the points' energies are much closer to
// the classical ones with the correction than without.
TEST_P(SurfaceCorrection, BringsUniaxialEnergiesTowardsClassical) {
  const Case c = GetParam();
  Simulation plain(testing::box_problem(plate(c.model, c.dimension, false)));
  Simulation corrected(testing::box_problem(plate(c.model, c.dimension, true)));
  const std::vector<double>& V = plain.discretization().volume;
  const double strain = 1e-7;
  const double classical = uniaxial_strain_energy(plain.model().params[0], plain.problem(), strain);
  double before = 0, after = 0;              // the largest |W_d/W_classical − 1| over points and axes
  double total_before = 0, total_after = 0;  // the largest |Σ W_d V / (W_classical Σ V) − 1| over the axes
  for (int d = 0; d < c.dimension; ++d) {
    const std::vector<double> W0 = uniaxial_energy(plain, d, strain), W1 = uniaxial_energy(corrected, d, strain);
    double sum0 = 0, sum1 = 0, volume = 0;
    for (std::size_t i = 0; i < W0.size(); ++i) {
      before = std::max(before, std::abs(W0[i] / classical - 1));
      after = std::max(after, std::abs(W1[i] / classical - 1));
      sum0 += W0[i] * V[i], sum1 += W1[i] * V[i], volume += V[i];
    }
    total_before = std::max(total_before, std::abs(sum0 / (classical * volume) - 1));
    total_after = std::max(total_after, std::abs(sum1 / (classical * volume) - 1));
  }
  std::printf("%s: uniaxial energy of the body off by %.2f %% uncorrected, %.2f %% corrected; of a point by up to "
              "%.1f %% and %.1f %%\n",
              c.name, 100 * total_before, 100 * total_after, 100 * before, 100 * after);
  EXPECT_NEAR(corrected.surface_correction().largest_uncorrected, before, 1e-6);
  EXPECT_NEAR(corrected.surface_correction().largest_deviation, after, 1e-6);
  EXPECT_LT(after, 0.9 * before);
  EXPECT_LT(total_after, c.model == std::string("pmb") ? 0.1 * total_before : 0.7 * total_before);
}

const Case cases[] = {
    {"Pmb2dPlaneStress", "pmb", 2},
    {"Lps2dPlaneStress", "lps", 2},
    {"Pmb3d", "pmb", 3},
    {"Lps3d", "lps", 3},
};
INSTANTIATE_TEST_SUITE_P(Models, SurfaceCorrection, ::testing::ValuesIn(cases),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace peridot
