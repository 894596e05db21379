// The isotropic bond quadrature (discretization.quadrature: isotropic, neighbor/quadrature.hpp).
//  - The fitted direction weight makes the lattice family's fourth moment isotropic and equal to the continuum
//    integral, for every lattice, horizon, influence function and partial-volume rule (to round-off), with
//    positive weights.
//  - With it an LPS (3D, plane stress, plane strain) or PMB block stores exactly the classical energy of an
//    affine strain in its interior at δ = 3.015Δx, where the one-point quadrature is off by percents.
//  - Second-order consistency: a quadratic displacement field gives, at points deeper than 2δ, the force
//    density of the Navier operator μ∇²u + (λ + μ)∇(∇·u) (what makes the manufactured-solution study of
//    examples/convergence_to_elasticity converge at second order in δ); the one-point quadrature does not.
//  - The deck refuses it, at the key, for a body read from a file and for a model whose sums are not moments.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "peridot/deck/deck.hpp"
#include "peridot/neighbor/influence.hpp"
#include "peridot/neighbor/quadrature.hpp"
#include "peridot/solvers/internal_force.hpp"
#include "peridot/solvers/simulation.hpp"
#include "support/problems.hpp"

namespace peridot {
namespace {

using testing::BlockSetup;

struct Moments {
  double xxxx = 0, xxyy = 0;  ///< Σ W w n_x⁴ and Σ W w n_x² n_y² over the family
  double smallest_weight = 1e300;
};

Moments family_moments(const QuadratureLattice& q, const IsotropicQuadrature& fit) {
  Moments m;
  const double reach = q.horizon + (q.bond_beyond_horizon ? q.partial_volume_radius : 0.0);
  const int n = static_cast<int>(std::ceil(reach / q.spacing));
  const int ny = q.dimension >= 2 ? n : 0, nz = q.dimension == 3 ? n : 0;
  for (int i = -n; i <= n; ++i)
    for (int j = -ny; j <= ny; ++j)
      for (int k = -nz; k <= nz; ++k) {
        const double d0 = i * q.spacing, d1 = j * q.spacing, d2 = k * q.spacing;
        const double xi = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
        if (xi == 0 || xi > reach) continue;
        const double pv = partial_volume_factor(xi, q.horizon, q.partial_volume_radius);
        if (pv <= 0) continue;
        const double w = quadrature_weight(fit, d0, d1, d2, xi);
        m.smallest_weight = std::min(m.smallest_weight, w);
        const double W = influence(q.influence, xi, q.horizon) * std::pow(xi, q.moment_power) * pv *
                         std::pow(q.spacing, q.dimension) * w;
        const double nx = d0 / xi, ny2 = d1 / xi;
        m.xxxx += W * nx * nx * nx * nx;
        m.xxyy += W * nx * nx * ny2 * ny2;
      }
  return m;
}

// ∫ over the ball of ω ξᵖ n_x⁴, by a fine radial midpoint rule (independent of the fit's own).
double continuum_xxxx(const QuadratureLattice& q) {
  const int intervals = 200000;
  const double h = q.horizon / intervals;
  double radial = 0;
  for (int k = 0; k < intervals; ++k) {
    const double r = (k + 0.5) * h;
    radial += influence(q.influence, r, q.horizon) * std::pow(r, q.moment_power + q.dimension - 1) * h;
  }
  return radial * (q.dimension == 3 ? 4 * M_PI / 5 : 0.75 * M_PI);
}

TEST(IsotropicQuadrature, FourthMomentIsIsotropicAndContinuous) {
  for (int dimension : {2, 3})
    for (double factor : {2.015, 3.015, 4.015, 5.015})
      for (InfluenceKind influence : {InfluenceKind::constant, InfluenceKind::inverse_distance, InfluenceKind::gaussian})
        for (int partial : {0, 1, 2})  // none, horizon, extended
          for (int power : {1, 2}) {
            QuadratureLattice q{.dimension = dimension,
                                .spacing = 1e-3,
                                .horizon = factor * 1e-3,
                                .influence = influence,
                                .partial_volume_radius = partial ? 0.5e-3 : 0.0,
                                .bond_beyond_horizon = partial == 2,
                                .moment_power = power};
            const IsotropicQuadrature fit = fit_isotropic_quadrature(q);
            const Moments m = family_moments(q, fit);
            const std::string where = ::testing::PrintToString(std::make_tuple(dimension, factor, static_cast<int>(influence), partial, power));
            EXPECT_NEAR(m.xxxx, 3 * m.xxyy, 1e-12 * m.xxxx) << where;
            EXPECT_NEAR(m.xxxx, continuum_xxxx(q), 1e-7 * m.xxxx) << where;
            EXPECT_GT(m.smallest_weight, 0.5) << where;
          }
}

// Without the quadrature the same sums are anisotropic by percents (what the fit is for): 3D, δ = 3.015Δx.
TEST(IsotropicQuadrature, OnePointQuadratureIsAnisotropic) {
  QuadratureLattice q{.dimension = 3, .spacing = 1e-3, .horizon = 3.015e-3};
  const Moments m = family_moments(q, IsotropicQuadrature{});
  EXPECT_LT(m.xxxx / m.xxyy, 2.6);  // 2.50 where isotropy needs 3
}

BlockSetup lattice_block(int dimension, PlaneKind plane, const std::string& model) {
  BlockSetup s;
  s.dimension = dimension;
  s.plane = plane;
  s.model = model;
  s.bulk_modulus = 70e9;
  s.shear_modulus = 26e9;
  s.horizon_factor = 3.015;
  const int n = dimension == 3 ? 16 : 30;
  s.cells[0] = s.cells[1] = s.cells[2] = n;
  return s;
}

Problem quadrature_problem(const BlockSetup& s, bool isotropic) {
  Problem p = testing::box_problem(s);
  p.quadrature = isotropic ? QuadratureKind::isotropic : QuadratureKind::one_point;
  return p;
}

/// The largest error(i) over the points deeper than min_depth in the block (there must be some).
template <class Error>
double largest_deeper_than(const Discretization& disc, const BlockSetup& s, double min_depth, Error error) {
  double worst = 0;
  int points = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    if (testing::depth(disc, s, i) > min_depth) worst = std::max(worst, error(i)), ++points;
  EXPECT_GT(points, 0);
  return worst;
}

// λ and G of the block's classical solid in its idealisation (plane stress: λ′ = 2λG/(λ + 2G)).
std::pair<double, double> lame(const Simulation& sim, const BlockSetup& s) {
  const ElasticConstants& c = sim.model().params[0].elastic;
  const double G = c.shear_modulus, lambda = c.bulk_modulus - 2 * G / 3;
  if (s.dimension == 2 && s.plane == PlaneKind::stress) return {2 * lambda * G / (lambda + 2 * G), G};
  return {lambda, G};
}

class QuadratureBlock : public ::testing::TestWithParam<std::tuple<int, PlaneKind, std::string>> {};

// An affine strain: the interior energy density against ½λ(tr ε)² + G ε:ε. Returns the largest relative error.
double largest_energy_error(const BlockSetup& s, bool isotropic) {
  Simulation sim(quadrature_problem(s, isotropic));
  const Discretization& disc = sim.discretization();
  // xx yy zz xy yz xz: small, so that the bonds' nonlinear stretch (a relative O(ε)) stays below 1e-6.
  const double e[6] = {1.0e-7, -0.4e-7, 0.7e-7, 0.5e-7, -0.3e-7, 0.2e-7};
  const bool three = s.dimension == 3;
  VectorField u(disc.num_points());
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    const Vec3 x = disc.x.get(i);
    u.set(i, {e[0] * x.x + e[3] * x.y + (three ? e[5] * x.z : 0), e[3] * x.x + e[1] * x.y + (three ? e[4] * x.z : 0),
              three ? e[5] * x.x + e[4] * x.y + e[2] * x.z : 0.0});
  }
  const auto [lambda, G] = lame(sim, s);
  const double tr = e[0] + e[1] + (three ? e[2] : 0);
  const double expected = 0.5 * lambda * tr * tr +
                          G * (e[0] * e[0] + e[1] * e[1] + 2 * e[3] * e[3] +
                               (three ? e[2] * e[2] + 2 * (e[4] * e[4] + e[5] * e[5]) : 0));
  State& state = sim.state();
  compute_dilatation(sim.model(), u, state.dilatation);
  std::vector<double> W;
  compute_strain_energy_density(sim.model(), u, state.dilatation, W);
  return largest_deeper_than(disc, s, s.horizon_factor * s.spacing,
                             [&](std::size_t i) { return std::abs(W[i] / expected - 1); });
}

TEST_P(QuadratureBlock, AffineStrainStoresTheClassicalEnergy) {
  const auto [dimension, plane, model] = GetParam();
  const BlockSetup s = lattice_block(dimension, plane, model);
  EXPECT_LT(largest_energy_error(s, true), 1e-6);
  EXPECT_GT(largest_energy_error(s, false), 5e-3);
}

// u_a = ½ Σ H_abc x_b x_c: the Navier operator is constant, f_a = G Σ_b H_abb + (λ + G) Σ_b H_bba.
// Returns the largest |f_PD − f| / |f| over the points deeper than 2δ + Δx.
double largest_navier_error(const BlockSetup& s, bool isotropic) {
  Simulation sim(quadrature_problem(s, isotropic));
  const Discretization& disc = sim.discretization();
  const int dim = s.dimension;
  const double A = 1e-3;  // 1/m: strains of order A·L ≈ 1e-5
  double H[3][3][3] = {};
  const double entries[3][6] = {{1.0, -0.6, 0.3, 0.8, 0.2, -0.5},  // xx yy zz xy yz xz of each component
                                {-0.4, 0.9, 0.5, -0.7, 0.6, 0.1},
                                {0.2, -0.3, 1.1, 0.4, -0.8, 0.7}};
  for (int a = 0; a < dim; ++a) {
    const double* h = entries[a];
    H[a][0][0] = h[0], H[a][1][1] = h[1], H[a][0][1] = H[a][1][0] = h[3];
    if (dim == 3) H[a][2][2] = h[2], H[a][1][2] = H[a][2][1] = h[4], H[a][0][2] = H[a][2][0] = h[5];
    for (auto& row : H[a])
      for (double& v : row) v *= A;
  }
  VectorField u(disc.num_points());
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    const Vec3 p = disc.x.get(i);
    const double x[3] = {p.x, p.y, p.z};
    double w[3] = {0, 0, 0};
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b)
        for (int c = 0; c < dim; ++c) w[a] += 0.5 * H[a][b][c] * x[b] * x[c];
    u.set(i, {w[0], w[1], w[2]});
  }
  const auto [lambda, G] = lame(sim, s);
  double expected[3] = {0, 0, 0};
  for (int a = 0; a < dim; ++a)
    for (int b = 0; b < dim; ++b) expected[a] += G * H[a][b][b] + (lambda + G) * H[b][b][a];
  const double scale = std::sqrt(expected[0] * expected[0] + expected[1] * expected[1] + expected[2] * expected[2]);
  State& state = sim.state();
  compute_dilatation(sim.model(), u, state.dilatation);
  compute_internal_force(sim.model(), u, state.dilatation, state.force);
  const Vec3 navier{expected[0], expected[1], expected[2]};
  return largest_deeper_than(disc, s, (2 * s.horizon_factor + 1) * s.spacing,
                             [&](std::size_t i) { return norm(state.force.get(i) - navier) / scale; });
}

