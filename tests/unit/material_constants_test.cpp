// Material calibration against the closed forms of docs/algorithms.md §2–3: micromodulus, critical
// stretch from fracture energy (3D and 2D), the 2D bulk modulus, and the influence-function moments.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "peridot/materials/models.hpp"
#include "support/problems.hpp"

namespace peridot {
namespace {

constexpr double pi = std::numbers::pi;

ResolvedMaterial resolve(int dimension, PlaneKind plane, std::string model, double fracture_energy,
                       InfluenceKind influence = InfluenceKind::constant) {
  testing::BlockSetup s;
  s.dimension = dimension;
  s.plane = plane;
  s.model = model;
  s.influence = influence;
  Problem p = testing::box_problem(s);
  p.materials[0].damage.enabled = true;
  p.materials[0].damage.fracture_energy = fracture_energy;
  return resolve_material(p.materials[0], 3e-3, p);
}

TEST(MaterialConstants, PmbMicromodulusAndCriticalStretch3D) {
  const ResolvedMaterial p_all = resolve(3, PlaneKind::none, "pmb", 42408);
  const MaterialParams& p = p_all.block;
  const double K = p.elastic.bulk_modulus, delta = 3e-3;
  EXPECT_NEAR(std::get<Pmb::Params>(p_all.model).micromodulus, 18 * K / (pi * std::pow(delta, 4)), 1e-12 * std::get<Pmb::Params>(p_all.model).micromodulus);
  EXPECT_NEAR(p.critical_stretch, std::sqrt(5 * 42408 / (9 * K * delta)), 1e-12);
  EXPECT_DOUBLE_EQ(p.stable_micromodulus, std::get<Pmb::Params>(p_all.model).micromodulus);
}

TEST(MaterialConstants, PmbMicromodulusAndCriticalStretch2D) {
  for (PlaneKind plane : {PlaneKind::stress, PlaneKind::strain}) {
    const ResolvedMaterial p_all = resolve(2, plane, "pmb", 3.8);
  const MaterialParams& p = p_all.block;
    const double E = p.elastic.youngs_modulus, nu = p.elastic.poisson_ratio, delta = 3e-3, h = 1e-3;
    const double K2 = plane == PlaneKind::stress ? E / (2 * (1 - nu)) : E / (2 * (1 - nu - 2 * nu * nu));
    EXPECT_NEAR(std::get<Pmb::Params>(p_all.model).micromodulus, 12 * K2 / (pi * h * std::pow(delta, 3)), 1e-12 * std::get<Pmb::Params>(p_all.model).micromodulus);
    EXPECT_NEAR(p.critical_stretch, std::sqrt(pi * 3.8 / (3 * K2 * delta)), 1e-12);
  }
}

// A bar of area A (box_problem: A = Δx²): c0 = 2E/(Aδ²), s0 = √(3G0/(Eδ)). And the closed form against the
// lattice: the bonds crossing a point of a bar at m = δ/Δx = 400, each at s0 with its energy ½ c0 s0² ξ V V,
// take G0 A with them to within 2/m (Σ k² = m³/3 (1 + 3/(2m) + …)).
TEST(MaterialConstants, PmbMicromodulusAndCriticalStretch1D) {
  const ResolvedMaterial p_all = resolve(1, PlaneKind::none, "pmb", 500);
  const MaterialParams& p = p_all.block;
  const double E = p.elastic.youngs_modulus, delta = 3e-3, A = 1e-6;
  const double c0 = std::get<Pmb::Params>(p_all.model).micromodulus;
  EXPECT_NEAR(c0, 2 * E / (A * delta * delta), 1e-12 * c0);
  EXPECT_NEAR(p.critical_stretch, std::sqrt(3 * 500 / (E * delta)), 1e-12);
  const int m = 400;
  const double dx = delta / m, V = A * dx, s0 = p.critical_stretch;
  double work = 0;
  for (int k = 1; k <= m; ++k) work += k * 0.5 * c0 * s0 * s0 * (k * dx) * V * V;  // k bonds of length k Δx cross
  EXPECT_NEAR(work / (500 * A), 1.0, 2.0 / m);
}

TEST(MaterialConstants, LpsCoefficients) {
  const ResolvedMaterial p3_all = resolve(3, PlaneKind::none, "lps", 100);
  const MaterialParams& p3 = p3_all.block;
  EXPECT_DOUBLE_EQ(std::get<Lps::Params>(p3_all.model).alpha_volumetric, 3 * p3.elastic.bulk_modulus);
  EXPECT_DOUBLE_EQ(std::get<Lps::Params>(p3_all.model).alpha_deviatoric, 15 * p3.elastic.shear_modulus);
  const ResolvedMaterial p2_all = resolve(2, PlaneKind::stress, "lps", 100);
  const MaterialParams& p2 = p2_all.block;
  const double E = p2.elastic.youngs_modulus, nu = p2.elastic.poisson_ratio;
  EXPECT_NEAR(std::get<Lps::Params>(p2_all.model).alpha_volumetric, 2 * E / (2 * (1 - nu)), 1e-6 * std::get<Lps::Params>(p2_all.model).alpha_volumetric);
  EXPECT_DOUBLE_EQ(std::get<Lps::Params>(p2_all.model).alpha_deviatoric, 8 * p2.elastic.shear_modulus);
  EXPECT_EQ(std::get<Lps::Params>(p2_all.model).dilatation_factor, 2);
}

TEST(MaterialConstants, InfluenceMomentsMatchQuadrature) {
  const double delta = 2.0;
  for (InfluenceKind kind : {InfluenceKind::constant, InfluenceKind::inverse_distance, InfluenceKind::gaussian})
    for (int p = 2; p <= 4; ++p) {
      const int n = 200000;
      double sum = 0;
      for (int k = 0; k < n; ++k) {
        const double xi = (k + 0.5) * delta / n;
        sum += influence(kind, xi, delta) * std::pow(xi, p) * delta / n;
      }
      EXPECT_NEAR(influence_moment(kind, delta, p), sum, 1e-8 * sum) << static_cast<int>(kind) << " p=" << p;
    }
}

// With ω = δ/ξ the critical stretch still satisfies G0 = (π c0 s0²/2) ∫ ω ξ⁴ dξ (3D), c0 from K.
TEST(MaterialConstants, CriticalStretchWithInfluenceFunction) {
  const ResolvedMaterial p_all = resolve(3, PlaneKind::none, "pmb", 1000, InfluenceKind::inverse_distance);
  const MaterialParams& p = p_all.block;
  const double delta = 3e-3, K = p.elastic.bulk_modulus;
  EXPECT_NEAR(std::get<Pmb::Params>(p_all.model).micromodulus, 27 * K / (2 * pi * std::pow(delta, 4)), 1e-12 * std::get<Pmb::Params>(p_all.model).micromodulus);
  const double g0 = pi * std::get<Pmb::Params>(p_all.model).micromodulus * p.critical_stretch * p.critical_stretch / 2 * std::pow(delta, 5) / 4;
  EXPECT_NEAR(g0, 1000, 1e-9);
}

}  // namespace
}  // namespace peridot
