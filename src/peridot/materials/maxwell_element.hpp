#pragma once
// The one integral the viscous models need over a step: a Maxwell element (spring and dashpot of relaxation
// time τ in series) whose total extension grows at a constant rate ρ over the step has a spring extension x with
// ẋ = ρ − x/τ, so x(t) = ρτ + (x₀ − ρτ) e^{−t/τ}; its dashpot dissipates in proportion to ∫ x² dt.
// lps_viscoelastic (V4) and thermoviscoelastic (M6) integrate their dissipation with it.

namespace peridot {

/// ∫₀^Δt x(t)² dt for ẋ = ρ − x/τ, x(0) = x₀: with a = ρτ, c = x₀ − ρτ, a²Δt + 2aτc(1 − ε) + c²(τ/2)(1 − ε²),
/// ε = e^{−Δt/τ}. 1 − ε and 1 − ε² are passed in (from expm1, so that Δt ≪ τ keeps its digits, and computed
/// once per step by the caller).
inline double maxwell_square_integral(double rate, double start, double tau, double dt, double one_minus_decay,
                                      double one_minus_decay2) {
  const double a = rate * tau, c = start - a;
  return a * a * dt + 2 * a * tau * c * one_minus_decay + c * c * 0.5 * tau * one_minus_decay2;
}

}  // namespace peridot
