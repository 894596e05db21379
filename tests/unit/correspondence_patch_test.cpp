// Patch tests of the correspondence model on point clouds built by the library's own generator and
// neighbour search (Foster, Silling & Chen 2010 eqs 4, 10–25):
//  - a homogeneous deformation history gives, at every point (boundaries included, jittered lattice,
//    partial volumes), the stress of the material-point driver;
//  - the force of a homogeneous deformation vanishes away from the surface;
//  - Σ f V = 0 and Σ y × f V = 0 for a random deformation (with hourglass springs and dashpots on);
//  - a rigid rotation gives F = R, no stress and no force;
//  - the force is bitwise the same with 1 and 2 threads (docs/design.md "Determinism").
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <memory>

#include <omp.h>

#include "peridot/correspondence/force.hpp"
#include "peridot/correspondence/hypoelastic.hpp"
#include "peridot/correspondence/j2_viscoplastic.hpp"
#include "peridot/correspondence/material_point_driver.hpp"
#include "support/correspondence_cloud.hpp"

namespace peridot {
namespace {

using namespace correspondence;

/// u = (F_end − I) x and v = Ḟ x: the state of a homogeneous motion at the end of a step.
void set_homogeneous(const Discretization& disc, const Mat3& F_end, const Mat3& F_rate, VectorField& u,
                     VectorField& v) {
  const std::size_t n = disc.num_points();
  u.resize(n);
  v.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d x(disc.x(i, 0), disc.x(i, 1), disc.x(i, 2));
    const Vec3d ui = (F_end - Mat3::Identity()) * x, vi = F_rate * x;
    for (int d = 0; d < 3; ++d) {
      u(i, d) = ui(d);
      v(i, d) = vi(d);
    }
  }
}

BlockRange whole(const Discretization& disc) { return {0, disc.num_points()}; }

/// Kinematics, stress and force of one step from the unstressed reference state to (u, v).
template <ConstitutiveLaw Law>
struct StepFromRest {
  KinematicFields kin;
  StressFields stress;
  std::vector<typename Law::History> history;
  VectorField force;
};

template <ConstitutiveLaw Law>
StepFromRest<Law> step_from_rest(const testing::CorrespondenceCloud& cloud, const Law& law, const VectorField& u,
                                 const VectorField& v, double dt) {
  StepFromRest<Law> out;
  compute_kinematics(cloud.ctx, u, v, out.kin);
  CorrespondenceBlock<Law> block(law, whole(cloud.disc));
  out.stress.resize(cloud.disc.num_points());
  update_block_stress(cloud.ctx, out.kin, dt, block, out.stress);
  compute_correspondence_force(cloud.ctx, out.kin, out.stress, u, v, out.force);
  out.history = std::move(block.history);
  return out;
}

TEST(CorrPatch, HomogeneousDeformationGivesDriverStressAtEveryPoint) {
  testing::CloudSetup setup;
  setup.jitter = 0.25;
  setup.partial_volume = true;
  auto cloud = testing::make_cloud(setup);
  const Discretization& disc = cloud->disc;
  const J2Viscoplastic law = J2Viscoplastic::aluminium_6061_t6();
  // Stretch, lateral contraction and shear at ~1e4 /s: plastic after a few steps, with rotation.
  auto F_of_t = [](double t) {
    Mat3 F;
    F << 1 + 2000 * t, 5000 * t, 0,  //
        0, 1 - 800 * t, 300 * t,     //
        0, 0, 1;
    return F;
  };
  const double dt = 1e-7;
  const int steps = 400;  // t = 40 µs: stretch 1.08, shear 0.2
  const auto reference = run_prescribed_deformation(law, F_of_t, dt, steps);
  ASSERT_GT(reference.back().history.equivalent_plastic_strain, 0.05);

  CorrespondenceBlock<J2Viscoplastic> block(law, whole(disc));
  StressFields stress;
  stress.resize(disc.num_points());
  KinematicFields kin;
  VectorField u, v;
  double worst = 0, worst_eqps = 0;
  for (int k = 0; k < steps; ++k) {
    const Mat3 F0 = F_of_t(k * dt), F1 = F_of_t((k + 1) * dt);
    set_homogeneous(disc, F1, (F1 - F0) / dt, u, v);
    compute_kinematics(cloud->ctx, u, v, kin);
    update_block_stress(cloud->ctx, kin, dt, block, stress);
    const auto& expected = reference[k + 1];
    for (std::size_t i = 0; i < disc.num_points(); ++i) {
      worst = std::max(worst, (stress.cauchy_stress.get(i) - expected.cauchy_stress).cwiseAbs().maxCoeff());
      worst_eqps = std::max(worst_eqps, std::abs(block.history[i].equivalent_plastic_strain -
                                                 expected.history.equivalent_plastic_strain));
    }
  }
  std::printf("homogeneous J2 patch: %zu points, %d steps, final εp %.4f, σ_vm %.1f MPa; max |σ − σ_driver| = "
              "%.2e Pa, max |εp − εp_driver| = %.2e\n",
              disc.num_points(), steps, reference.back().history.equivalent_plastic_strain,
              von_mises(reference.back().cauchy_stress) / 1e6, worst, worst_eqps);
  // The same per-point step as the driver, fed an F exact to round-off: round-off agreement.
  EXPECT_LT(worst, 1e-9 * law.yield_stress);
  EXPECT_LT(worst_eqps, 1e-11);
}

TEST(CorrPatch, HomogeneousDeformationGivesZeroForceAwayFromSurface) {
  testing::CloudSetup setup;  // regular lattice: the interior families are point-symmetric
  setup.cells[0] = setup.cells[1] = setup.cells[2] = 15;
  auto cloud = testing::make_cloud(setup);
  const Discretization& disc = cloud->disc;
  const std::size_t n = disc.num_points();
  const Hypoelastic law = Hypoelastic::from_young_poisson(68.9e9, 0.333);
  cloud->ctx.hourglass_stiffness = {hourglass_stiffness(default_hourglass_coefficient, law.bulk, cloud->horizon)};
  cloud->ctx.hourglass_damping = {hourglass_damping(0.1, 2700, law.bulk, cloud->horizon)};  // ż = 0 here too
  Mat3 F;
  F << 1.01, 0.004, -0.002,  //
      0.003, 0.995, 0.006,   //
      -0.001, 0.002, 1.007;
  const double dt = 1e-7;
  VectorField u, v;
  set_homogeneous(disc, F, (F - Mat3::Identity()) / dt, u, v);
  const auto step = step_from_rest(*cloud, law, u, v, dt);
  const VectorField& f = step.force;
  const StressFields& stress = step.stress;
  // Scale: the size of the one-sided sum Σ_j |ω P K⁻¹ ξ| V_j, what cancels in the interior.
  const Mat3 A = stress.force_tensor.get(0);
  double scale = 0;
  const auto& bonds = cloud->bonds;
  for (std::uint64_t b = bonds.offsets[0]; b < bonds.offsets[1]; ++b) {
    const std::size_t j = bonds.neighbors[b];
    const Vec3d xi(disc.x(j, 0) - disc.x(0, 0), disc.x(j, 1) - disc.x(0, 1), disc.x(j, 2) - disc.x(0, 2));
    scale += (A * xi).norm() * disc.volume[j];
  }
  double worst_interior = 0, largest_surface = 0;
  std::size_t interior = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double fi = Vec3d(f(i, 0), f(i, 1), f(i, 2)).norm();
    // Beyond 2δ from the surface, i and all its neighbours have complete, point-symmetric families.
    if (testing::distance_to_surface(*cloud, setup.cells, i) > 2 * cloud->horizon) {
      ++interior;
      worst_interior = std::max(worst_interior, fi);
    } else {
      largest_surface = std::max(largest_surface, fi);
    }
  }
  std::printf("homogeneous force: %zu interior points, max |f| %.2e N/m³ inside vs %.2e at the surface "
              "(scale %.2e)\n", interior, worst_interior, largest_surface, scale);
  EXPECT_EQ(interior, 27u);
  EXPECT_LT(worst_interior, 1e-13 * scale);
  EXPECT_GT(largest_surface, 1e-2 * scale);  // a free surface under stress is not in equilibrium
}

