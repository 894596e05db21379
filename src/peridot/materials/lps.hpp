#pragma once
// Linear peridynamic solid (LPS), ordinary state-based.
// Silling, Epton, Weckner, Xu & Askari, J. Elasticity 88 (2007) 151–184; docs/algorithms.md §2:
//   m = Σ ω ξ² V,  θ = (3/m) Σ ω ξ e V,  t = (3Kθ/m) ω ξ + (15G/m) ω e^d,  e^d = e − θξ/3,
//   W = Kθ²/2 + (15G/2m) Σ ω (e^d)² V.
// 2D (docs/algorithms.md §3, derived there and checked by the patch tests):
//   θ₂ = (2/m) Σ ω ξ e V (= ε₁₁ + ε₂₂ for homogeneous strain),
//   t = (ω/m)[2K′ θ₂ ξ + 8G (e − θ₂ξ/2)],  W = K′θ₂²/2 + (4G/m) Σ ω (e − θ₂ξ/2)² V,
//   K′ = K + G/3 (plane strain) or 9KG/(3K + 4G) (plane stress).
// One form covers both: t = (ω/m)[α_v θ ξ + α_d (e − θξ/n)] with (n, α_v, α_d) = (3, 3K, 15G) in 3D
// and (2, 2K′, 8G) in 2D; W = α_v θ²/(2n) + (α_d/2m) Σ ω (e − θξ/n)² V. Since Σ ω ξ (e − θξ/n) V = 0,
// t = ∂W/∂e exactly.
#include <array>
#include <cstdint>

#include "peridot/materials/material.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

struct Lps {
  static constexpr bool uses_dilatation = true;
  static constexpr int bond_history_arrays = 0;
  /// Per-point scratch of this model that a partner's force reads (exchanged to ghosts): none.
  static constexpr std::array<std::vector<double> MaterialHistory::*, 0> partner_point_scratch{};
  /// The extension a bond adds to the dilatation sum.
  static double dilatation_extension(const KernelFields&, std::uint64_t /*bond*/, double e) { return e; }

  /// 1/m is precomputed per point: a kernel multiplies, never divides, per bond.
  static double force_scalar(const MaterialParams& p, const KernelFields& s, std::size_t i, std::uint64_t /*bond*/,
                             double e, double xi, double omega) {
    const double theta = s.theta[i];
    return omega * s.inverse_m[i] *
           (p.alpha_volumetric * theta * xi + p.alpha_deviatoric * (e - theta * xi * p.inverse_dilatation_factor));
  }
  static double bond_energy(const MaterialParams& p, const KernelFields& s, std::size_t i, std::uint64_t /*bond*/,
                            double e, double xi, double omega) {
    const double ed = e - s.theta[i] * xi * p.inverse_dilatation_factor;
    return 0.5 * p.alpha_deviatoric * s.inverse_m[i] * omega * ed * ed;
  }
  static double point_energy(const MaterialParams& p, const KernelFields& s, std::size_t i) {
    return p.alpha_volumetric * s.theta[i] * s.theta[i] / (2 * p.dilatation_factor);
  }
};

}  // namespace peridot
