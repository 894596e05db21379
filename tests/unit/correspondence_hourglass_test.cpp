// Hourglass (zero-energy mode) control of the correspondence model (docs/algorithms.md §7, force.hpp).
// The checkerboard displacement u_i = a s_i e_x, s_i = (−1)^(i+j+k) on a cubic lattice, leaves F = I at every
// point whose family is point-symmetric (odd neighbours all move by −2a s_i e_x, and Σ_odd ξ = 0), so the
// correspondence force of eq 25 cannot resist it. A small explicit dynamic run (velocity Verlet, the step
// order of docs/algorithms.md §5: F at u^{n+1}, Ḟ from v^{n+1/2}) started with a checkerboard velocity
// shows the mode drifting away without control and oscillating, bounded, with C_HG = 0.05 (the default) and
// 0.02 (the Taylor example); with the hourglass dashpots (C_HV) the oscillation dies away.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "peridot/correspondence/force.hpp"
#include "peridot/correspondence/hypoelastic.hpp"
#include "support/correspondence_cloud.hpp"

namespace peridot {
namespace {

using namespace correspondence;

struct ModeHistory {
  std::vector<double> amplitude;  ///< checkerboard component of u_x over the deep interior, (1/N) Σ s_i u_x,i (m)
};

ModeHistory run_checkerboard(double hourglass_coefficient, int steps, double dt, double hourglass_viscosity = 0) {
  // 14³ points, δ = 3.015 Δx: the 2³ points deeper than 2δ have complete families whose neighbours have
  // complete families too; there the checkerboard is exactly zero-energy, and there it is measured. The
  // surface layers do resist the mode, and slowly feed back into the interior.
  testing::CloudSetup setup;
  setup.cells[0] = setup.cells[1] = setup.cells[2] = 14;
  auto cloud = testing::make_cloud(setup);
  const Discretization& disc = cloud->disc;
  const std::size_t n = disc.num_points();
  const Hypoelastic law = Hypoelastic::from_young_poisson(68.9e9, 0.333);
  const double density = 2700;  // kg/m³
  cloud->ctx.hourglass_stiffness = {hourglass_stiffness(hourglass_coefficient, law.bulk, cloud->horizon)};
  cloud->ctx.hourglass_damping = {hourglass_damping(hourglass_viscosity, density, law.bulk, cloud->horizon)};

  std::vector<double> sign(n);
  for (std::size_t i = 0; i < n; ++i) {
    long parity = 0;
    for (int d = 0; d < 3; ++d) parity += std::lround(disc.x(i, d) / cloud->spacing - 0.5);
    sign[i] = parity % 2 == 0 ? 1.0 : -1.0;
  }
  const double v0 = 1.0;  // m/s
  VectorField u(n), v(n), f(n);
  for (std::size_t i = 0; i < n; ++i) v(i, 0) = v0 * sign[i];

  CorrespondenceBlock<Hypoelastic> block(law, {0, n});
  StressFields stress;
  stress.resize(n);
  KinematicFields kin;
  ModeHistory history;
  // f⁰ = 0: the body starts undeformed and unstressed.
  for (int step = 0; step < steps; ++step) {
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) {
        v(i, d) += 0.5 * dt * f(i, d) / density;  // v^{n+1/2}
        u(i, d) += dt * v(i, d);                   // u^{n+1}
      }
    compute_kinematics(cloud->ctx, u, v, kin);
    update_block_stress(cloud->ctx, kin, dt, block, stress);
    compute_correspondence_force(cloud->ctx, kin, stress, u, v, f);
    for (std::size_t i = 0; i < n; ++i)
      for (int d = 0; d < 3; ++d) v(i, d) += 0.5 * dt * f(i, d) / density;  // v^{n+1}
    double a = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (testing::distance_to_surface(*cloud, setup.cells, i) > 2 * cloud->horizon) {
        a += sign[i] * u(i, 0);
        ++count;
      }
    history.amplitude.push_back(a / count);
  }
  return history;
}

double max_abs(const std::vector<double>& a, std::size_t begin, std::size_t end) {
  double m = 0;
  for (std::size_t k = begin; k < end; ++k) m = std::max(m, std::abs(a[k]));
  return m;
}

TEST(CorrHourglass, CheckerboardModeGrowsWithoutControlAndStaysBoundedWithIt) {
  // Δt well below Δx/c_p = 1e-3 m / 6200 m/s ≈ 1.6e-7 s; 800 steps = 16 µs, several periods of the
  // controlled mode.
  const double dt = 2e-8;
  const int steps = 800;
  const ModeHistory free = run_checkerboard(0.0, steps, dt);
  const ModeHistory controlled = run_checkerboard(default_hourglass_coefficient, steps, dt);
  const std::size_t quarter = steps / 4, half = steps / 2;
  std::printf("checkerboard amplitude (µm) every 100 steps:\n  without control:");
  for (int k = 99; k < steps; k += 100) std::printf(" %7.3f", free.amplitude[k] * 1e6);
  std::printf("\n  C_HG = %.2f:      ", default_hourglass_coefficient);
  for (int k = 99; k < steps; k += 100) std::printf(" %7.3f", controlled.amplitude[k] * 1e6);
  const double free_first = max_abs(free.amplitude, 0, quarter), free_last = max_abs(free.amplitude, 3 * quarter, steps);
  const double ctrl_first = max_abs(controlled.amplitude, 0, half), ctrl_second = max_abs(controlled.amplitude, half, steps);
  std::printf("\n  max |a|: without control %.3f (first quarter) → %.3f (last quarter); with control %.3f (first "
              "half) → %.3f (second half)\n",
              free_first * 1e6, free_last * 1e6, ctrl_first * 1e6, ctrl_second * 1e6);
  // Without control nothing resists the mode in the interior: it drifts on (v0 t would be 16 µm at the end).
  EXPECT_GT(free_last, 2 * free_first);
  // With control it oscillates about zero with no growth, an order of magnitude below the drift.
  EXPECT_LT(ctrl_second, 1.1 * ctrl_first);
  EXPECT_LT(ctrl_first, 0.1 * free_last);
  // The Taylor impact example (examples/taylor_impact/deck.yaml) runs at C_HG = 0.02, the bottom of the Peridigm
  // range: the weaker springs hold the mode too. Measured: 0.819 µm (first half) → 0.790 µm (second half).
  const ModeHistory weak = run_checkerboard(0.02, steps, dt);
  const double weak_first = max_abs(weak.amplitude, 0, half), weak_second = max_abs(weak.amplitude, half, steps);
  std::printf("  C_HG = 0.02: max |a| %.3f (first half) → %.3f (second half)\n", weak_first * 1e6, weak_second * 1e6);
  EXPECT_LT(weak_second, 1.1 * weak_first);
  EXPECT_LT(weak_first, 0.1 * free_last);
}

TEST(CorrHourglass, DashpotsDampTheCheckerboardModeAndSpringsAloneDoNot) {
  // The Taylor example's springs (C_HG = 0.02) with and without dashpots. An impact rings this mode; the
  // springs store its energy and give it back, the dashpots dissipate it. Same run as above.
  const double dt = 2e-8;
  const int steps = 800;
  const std::size_t quarter = steps / 4;
  std::printf("checkerboard amplitude (µm) every 100 steps, C_HG = 0.02:\n");
  double first[3], last[3];
  const double viscosities[3] = {0.0, 0.02, 0.05};
  for (int k = 0; k < 3; ++k) {
    const ModeHistory h = run_checkerboard(0.02, steps, dt, viscosities[k]);
    std::printf("  C_HV = %.2f:", viscosities[k]);
    for (int s = 99; s < steps; s += 100) std::printf(" %7.3f", h.amplitude[s] * 1e6);
    first[k] = max_abs(h.amplitude, 0, quarter);
    last[k] = max_abs(h.amplitude, 3 * quarter, steps);
    std::printf("   max |a| first quarter %.3f, last quarter %.3f\n", first[k] * 1e6, last[k] * 1e6);
  }
  // Springs alone: the oscillation keeps its amplitude (within 10 %).
  EXPECT_GT(last[0], 0.9 * first[0]);
  // With dashpots it decays, faster with the larger coefficient.
  EXPECT_LT(last[1], 0.5 * first[1]);
  EXPECT_LT(last[2], 0.2 * first[2]);
  EXPECT_LT(last[2], last[1]);
}

}  // namespace
}  // namespace peridot
