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
// With surface_correction the bond loops hand the kernels ω̃ = G ω (G the bond's factor, solvers/
// surface_correction.hpp) and m stays the reference Σ ω ξ² V: θ = (n/m) Σ ω̃ ξ e V and
// W = α_v θ²/(2n) + (α_d/2m) Σ ω̃ (e − θξ/n)² V, whose derivative is
//   t = (ω̃/m)[α_v θ ξ + α_d (e − κ θξ/n)],  κ = 2 − m̃/m,  m̃ = Σ ω̃ ξ² V
// (Σ ω̃ ξ (e − θξ/n) V = θ(m − m̃)/n no longer vanishes); κ is a point constant (calibrate).
#include <cstdint>
#include <string_view>

#include "peridot/deck/model_schema.hpp"
#include "peridot/materials/model_base.hpp"

namespace peridot {

/// The constants of the LPS force state, shared by the models built on it (lps_plastic, lps_viscoelastic):
/// t = (ω/m)[α_v θ ξ + α_d (e − θξ/n)], θ = (n/m) Σ ω ξ e V.
struct LpsConstants {
  double alpha_volumetric = 0;
  double alpha_deviatoric = 0;
  double dilatation_factor = 3;               ///< n: 3 in 3D, 2 in 2D
  double inverse_dilatation_factor = 1.0 / 3;  ///< 1/n: the bond loops multiply, never divide
};
/// (n, α_v, α_d) = (3, 3K, 15G) in 3D and (2, 2K′, 8G) in 2D.
LpsConstants lps_constants(const ElasticConstants& elastic, const Problem& problem);

struct Lps : ModelBase {
  static constexpr std::string_view name = "lps";
  static ModelInfo info();
  static constexpr bool uses_dilatation = true;
  static constexpr bool corrects_surfaces = true;
  static constexpr int quadrature_moment_power = 2;
  /// κ = 2 − m̃/m per point (surface_correction only).
  static constexpr int point_constant_arrays = 1;

  struct Params : LpsConstants {
    bool surface_correction = false;
  };
  static Params resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block);

  /// 1/m is precomputed per point: a kernel multiplies, never divides, per bond.
  static double force_scalar(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t /*bond*/,
                             double e, double xi, double omega) {
    const double theta = s.theta[i];
    return omega * s.inverse_m[i] *
           (p.alpha_volumetric * theta * xi + p.alpha_deviatoric * (e - theta * xi * p.inverse_dilatation_factor));
  }
  /// With surface_correction (bond_loop::end_force_scalar picks it): κθ in the deviatoric term, κ = 2 − m̃/m. A kernel
  /// of its own, so that the uncorrected loops stay what they were (a select in force_scalar cost 10–20 % of a 2D
  /// run and moved its round-off).
  static double corrected_force_scalar(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t /*bond*/,
                                       double e, double xi, double omega) {
    const double theta = s.theta[i];
    const double reduced = s.point_constant[0][i] * theta;  // κθ
    return omega * s.inverse_m[i] *
           (p.alpha_volumetric * theta * xi + p.alpha_deviatoric * (e - reduced * xi * p.inverse_dilatation_factor));
  }
  static double bond_energy(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t /*bond*/,
                            double e, double xi, double omega) {
    const double ed = e - s.theta[i] * xi * p.inverse_dilatation_factor;
    return 0.5 * p.alpha_deviatoric * s.inverse_m[i] * omega * ed * ed;
  }
  static double point_energy(const Params& p, const KernelFields& s, std::size_t i) {
    return p.alpha_volumetric * s.theta[i] * s.theta[i] / (2 * p.dilatation_factor);
  }
  /// κ = 2 − m̃/m of every point of a corrected block (1 before the bond factors exist).
  static void calibrate(ModelContext& ctx, const MaterialParams& block, const Params& p, BlockRange range);
};

}  // namespace peridot
