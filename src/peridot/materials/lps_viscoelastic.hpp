#pragma once
// Viscoelastic ordinary state-based solid: the nonlocal standard linear solid of Mitchell (SAND2011-8064, 2011;
// docs/algorithms.md §8). The bulk response is the elastic LPS of
// lps.hpp; the deviatoric response is an equilibrium spring in parallel with a Maxwell branch (spring and
// dashpot) that carries the fraction λ_i of the deviatoric stiffness and relaxes with time constant τ_b:
//   (V1) t = (ω/m)[α_v θ ξ + α_d ((1 − λ_i) e^d + λ_i (e^d − e^b))],  e^d = e − θξ/n  (n, α_v, α_d: lps.hpp)
//   (V2) back extension: ė^b = (e^d − e^b)/τ_b, e^b = 0 at t = 0
//   (V3) exact integral of (V2) for e^d linear over the step, ε = exp(−Δt/τ_b), β = 1 − (τ_b/Δt)(1 − ε):
//        e^b_{n+1} = ε e^b_n + (1 − ε) e^d_n + β (e^d_{n+1} − e^d_n)
//        — unconditionally stable: the viscous part sets no limit on Δt.
//   (V4) dissipation density of the dashpots, integrated exactly for the same e^d(t): with z = e^d − e^b,
//        ż = ė^d − z/τ_b, D = Σ (λ_i α_d ω/(m τ_b)) ∫ z² dt V; over a step with ė^d = ρ and z_n,
//        ∫ z² dt = z_n² (τ/2)(1 − ε²) + z_n ρ τ²(1 − ε)² + ρ²τ³ g(Δt/τ) (materials/maxwell_element.hpp).
//   (V5) stored energy W = α_v θ²/(2n) + (α_d/2m) Σ ω [(1 − λ_i)(e^d)² + λ_i (e^d − e^b)²] V.
// λ_i = 0 is the elastic LPS; λ_i = 1 relaxes the shear completely (a nonlocal Maxwell fluid in shear).
// History: MaterialHistory::bond[0] = e^b and bond[1] = e^d of the last completed step, per bond;
// dissipation = D per point. Instantaneous (glassy) response α_d, relaxed (equilibrium) (1 − λ_i) α_d.
#include <cstdint>
#include <string_view>
#include <vector>

#include "peridot/deck/model_schema.hpp"
#include "peridot/materials/lps.hpp"
#include "peridot/materials/model_base.hpp"

namespace peridot {

struct LpsViscoelastic : ModelBase {
  static constexpr std::string_view name = "lps_viscoelastic";
  static ModelInfo info();
  static constexpr bool uses_dilatation = true;
  static constexpr int quadrature_moment_power = 2;
  static constexpr int bond_history_arrays = 2;  ///< bond[0] = e^b, bond[1] = e^d of the last step

  struct Params : LpsConstants {
    double relaxing_fraction = 0;  ///< λ_i (-)
    double relaxation_time = 0;    ///< τ_b (s)
    /// For the current Δt (set_time_step): ε = exp(−Δt/τ_b) and β = 1 − (τ_b/Δt)(1 − ε); Δt = 0 gives
    /// ε = 1, β = 0: no time passes.
    double viscous_decay = 1;
    double viscous_ramp = 0;
  };
  static Params resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block);
  static void set_time_step(Params& p, double dt);

  /// e^b at the end of the step being computed (V3): a function of this step's e^d.
  static double back_extension(const Params& p, const KernelFields& s, std::uint64_t b, double ed) {
    return p.viscous_decay * s.bond[0][b] + (1 - p.viscous_decay) * s.bond[1][b] + p.viscous_ramp * (ed - s.bond[1][b]);
  }
  static double force_scalar(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t b,
                             double e, double xi, double omega) {
    const double theta = s.theta[i];
    const double ed = e - theta * xi * p.inverse_dilatation_factor;
    return omega * s.inverse_m[i] *
           (p.alpha_volumetric * theta * xi + p.alpha_deviatoric * (ed - p.relaxing_fraction * back_extension(p, s, b, ed)));
  }
  /// (V5) with the committed e^b: call after commit (or with Δt = 0, when the force uses that e^b too).
  static double bond_energy(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t b,
                            double e, double xi, double omega) {
    const double ed = e - s.theta[i] * xi * p.inverse_dilatation_factor;
    const double z = ed - s.bond[0][b];
    return 0.5 * p.alpha_deviatoric * s.inverse_m[i] * omega *
           ((1 - p.relaxing_fraction) * ed * ed + p.relaxing_fraction * z * z);
  }
  static double point_energy(const Params& p, const KernelFields& s, std::size_t i) {
    return p.alpha_volumetric * s.theta[i] * s.theta[i] / (2 * p.dilatation_factor);
  }

  /// Makes the step final: e^b and e^d advance (V3), the dissipation (V4) accumulates. Δt as in set_time_step.
  static void commit(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                     MaterialHistory& history, const MaterialParams& block, const Params& p, BlockRange range, double dt);
};

}  // namespace peridot
