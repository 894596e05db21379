// The Maxwell element's step integral ∫ x² dt (materials/maxwell_element.hpp) against a numerical quadrature
// of the closed-form x(t), from Δt far below τ (where the textbook form loses (τ/Δt)² of its digits) to far
// above it.
#include <gtest/gtest.h>

#include <cmath>

#include "peridot/materials/maxwell_element.hpp"

namespace peridot {
namespace {

/// ∫₀^Δt x(t)² dt, x(t) = x₀ e^{−t/τ} + ρτ(1 − e^{−t/τ}), by composite Gauss–Legendre (5 points, 2000 panels).
double quadrature(double rate, double start, double tau, double dt) {
  static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  static const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                   0.2369268850561891};
  const int panels = 2000;
  const double width = dt / panels;
  double sum = 0;
  for (int p = 0; p < panels; ++p)
    for (int q = 0; q < 5; ++q) {
      const double t = width * (p + 0.5 * (node[q] + 1));
      const double decay = std::exp(-t / tau);
      // 1 − e^{−t/τ} through expm1: the reference must not cancel either
      const double x = start * decay - rate * tau * std::expm1(-t / tau);
      sum += 0.5 * width * weight[q] * x * x;
    }
  return sum;
}

TEST(MaxwellStep, StepIntegralMatchesQuadratureFromTinyToLargeSteps) {
  const double tau = 2e-3;
  for (double h : {1e-6, 1e-3, 0.1, 0.49, 0.51, 2.0, 40.0})
    for (double start : {0.0, 3e-4, -1e-4}) {
      const double dt = h * tau, rate = 0.7;  // extension rate (1/s × length); x₀ in the same length
      const double exact = quadrature(rate, start, tau, dt);
      const double got = MaxwellStep(tau, dt).integral(rate, start);
      EXPECT_NEAR(got, exact, 1e-12 * std::abs(exact)) << "Δt/τ = " << h << ", x₀ = " << start;
    }
}

TEST(MaxwellStep, RampSquareSeriesAndClosedFormAgreeWhereTheyMeet) {
  // g(h) = ∫₀^h (1 − e^{−s})² ds: the series below h = 1/2, the closed form above, which keeps all but a few
  // ε there (its cancellation costs about 3ε/h²).
  const double below = MaxwellStep::ramp_square(0.5), above = MaxwellStep::ramp_square(std::nextafter(0.5, 1.0));
  EXPECT_NEAR(below, above, 5e-15 * above);
  // h³/3 − h⁴/4 + 7h⁵/60 − h⁶/24 at h = 1e-4 (the next term, 31h⁷/2520, is 4e-18 of the sum)
  const double h = 1e-4, h3 = h * h * h;
  EXPECT_NEAR(MaxwellStep::ramp_square(h), h3 * (1.0 / 3 - h / 4 + 7 * h * h / 60 - h * h * h / 24), 1e-15 * h3);
}

}  // namespace
}  // namespace peridot
