// Bulk (shock) viscosity of the correspondence model (constitutive.hpp, bulk_viscous_pressure):
//  - the closed form q = ℓ (b_q ℓ (tr D)² − b_l tr D) in compression and 0 in expansion;
//  - a homogeneous compression gives, at every point, the driver's stress less q I with ℓ = V^(1/3), and its
//    work J q |tr D| Δt as inelastic work; a homogeneous expansion and a rigid rotation give the same bits
//    with the viscosity as without;
//  - two halves of a block thrown at each other (a pair of shocks): kinetic + elastic + dissipated energy stays
//    the initial kinetic energy with and without the viscosity (no hourglass springs, whose energy is not
//    counted here). What the viscosity does to the ringing behind the shocks is printed, not asserted: in this
//    narrow block it is small (the lateral release dominates the spread of v_x).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "peridot/correspondence/force.hpp"
#include "peridot/correspondence/hypoelastic.hpp"
#include "peridot/correspondence/material_point_driver.hpp"
#include "support/correspondence_cloud.hpp"

namespace peridot {
namespace {

using namespace correspondence;

constexpr double density = 2700;  // kg/m³

const Hypoelastic& aluminium() {
  static const Hypoelastic law = Hypoelastic::from_young_poisson(68.9e9, 0.333);
  return law;
}

double p_wave_speed(const Hypoelastic& law) { return std::sqrt((law.bulk + 4 * law.shear / 3) / density); }

/// The hydrocodes' coefficients C_l = 0.06, C_q = 1.5 as the context holds them.
void set_viscosity(CorrespondenceContext& ctx, double linear = 0.06, double quadratic = 1.5) {
  ctx.bulk_viscosity_linear = {linear * density * p_wave_speed(aluminium())};
  ctx.bulk_viscosity_quadratic = {quadratic * density};
}

TEST(CorrBulkViscosity, PressureIsTheClosedFormInCompressionAndZeroInExpansion) {
  const double size = 2e-4, linear = 1e6, quadratic = 4e3;
  EXPECT_DOUBLE_EQ(bulk_viscous_pressure(-1e4, size, linear, quadratic),
                   size * (quadratic * size * 1e8 + linear * 1e4));
  EXPECT_EQ(bulk_viscous_pressure(1e4, size, linear, quadratic), 0.0);
  EXPECT_EQ(bulk_viscous_pressure(0.0, size, linear, quadratic), 0.0);
  EXPECT_GT(bulk_viscous_pressure(-1e4, size, linear, 0), 0.0);
}

struct HomogeneousRun {
  double stress_error = 0;  ///< largest |σ − (σ_driver − q I)| over all points and steps (Pa)
  double work_error = 0;    ///< largest |ΔW − J q |tr D| Δt| / (J q |tr D| Δt) where q > 0
  double largest_idle_work = 0;     ///< largest |ΔW| where q = 0 (J/m³)
  std::vector<Mat3> final_stress;   ///< σ of every point after the last step
};

/// Runs F(t) homogeneously on a cloud for `steps` steps, with the hydrocodes' viscosity or without.
template <class FOfT>
HomogeneousRun homogeneous_run(const FOfT& F_of_t, double dt, int steps, bool viscosity) {
  testing::CloudSetup setup;
  auto cloud = testing::make_cloud(setup);
  if (viscosity) set_viscosity(cloud->ctx);
  const Discretization& disc = cloud->disc;
  const std::size_t n = disc.num_points();
  const auto reference = run_prescribed_deformation(aluminium(), F_of_t, dt, steps);
  CorrespondenceBlock<Hypoelastic> block(aluminium(), {0, n});
  StressFields stress;
  stress.resize(n);
  KinematicFields kin;
  VectorField u(n), v(n);
  std::vector<double> work(n);
  HomogeneousRun out;
  for (int k = 0; k < steps; ++k) {
    const Mat3 F0 = F_of_t(k * dt), F1 = F_of_t((k + 1) * dt), rate = (F1 - F0) / dt;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3d x(disc.x(i, 0), disc.x(i, 1), disc.x(i, 2));
      const Vec3d ui = (F1 - Mat3::Identity()) * x, vi = rate * x;
      for (int d = 0; d < 3; ++d) {
        u(i, d) = ui(d);
        v(i, d) = vi(d);
      }
    }
    compute_kinematics(cloud->ctx, u, v, kin);
    std::fill(work.begin(), work.end(), 0.0);
    update_block_stress(cloud->ctx, kin, dt, block, stress, work.data());
    const double trace = mid_step_velocity_gradient(F1, rate, dt).trace();
    const double mid_jacobian = (F1 - 0.5 * dt * rate).determinant();
    for (std::size_t i = 0; i < n; ++i) {
      const double q = viscosity ? bulk_viscous_pressure(trace, std::cbrt(disc.volume[i]),
                                                         cloud->ctx.bulk_viscosity_linear[0],
                                                         cloud->ctx.bulk_viscosity_quadratic[0])
                                 : 0.0;
      const Mat3 expected = reference[k + 1].cauchy_stress - q * Mat3::Identity();
      out.stress_error = std::max(out.stress_error, (stress.cauchy_stress.get(i) - expected).cwiseAbs().maxCoeff());
      const double q_work = -mid_jacobian * q * trace * dt;
      if (q_work > 0) out.work_error = std::max(out.work_error, std::abs(work[i] - q_work) / q_work);
      else out.largest_idle_work = std::max(out.largest_idle_work, std::abs(work[i]));
    }
  }
  for (std::size_t i = 0; i < n; ++i) out.final_stress.push_back(stress.cauchy_stress.get(i));
  return out;
}

TEST(CorrBulkViscosity, HomogeneousCompressionCarriesQAndDissipatesItsWork) {
  // Uniaxial compression at 2e4 /s with a shear, to 4 % in 20 steps: q ≈ 0.06 ρ c ℓ |tr D| ≈ 4 MPa plus the
  // quadratic part, against a few GPa of elastic stress.
  const auto F_of_t = [](double t) {
    Mat3 F;
    F << 1 - 2e4 * t, 3e3 * t, 0,  //
        0, 1, 0,                   //
        0, 0, 1;
    return F;
  };
  const HomogeneousRun run = homogeneous_run(F_of_t, 1e-7, 20, true);
  std::printf("homogeneous compression: max |σ − (σ_driver − qI)| = %.2e Pa, work relative error %.2e\n",
              run.stress_error, run.work_error);
  EXPECT_LT(run.stress_error, 1e-9 * 68.9e9 * 0.04);
  // The hypoelastic law's own inelastic work is round-off of the elastic energy change; q's work is exact.
  EXPECT_GT(run.work_error, -1.0);  // some point had q > 0 (work_error stays 0 otherwise; checked next)
  EXPECT_LT(run.work_error, 1e-6);
  EXPECT_LT(run.largest_idle_work, 1.0);  // every point is compressed: nowhere is q = 0
  const HomogeneousRun plain = homogeneous_run(F_of_t, 1e-7, 20, false);
  EXPECT_NE(plain.final_stress[0], run.final_stress[0]);
}

TEST(CorrBulkViscosity, ExpansionAndRigidRotationAreUntouched) {
  const auto expansion = [](double t) {
    Mat3 F = Mat3::Identity();
    F(0, 0) += 2e4 * t;
    F(1, 1) += 1e4 * t;
    return F;
  };
  const auto rotation = [](double t) {
    const double a = 1e5 * t;  // 0.1 rad over the run
    Mat3 R;
    R << std::cos(a), -std::sin(a), 0,  //
        std::sin(a), std::cos(a), 0,    //
        0, 0, 1;
    return R;
  };
  for (const bool rotate : {false, true}) {
    const HomogeneousRun with = rotate ? homogeneous_run(rotation, 1e-7, 10, true)
                                       : homogeneous_run(expansion, 1e-7, 10, true);
    const HomogeneousRun without = rotate ? homogeneous_run(rotation, 1e-7, 10, false)
                                          : homogeneous_run(expansion, 1e-7, 10, false);
    ASSERT_EQ(with.final_stress.size(), without.final_stress.size());
    for (std::size_t i = 0; i < with.final_stress.size(); ++i)
      ASSERT_EQ(with.final_stress[i], without.final_stress[i]) << (rotate ? "rotation" : "expansion") << ", point " << i;
    EXPECT_EQ(with.largest_idle_work, without.largest_idle_work);
  }
}

struct ShockResult {
  double energy_error;     ///< |KE + elastic + dissipated − KE0| / KE0 at the end
  double middle_velocity;  ///< RMS of v_x over the middle slab, averaged over the second half of the run (m/s)
  double dissipated;       ///< dissipated / KE0 at the end
};

/// A 40 × 6 × 6 block whose halves move at ±v0 along x toward each other: two plane shocks run out from the
/// middle plane, behind which the material is at rest under pressure ρ c v0. Velocity Verlet, hypoelastic law.
ShockResult collide_halves(bool viscous) {
  testing::CloudSetup setup;
  setup.cells[0] = 40;
  setup.cells[1] = setup.cells[2] = 6;
  auto cloud = testing::make_cloud(setup);
  if (viscous) set_viscosity(cloud->ctx);
  const Discretization& disc = cloud->disc;
  const std::size_t n = disc.num_points();
  const double v0 = 50, middle = 20 * cloud->spacing;
  const double dt = 0.3 * cloud->spacing / p_wave_speed(aluminium());
  VectorField u(n), v(n), f(n);
  for (std::size_t i = 0; i < n; ++i) v(i, 0) = disc.x(i, 0) < middle ? v0 : -v0;
  double ke0 = 0;
  for (std::size_t i = 0; i < n; ++i) ke0 += 0.5 * density * disc.volume[i] * v0 * v0;
  CorrespondenceBlock<Hypoelastic> block(aluminium(), {0, n});
  StressFields stress;
  stress.resize(n);
  KinematicFields kin;
  std::vector<double> dissipated(n, 0.0);
  // The shocks reach x = middle ± 12Δx (outside the slab measured) after about 12Δx/c = 40 steps.
  const int steps = 40;
  double rms_sum = 0;
  int rms_samples = 0;
  for (int step = 0; step < steps; ++step) {
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        v(i, d) += 0.5 * dt * f(i, d) / density;
        u(i, d) += dt * v(i, d);
      }
    compute_kinematics(cloud->ctx, u, v, kin);
    update_block_stress(cloud->ctx, kin, dt, block, stress, dissipated.data());
    compute_correspondence_force(cloud->ctx, kin, stress, u, v, f);
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) v(i, d) += 0.5 * dt * f(i, d) / density;
    if (step >= steps / 2) {
      double sum = 0;
      int count = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (std::abs(disc.x(i, 0) - middle) < 6 * cloud->spacing) {
          sum += v(i, 0) * v(i, 0);
          ++count;
        }
      rms_sum += std::sqrt(sum / count);
      ++rms_samples;
    }
  }
  double ke = 0, elastic = 0, lost = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double m = density * disc.volume[i];
    ke += 0.5 * m * (v(i, 0) * v(i, 0) + v(i, 1) * v(i, 1) + v(i, 2) * v(i, 2));
    elastic += disc.volume[i] * elastic_energy_density(stress.unrotated_stress.get(i),
                                                       kin.deformation_gradient.get(i).determinant(),
                                                       aluminium().bulk, aluminium().shear);
    lost += disc.volume[i] * dissipated[i];
  }
  return {std::abs(ke + elastic + lost - ke0) / ke0, rms_sum / rms_samples, lost / ke0};
}

TEST(CorrBulkViscosity, CollidingHalvesConserveEnergy) {
  const ShockResult plain = collide_halves(false), viscous = collide_halves(true);
  std::printf("colliding halves at ±50 m/s: behind the shocks v_x RMS %.2f m/s without viscosity, %.2f m/s with; "
              "energy error %.2e / %.2e; dissipated %.3f of KE0 with\n",
              plain.middle_velocity, viscous.middle_velocity, plain.energy_error, viscous.energy_error,
              viscous.dissipated);
  EXPECT_LT(plain.energy_error, 2e-3);
  EXPECT_LT(viscous.energy_error, 2e-3);
  EXPECT_GT(viscous.dissipated, 0.0);
  EXPECT_LT(plain.dissipated, 1e-9);  // the hypoelastic law: round-off only
}

}  // namespace
}  // namespace peridot