/// A jittered cloud with partial volumes, 6061-T6 J2 with hourglass springs and dashpots (C_HV = 0.1), and a
/// displacement of 1 % strain plus a random part of 0.05 Δx reached in one step of 0.1 µs: well into the
/// plastic range.
struct RandomMotion {
  std::unique_ptr<testing::CorrespondenceCloud> cloud;
  J2Viscoplastic law = J2Viscoplastic::aluminium_6061_t6();
  VectorField u, v;
  double dt = 1e-7;
};

RandomMotion random_motion() {
  RandomMotion m;
  testing::CloudSetup setup;
  setup.jitter = 0.25;
  setup.partial_volume = true;
  setup.influence = InfluenceKind::inverse_distance;
  m.cloud = testing::make_cloud(setup);
  m.cloud->ctx.hourglass_stiffness = {
      hourglass_stiffness(default_hourglass_coefficient, m.law.bulk, m.cloud->horizon)};
  m.cloud->ctx.hourglass_damping = {hourglass_damping(0.1, 2700, m.law.bulk, m.cloud->horizon)};
  const Discretization& disc = m.cloud->disc;
  const std::size_t n = disc.num_points();
  m.u.resize(n);
  m.v.resize(n);
  std::uint64_t seed = 99;
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      m.u(i, d) = 0.01 * disc.x(i, (d + 1) % 3) + 0.05 * m.cloud->spacing * (2 * uniform01(seed) - 1);
      m.v(i, d) = m.u(i, d) / m.dt;
    }
  return m;
}