TEST_P(QuadratureBlock, QuadraticFieldGivesTheNavierForce) {
  const auto [dimension, plane, model] = GetParam();
  const BlockSetup s = lattice_block(dimension, plane, model);
  EXPECT_LT(largest_navier_error(s, true), 1e-4);
  EXPECT_GT(largest_navier_error(s, false), 1e-2);
}

std::string block_name(const ::testing::TestParamInfo<std::tuple<int, PlaneKind, std::string>>& info) {
  const auto& [dimension, plane, model] = info.param;
  const std::string where = dimension == 3 ? "ThreeD" : plane == PlaneKind::stress ? "PlaneStress" : "PlaneStrain";
  return where + "_" + model;
}

INSTANTIATE_TEST_SUITE_P(Models, QuadratureBlock,
                         ::testing::Values(std::make_tuple(3, PlaneKind::none, std::string("lps")),
                                           std::make_tuple(2, PlaneKind::stress, std::string("lps")),
                                           std::make_tuple(2, PlaneKind::strain, std::string("lps")),
                                           std::make_tuple(3, PlaneKind::none, std::string("pmb"))),
                         block_name);

std::string refusal(const std::string& deck, const std::string& directory) {
  try {
    Simulation sim(parse_deck(deck, "deck.yaml", directory));
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(IsotropicQuadrature, DeckRefusesPointFilesAndOtherModels) {
  const std::string lattice = R"(discretization:
  dimension: 2
  plane: stress
  spacing: 1 mm
  horizon_factor: 3.015
  quadrature: isotropic
materials:
  glass: {model: MODEL, density: 2500, youngs_modulus: 70 GPa, poisson_ratio: 0.2}
bodies:
  plate: {material: glass, BODY}
solver: {type: explicit, num_steps: 1}
)";
  auto deck = [&](const std::string& model, const std::string& body) {
    std::string d = lattice;
    d.replace(d.find("MODEL"), 5, model);
    d.replace(d.find("BODY"), 4, body);
    return d;
  };
  const std::string box = "shape: {box: {min: [0, 0], max: [0.01, 0.01]}}";
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "peridot_quadrature_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "points.txt") << "0 0 1e-6\n0.001 0 1e-6\n";
  EXPECT_EQ(refusal(deck("lps", box), dir.string()), "accepted");
  const std::string from_file = refusal(deck("lps", "points_file: points.txt"), dir.string());
  EXPECT_NE(from_file.find("deck.yaml:6:15: error: discretization.quadrature: isotropic quadrature is fitted to the "
                           "lattice; body 'plate' is read from a file"),
            std::string::npos)
      << from_file;
  const std::string other = refusal(deck("thermoviscoelastic", box), dir.string());
  EXPECT_NE(other.find("deck.yaml:6:15"), std::string::npos) << other;
  EXPECT_NE(other.find("isotropic quadrature applies to pmb and the lps models; body 'plate' has model thermoviscoelastic"),
            std::string::npos)
      << other;
}

}  // namespace
}  // namespace peridot
