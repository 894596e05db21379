#pragma once
// Prototype microelastic brittle (PMB) bond-based model.
// Silling & Askari, Comput. Struct. 83 (2005) 1526–1535; calibration: docs/algorithms.md §2:
//   pair force f = c s (y′ − y)/|y′ − y|, s = (|Y| − |ξ|)/|ξ|, T⟨ξ⟩ = ½ f, pair energy w = ½ c s² |ξ|.
// With an influence function the micromodulus is c(ξ) = c0 ω(ξ), c0 calibrated so that an isotropic
// strain gives the classical energy density (3D: W = 9Ks²/2 → c0 = 9K / (2π ∫₀^δ ω ξ³ dξ), which is
// 18K/(πδ⁴) for ω = 1; 2D, thickness h: W = 2K′s² → c0 = 4K′ / (πh ∫₀^δ ω ξ² dξ), 12K′/(πhδ³) for ω = 1;
// 1D, a bar of area A: W = Eε²/2 → c0 = E / (A ∫₀^δ ω ξ dξ), 2E/(Aδ²) for ω = 1).
// Bond-based models force ν = 1/4 (3D, plane strain) or 1/3 (plane stress).
#include <cstdint>
#include <string_view>

#include "peridot/deck/model_schema.hpp"
#include "peridot/materials/model_base.hpp"

namespace peridot {

struct Pmb : ModelBase {
  static constexpr std::string_view name = "pmb";
  static ModelInfo info();
  /// surface_correction: the bond loops hand the kernels ω G (the pair's micromodulus c0 ω G).
  static constexpr bool corrects_surfaces = true;
  static constexpr int quadrature_moment_power = 1;

  struct Params {
    /// Micromodulus c0 (N/m⁶ in 3D): bond micromodulus c(ξ) = c0 ω(ξ).
    double micromodulus = 0;
  };
  static Params resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block);

  /// Scalar force state t = T⟨ξ⟩·M (N/m⁶) of a bond of reference length xi and extension e.
  static double force_scalar(const Params& p, const KernelFields&, std::size_t /*point*/, std::uint64_t /*bond*/,
                             double e, double xi, double omega) {
    return 0.5 * p.micromodulus * omega * e / xi;
  }
  /// This point's share of the bond energy density per unit neighbour volume (J/m⁶): ½ · ½ c s² ξ.
  static double bond_energy(const Params& p, const KernelFields&, std::size_t /*point*/, std::uint64_t /*bond*/,
                            double e, double xi, double omega) {
    return 0.25 * p.micromodulus * omega * e * e / xi;
  }
  static double point_energy(const Params&, const KernelFields&, std::size_t /*point*/) { return 0; }
};

/// The Poisson ratio a bond-based model implies: 1/3 in plane stress, 1/4 otherwise.
constexpr double pmb_implied_poisson_ratio(PlaneKind plane) { return plane == PlaneKind::stress ? 1.0 / 3.0 : 0.25; }

}  // namespace peridot