TEST(CorrPatch, RandomDeformationConservesLinearAndAngularMomentum) {
  const RandomMotion m = random_motion();
  const Discretization& disc = m.cloud->disc;
  const std::size_t n = disc.num_points();
  const VectorField& u = m.u;
  const auto step = step_from_rest(*m.cloud, m.law, m.u, m.v, m.dt);
  const VectorField& f = step.force;
  std::size_t plastic = 0;
  for (const auto& h : step.history) plastic += h.equivalent_plastic_strain > 0;
  Vec3d momentum = Vec3d::Zero(), moment = Vec3d::Zero();
  double momentum_scale = 0, moment_scale = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d fi = Vec3d(f(i, 0), f(i, 1), f(i, 2)) * disc.volume[i];
    const Vec3d yi(disc.x(i, 0) + u(i, 0), disc.x(i, 1) + u(i, 1), disc.x(i, 2) + u(i, 2));
    momentum += fi;
    moment += yi.cross(fi);
    momentum_scale += fi.norm();
    moment_scale += yi.norm() * fi.norm();
  }
  std::printf("random deformation: %zu of %zu points plastic; |Σ f V| / Σ|f V| = %.2e, |Σ y × f V| / Σ|y||f V| "
              "= %.2e\n", plastic, n, momentum.norm() / momentum_scale, moment.norm() / moment_scale);
  EXPECT_GT(plastic, n / 2);
  EXPECT_LT(momentum.norm(), 1e-14 * momentum_scale);
  // Angular momentum holds because Σ_j ω Y⊗(P K⁻¹ ξ) V_j = F Pᵀ = Jσ is symmetric (force.hpp).
  EXPECT_LT(moment.norm(), 1e-14 * moment_scale);
}

TEST(CorrPatch, RigidRotationGivesFEqualsRNoStressNoForce) {
  testing::CloudSetup setup;
  setup.jitter = 0.25;
  auto cloud = testing::make_cloud(setup);
  const Discretization& disc = cloud->disc;
  const std::size_t n = disc.num_points();
  const J2Viscoplastic law = J2Viscoplastic::aluminium_6061_t6();
  cloud->ctx.hourglass_stiffness = {hourglass_stiffness(default_hourglass_coefficient, law.bulk, cloud->horizon)};
  // The hourglass dashpots too: a rigid motion has no non-affine rate either.
  cloud->ctx.hourglass_damping = {hourglass_damping(0.1, 2700, law.bulk, cloud->horizon)};
  const Vec3d axis = Vec3d(1, -2, 3).normalized();
  const double rate = 1e4, dt = 1e-6;  // 0.01 rad per step
  const int steps = 160;              // 1.6 rad, past a quarter turn
  auto R_of_t = [&](double t) { return Mat3(Eigen::AngleAxisd(rate * t, axis).toRotationMatrix()); };
  CorrespondenceBlock<J2Viscoplastic> block(law, whole(disc));
  StressFields stress;
  stress.resize(n);
  KinematicFields kin;
  VectorField u, v, f;
  double worst_F = 0, worst_sigma = 0, worst_force = 0;
  for (int k = 0; k < steps; ++k) {
    const Mat3 R0 = R_of_t(k * dt), R1 = R_of_t((k + 1) * dt);
    set_homogeneous(disc, R1, (R1 - R0) / dt, u, v);
    for (std::size_t i = 0; i < n; ++i) u(i, 0) += 1e-3 * (k + 1);  // plus a translation
    compute_kinematics(cloud->ctx, u, v, kin);
    update_block_stress(cloud->ctx, kin, dt, block, stress);
    compute_correspondence_force(cloud->ctx, kin, stress, u, v, f);
    for (std::size_t i = 0; i < n; ++i) {
      worst_F = std::max(worst_F, (kin.deformation_gradient.get(i) - R1).cwiseAbs().maxCoeff());
      worst_sigma = std::max(worst_sigma, stress.cauchy_stress.get(i).cwiseAbs().maxCoeff());
      worst_force = std::max(worst_force, Vec3d(f(i, 0), f(i, 1), f(i, 2)).norm());
      EXPECT_LT((stress.rotation.get(i) - R1).cwiseAbs().maxCoeff(), 1e-12);
    }
  }
  // Force scale: what a strain of 1 would give, μ/Δx.
  const double force_scale = law.shear / cloud->spacing;
  std::printf("rigid rotation: max |F − R| %.2e, max |σ| %.2e Pa (μ = %.3g Pa), max |f| %.2e N/m³ (μ/Δx = %.2e)\n",
              worst_F, worst_sigma, law.shear, worst_force, force_scale);
  EXPECT_LT(worst_F, 1e-13);
  // Round-off in D (~1e-16 |L|) times μΔt per step, over 160 steps.
  EXPECT_LT(worst_sigma, 1e-12 * law.shear);
  EXPECT_LT(worst_force, 1e-12 * force_scale);
}

TEST(CorrPatch, ForceIsBitwiseIndependentOfThreadCount) {
  const RandomMotion m = random_motion();
  const std::size_t n = m.cloud->disc.num_points();
  auto force_with = [&](int threads) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    VectorField f = step_from_rest(*m.cloud, m.law, m.u, m.v, m.dt).force;
    omp_set_num_threads(saved);
    return f;
  };
  const VectorField one = force_with(1), two = force_with(2);
  EXPECT_EQ(std::memcmp(one.data(), two.data(), 3 * n * sizeof(double)), 0);
}

}  // namespace
}  // namespace peridot
