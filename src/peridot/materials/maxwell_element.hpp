#pragma once
// The one integral the viscous models need over a step: a Maxwell element (spring and dashpot of relaxation
// time τ in series) whose total extension grows at a constant rate ρ over the step has a spring extension x with
// ẋ = ρ − x/τ, so x(t) = x₀ ε(t) + ρτ (1 − ε(t)), ε(t) = e^{−t/τ}; its dashpot dissipates in proportion to
// ∫ x² dt. lps_viscoelastic (V4) and thermoviscoelastic (M6) integrate their dissipation with it.
//
// Written as x₀² ∫ε² + 2x₀ρτ ∫ε(1 − ε) + ρ²τ² ∫(1 − ε)², every integral in closed form and without
// cancellation: the form a²Δt + 2aτc(1 − ε) + c²(τ/2)(1 − ε²), a = ρτ, c = x₀ − a, adds terms of size
// ρ²τ²Δt to get about ρ²Δt³/3 when Δt ≪ τ, and lost a factor (τ/Δt)² of its precision (errors of 1e-10 of
// the dissipation at Δt = τ/1000, different on each SIMD target).
#include <cmath>

namespace peridot {

/// The step's constants of one Maxwell element, computed once per step (and relaxation time).
struct MaxwellStep {
  double start_square = 0;  ///< ∫₀^Δt ε² dt = τ(1 − ε²)/2
  double cross = 0;         ///< 2τ ∫₀^Δt ε(1 − ε) dt = τ²(1 − ε)²
  double rate_square = 0;   ///< τ² ∫₀^Δt (1 − ε)² dt = τ³ g(Δt/τ), g(h) = h − 2(1 − e^{−h}) + (1 − e^{−2h})/2

  MaxwellStep() = default;
  MaxwellStep(double tau, double dt) {
    const double h = dt / tau;
    const double one_minus_decay = -std::expm1(-h);  // expm1: Δt ≪ τ keeps its digits
    start_square = 0.5 * tau * -std::expm1(-2 * h);
    cross = tau * tau * one_minus_decay * one_minus_decay;
    rate_square = tau * tau * tau * ramp_square(h);
  }

  /// ∫₀^Δt x(t)² dt for ẋ = ρ − x/τ, x(0) = x₀.
  double integral(double rate, double start) const {
    return start * start * start_square + start * rate * cross + rate * rate * rate_square;
  }

  /// g(h) = ∫₀^h (1 − e^{−s})² ds = h³/3 − h⁴/4 + …: its Taylor series, Σ_{k≥3} (−1)^{k+1} (2^{k−1} − 2) h^k/k!,
  /// below h = 1/2 (18 terms: the next is below 1e-16 of the sum), the closed form above (its cancellation
  /// costs a relative error of about 3ε/h²: 3e-15 at h = 1/2, less above).
  static double ramp_square(double h) {
    if (h > 0.5) return h + 2 * std::expm1(-h) - 0.5 * std::expm1(-2 * h);
    double sum = 0, power = h * h, factorial = 2, two_power = 2;  // h^k, k!, 2^{k−1} for k = 2
    for (int k = 3; k <= 20; ++k) {
      power *= h, factorial *= k, two_power *= 2;
      sum += (k % 2 == 1 ? 1 : -1) * (two_power - 2) / factorial * power;
    }
    return sum;
  }
};

}  // namespace peridot
