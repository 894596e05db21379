// A known defect of the correspondence model, kept as a disabled test until it is fixed (run it with
// --gtest_also_run_disabled_tests --gtest_filter='CorrSurfaceRelease.*').
//
// A cube held at a uniform pressure p and let go: at its free faces the pressure is released. In the continuum
// the release wave leaves the material behind it at rest in stress (σ_xx = 0 at the face) moving outward at
// p/(ρ c), c the P-wave speed, until the waves from the other faces arrive. In the correspondence model the
// layer of points within about a horizon of the face does not settle: it oscillates against the material
// behind it, with a period of about 2δ/c, and its stress swings from −p to about +0.8p (tension) and back.
// Measured here (16³ points, Δx = 1 mm, δ = 3.015Δx, C_HG = 0.02, p = 1 GPa, to 0.87 µs, before the lateral
// release arrives): the middle of a face peaks at σ_xx = +0.78 GPa, moving at 86 m/s (the continuum: 60 m/s)
// and then falling back to 10 m/s. The amplitude is the same at 24³ points, Δx = 0.67 mm (+0.75 GPa, period
// shorter in proportion), with the other influence functions, and with δ = 1.5Δx or 2Δx; a bulk viscosity
// (C_l up to 0.5, in expansion too) or a Kelvin–Voigt viscosity of 0.3 ρ c Δx lowers it by at most a third.
// It is the reason the impact face of a Taylor rod fails under Johnson–Cook damage at any speed
// (examples/taylor_impact/README.md, "High-speed failure"): the edge of the face goes through this tension
// within 0.4 µs of impact.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "peridot/correspondence/force.hpp"
#include "peridot/correspondence/hypoelastic.hpp"
#include "support/correspondence_cloud.hpp"

namespace peridot {
namespace {

using namespace correspondence;

TEST(CorrSurfaceRelease, DISABLED_FreeFaceCarriesNoTensionAfterTheRelease) {
  testing::CloudSetup setup;
  setup.cells[0] = setup.cells[1] = setup.cells[2] = 16;
  auto cloud = testing::make_cloud(setup);
  const double density = 2700, pressure = 1e9;
  const Hypoelastic law = Hypoelastic::from_young_poisson(68.9e9, 0.333);
  cloud->ctx.hourglass_stiffness = {hourglass_stiffness(0.02, law.bulk, cloud->horizon)};
  const Discretization& disc = cloud->disc;
  const std::size_t n = disc.num_points();
  const double c = std::sqrt((law.bulk + 4 * law.shear / 3) / density), dt = 0.2 * cloud->spacing / c;
  const double release_velocity = pressure / (density * c);
  VectorField u(n), v(n), f(n);
  CorrespondenceBlock<Hypoelastic> block(law, {0, n});
  StressFields stress;
  stress.resize(n);
  KinematicFields kin;
  // The held state: τ = σ = −p I at u = 0, and its force.
  compute_kinematics(cloud->ctx, u, v, kin);
  for (std::size_t i = 0; i < n; ++i) {
    stress.unrotated_stress.set(i, -pressure * Mat3::Identity());
    stress.cauchy_stress.set(i, -pressure * Mat3::Identity());
    stress.force_tensor.set(i, -pressure * kin.shape_inverse.get(i));
  }
  compute_correspondence_force(cloud->ctx, kin, stress, u, v, f);
  // The point of the face x = 0 nearest the middle of the face.
  const double side = 16 * cloud->spacing;
  std::size_t probe = 0;
  double best = 1e300;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = std::hypot(disc.x(i, 0), disc.x(i, 1) - side / 2, disc.x(i, 2) - side / 2);
    if (d < best) best = d, probe = i;
  }
  // Until the release from the faces y, z = 0, L reaches the probe's family: (L/2 − δ)/c.
  const int steps = static_cast<int>((side / 2 - cloud->horizon) / c / dt);
  double largest_tension = -1e300, fastest = 0;
  for (int step = 0; step < steps; ++step) {
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        v(i, d) += 0.5 * dt * f(i, d) / density;
        u(i, d) += dt * v(i, d);
      }
    compute_kinematics(cloud->ctx, u, v, kin);
    update_block_stress(cloud->ctx, kin, dt, block, stress);
    compute_correspondence_force(cloud->ctx, kin, stress, u, v, f);
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) v(i, d) += 0.5 * dt * f(i, d) / density;
    largest_tension = std::max(largest_tension, stress.cauchy_stress.get(probe)(0, 0));
    fastest = std::max(fastest, -v(probe, 0));
  }
  std::printf("released face: largest σ_xx %.0f MPa (p = %.0f MPa), fastest outward velocity %.1f m/s (continuum "
              "%.1f m/s), over %.2f µs\n",
              largest_tension / 1e6, pressure / 1e6, fastest, release_velocity, steps * dt * 1e6);
  EXPECT_LT(largest_tension, 0.1 * pressure);
  EXPECT_LT(fastest, 1.1 * release_velocity);
}

}  // namespace
}  // namespace peridot
