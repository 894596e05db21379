// Flanagan–Taylor incremental rotation (docs/algorithms.md §6; Foster, Silling & Chen 2010 eqs 15–18):
// a constant-rate rigid rotation is recovered to round-off with V = I and d = 0; for rotation with stretch,
// R converges to the rotation of the polar decomposition of F and stays orthogonal.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "peridot/correspondence/flanagan_taylor.hpp"
#include "peridot/correspondence/kinematics.hpp"

namespace peridot {
namespace {

using correspondence::Mat3;
using correspondence::PolarState;
using correspondence::Vec3d;

Mat3 rotation(const Vec3d& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

/// Drives Flanagan–Taylor through F(t_k), k = 0…steps, with the mid-step L of the peridynamic step.
/// Returns the largest ‖d‖ seen (1/s) and leaves the final R, V in `polar`.
double drive(const std::function<Mat3(double)>& F_of_t, double dt, int steps, PolarState& polar) {
  double largest_d = 0;
  for (int k = 0; k < steps; ++k) {
    const Mat3 F0 = F_of_t(k * dt), F1 = F_of_t((k + 1) * dt);
    const Mat3 L = correspondence::mid_step_velocity_gradient(F1, (F1 - F0) / dt, dt);
    largest_d = std::max(largest_d, correspondence::flanagan_taylor_update(L, dt, polar).norm());
  }
  return largest_d;
}

TEST(CorrFlanaganTaylor, RecoversConstantRateRotation) {
  const Vec3d axis(1, 2, 3);
  const double rate = 2000;  // rad/s
  const double dt = 1e-6;
  const int steps = 2000;  // 4 rad, more than half a turn
  PolarState polar;
  const double largest_d = drive([&](double t) { return rotation(axis, rate * t); }, dt, steps, polar);
  const Mat3 exact = rotation(axis, rate * steps * dt);
  EXPECT_LT((polar.rotation - exact).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((polar.left_stretch - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  // d = 0 up to round-off of L (|L| = 2000/s): no strain rate from a rigid rotation.
  EXPECT_LT(largest_d, 1e-12 * rate);
  // Orthogonality is lost only to round-off, at most a few ε per step.
  EXPECT_LT((polar.rotation.transpose() * polar.rotation - Mat3::Identity()).norm(),
            4 * steps * std::numeric_limits<double>::epsilon());
}

TEST(CorrFlanaganTaylor, RotationWithStretchConvergesToPolarDecomposition) {
  // F(t) = R(t) U(t): a rotation about a tilting axis times a growing non-diagonal stretch, t ∈ [0, 1] s
  // (the kind of test described in docs/algorithms.md §6).
  auto F_of_t = [](double t) {
    const Mat3 R = rotation(Vec3d(1, 0, 0), 1.2 * t) * rotation(Vec3d(0, 1, 1), 0.8 * t * t);
    Mat3 U;
    U << 1 + 0.3 * t, 0.1 * t, 0.05 * t,  //
        0.1 * t, 1 - 0.2 * t, 0.02 * t,   //
        0.05 * t, 0.02 * t, 1 + 0.1 * t;
    return Mat3(R * U);
  };
  const Mat3 F_end = F_of_t(1.0);
  const Eigen::JacobiSVD<Mat3> svd(F_end, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Mat3 R_exact = svd.matrixU() * svd.matrixV().transpose();
  const Mat3 V_exact = F_end * R_exact.transpose();
  double previous_error = 0;
  for (int steps : {100, 200, 400, 800}) {
    PolarState polar;
    drive(F_of_t, 1.0 / steps, steps, polar);
    const double error = (polar.rotation - R_exact).norm();
    const double stretch_error = (polar.left_stretch - V_exact).norm();
    std::printf("steps %4d: |R - R_polar| = %.3e, |V - V_polar| = %.3e\n", steps, error, stretch_error);
    EXPECT_LT((polar.rotation.transpose() * polar.rotation - Mat3::Identity()).norm(), 1e-13);
    EXPECT_NEAR(polar.rotation.determinant(), 1.0, 1e-13);
    // First-order convergence at least (forward-Euler V): halving Δt at least roughly halves the error.
    if (previous_error > 0) {
      EXPECT_LT(error, 0.55 * previous_error);
    }
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-3);
}

}  // namespace
}  // namespace peridot
