#pragma once
// Closed-form creep of a Prony solid, the reference of the viscoelastic validations (docs/algorithms.md §11).
// Shear relaxation modulus μ(t) = μ∞ + Σᵢ μᵢ exp(−t/τᵢ), λᵢ = 1/τᵢ. Under a shear stress history τ(t) the strain
// is γ(t) = ∫ J(t − s) dτ(s), with the creep compliance J the inverse of μ in the Laplace domain:
//   s μ̂(s) · s Ĵ(s) = 1,   s μ̂(s) = g(s) = μ∞ + Σᵢ μᵢ s/(s + λᵢ),   so   Ĵ(s) = 1/(s g(s)).
// g has one root ρ_k in (−λ₁, 0) and one in each (−λ_{k+1}, −λ_k) (λ ascending: g runs from −∞ to +∞ between
// consecutive poles, and from −∞ to μ∞ > 0 on (−λ₁, 0)), N roots for N terms, so
//   J(t) = 1/μ∞ + Σ_k exp(ρ_k t) / (ρ_k g′(ρ_k)),   g′(s) = Σᵢ μᵢ λᵢ/(s + λᵢ)²,
// the residues of Ĵ at 0 and at the ρ_k. J(0) = 1/(μ∞ + Σ μᵢ) (glassy), J(∞) = 1/μ∞ (relaxed). A stress τ0
// applied at t = 0 and removed at t₁ (creep and recovery) gives γ(t) = τ0 [J(t) − H(t − t₁) J(t − t₁)].
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace peridot::testing {

struct PronySeries {
  double equilibrium = 0;      ///< μ∞ (> 0: a solid)
  std::vector<double> moduli;  ///< μᵢ
  std::vector<double> times;   ///< τᵢ, distinct

  double relaxation(double t) const {
    double mu = equilibrium;
    for (std::size_t i = 0; i < moduli.size(); ++i) mu += moduli[i] * std::exp(-t / times[i]);
    return mu;
  }
  /// ∫_a^b μ(t − s) ds in closed form (t ≥ b ≥ a): τᵢ e^{−(t−b)/τᵢ} (1 − e^{−(b−a)/τᵢ}) per term, with expm1 so
  /// that a τᵢ far beyond b − a keeps its μᵢ (b − a).
  double relaxation_integral(double t, double a, double b) const {
    double sum = equilibrium * (b - a);
    for (std::size_t i = 0; i < moduli.size(); ++i)
      sum += -moduli[i] * times[i] * std::exp(-(t - b) / times[i]) * std::expm1(-(b - a) / times[i]);
    return sum;
  }
};

/// J(t) = 1/μ∞ + Σ_k amplitude_k exp(rate_k t).
struct CreepCompliance {
  double relaxed = 0;
  std::vector<double> amplitude, rate;

  double operator()(double t) const {
    double j = relaxed;
    for (std::size_t k = 0; k < rate.size(); ++k) j += amplitude[k] * std::exp(rate[k] * t);
    return j;
  }
};

inline CreepCompliance creep_compliance(const PronySeries& p) {
  if (!(p.equilibrium > 0)) throw std::invalid_argument("creep_compliance: μ∞ must be positive (a solid)");
  std::vector<double> lambda;
  for (double tau : p.times) lambda.push_back(1 / tau);
  std::vector<std::size_t> order(lambda.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  for (std::size_t i = 1; i < order.size(); ++i)  // ascending λ
    for (std::size_t k = i; k > 0 && lambda[order[k]] < lambda[order[k - 1]]; --k) std::swap(order[k], order[k - 1]);
  auto g = [&](double s) {
    double value = p.equilibrium;
    for (std::size_t i = 0; i < lambda.size(); ++i) value += p.moduli[i] * s / (s + lambda[i]);
    return value;
  };
  auto dg = [&](double s) {
    double value = 0;
    for (std::size_t i = 0; i < lambda.size(); ++i) value += p.moduli[i] * lambda[i] / ((s + lambda[i]) * (s + lambda[i]));
    return value;
  };
  CreepCompliance j;
  j.relaxed = 1 / p.equilibrium;
  for (std::size_t k = 0; k < order.size(); ++k) {
    // The root between −λ_(k+1) (or −λ₁ for k = 0) and −λ_k (or 0): g < 0 at the left end, > 0 at the right.
    double lo = -lambda[order[k]], hi = k == 0 ? 0.0 : -lambda[order[k - 1]];
    for (int iteration = 0; iteration < 400; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;  // as narrow as doubles go
      (g(mid) < 0 ? lo : hi) = mid;
    }
    const double root = 0.5 * (lo + hi);
    j.rate.push_back(root);
    j.amplitude.push_back(1 / (root * dg(root)));
  }
  return j;
}

}  // namespace peridot::testing
