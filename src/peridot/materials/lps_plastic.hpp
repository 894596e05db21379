#pragma once
// Elastic-plastic ordinary state-based solid (Mitchell, SAND2011-3166, 2011; with critical-stretch damage:
// docs/algorithms.md §9). The LPS of lps.hpp with the deviatoric extension split additively,
// e^d = e^de + e^dp, the plastic part e^dp a history value of every bond:
//   (P1) t = (ω/m)[α_v θ ξ + α_d (e^d − e^dp − q ξ)],  e^d = e − θξ/n, θ as in (P7)  (n, α_v, α_d: lps.hpp)
//        q = Σ ω ξ (e^d − e^dp) V / m over the intact bonds (see (P6))
//   (P2) yield function f(t^d) = ‖t^d‖²/2 − ψ0(ε̄p),  ‖t^d‖² = Σ (t^d)² V over the point's intact bonds
//   (P3) trial state t^d_tr = α ω (e^d_{n+1} − e^dp_n), α = α_d/m; elastic when ‖t^d_tr‖ ≤ √(2ψ0)
//   (P4) otherwise the radial return t^d_{n+1} = r t^d_tr, r = √(2ψ0)/‖t^d_tr‖, and
//        e^dp_{n+1} = e^dp_n + (1 − r)(e^d_{n+1} − e^dp_n).
// For ω = 1 (P4) is exactly Mitchell's backward-Euler step e^dp_{n+1} = e^dp_n + Δλ t^d_{n+1},
// Δλ = (‖t^d_tr‖/√(2ψ0) − 1)/α. For another ω it is the backward-Euler step of the flow rule
// ė^dp = λ t^d/ω, which keeps the return radial (so exact in one step) and dissipates Σ λ (t^d)²/ω V ≥ 0.
//
// Calibration: ψ0 is ‖t^d‖²/2 at von Mises yield, ‖t^d‖² = (α_d/m)² Σ ω² ξ² (n·ε^d n)² V for a small
// deviatoric strain ε^d, with the direction average of (n·ε^d n)² ((2/15) ε^d:ε^d in 3D, ε^d:ε^d/4 for
// in-plane directions), so √(2ψ0) = k σ_Y with, per point, k² = c Σ_j ω² ξ² V_j / m² and
//   (C1) 3D, any deviatoric state:          c = 5    (continuum, ω = 1: ψ0 = 25σ_Y²/(8πδ⁵), docs/algorithms.md §2)
//   (C2) plane stress, in-plane uniaxial:  c = 2    (continuum, ω = 1: ψ0 = 2σ_Y²/(πhδ⁴))
//   (C3) plane strain, in-plane pure shear: c = 8/3  (continuum, ω = 1: ψ0 = 8σ_Y²/(3πhδ⁴)).
// The sums run over the point's own reference family (as m does), so the lattice quadrature of the
// radial moment cancels between the force state and the yield value. The 2D deviatoric norm sees only
// the in-plane deviator, so one 2D constant cannot match von Mises for every stress state; (C2) and (C3)
// are the states that stay exact.
//
// Hardening: linear isotropic, σ_Y = σ_y + H ε̄p, with the equivalent plastic strain defined by the
// plastic work, σ_Y Δε̄p = ΔW_p = Σ t^d_{n+1} Δe^dp V = r(1 − r) S/α, S = Σ (t^d_tr)²/ω V, so that a
// homogeneous deformation gives the classical ε̄p. Backward Euler (r uses σ_Y at n+1) is linear in Δε̄p:
//   (P5) Δε̄p = g(1 − kσ_Y,n/‖t^d_tr‖) / (1 + gkH/‖t^d_tr‖),  g = kS/(α‖t^d_tr‖);
//        σ_Y,n+1 = σ_Y,n + HΔε̄p,  r = kσ_Y,n+1/‖t^d_tr‖.
// History: MaterialHistory::bond[0] = e^dp per bond; plastic_strain = ε̄p and dissipation = W_p per point;
// the point arrays of the step (r, Δε̄p, q, ρ) and the constant k: see the struct.
// Stored (free) energy: W = α_v θ²/(2n) + (α_d/2m) Σ ω (e^d − e^dp)² V.
//   (P6) t = ∂W/∂e needs the term −(α_d/m) q ω ξ, since ∂θ/∂e couples every bond. With a full family q = 0:
//        Σ ω ξ e^d V = 0 by the definition of θ, and Σ ω ξ e^dp V = 0 is kept exactly by (P4), since
//        Σ ω ξ e^dp_{n+1} V = r Σ ω ξ e^dp_n V + (1 − r) Σ ω ξ e^d V. Once bonds break (θ over the intact
//        bonds, m over all of them, as in Peridigm) q ≠ 0, and without the term the forces are no longer
//        conservative. q_{n+1} = r q_trial, so it is found with r.
//   (P7) θ = (n/m) Σ ω ξ (e − e^dp) V over the intact bonds: the elastic volume change. On a full family it
//        is the θ of lps (Σ ω ξ e^dp V = 0, see (P6)); once bonds break it is not: the bonds that break are
//        the plastically stretched ones, and a θ of the total extensions would then see the shortened
//        survivors as a compression that never happened (a fragmenting ring gained 20 % energy that way).
//   (P8) a bond that breaks takes its share ρ = Σ_broken now ω ξ (e − e^dp) V / m out of θ, which would shift
//        e^d of every surviving bond by ρξ at once. The step in which bonds break moves the same ρξ into e^dp
//        of the survivors, so that their elastic state is continuous and breaking only releases energy.
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "peridot/deck/model_schema.hpp"
#include "peridot/materials/lps.hpp"
#include "peridot/materials/model_base.hpp"

namespace peridot {

struct LpsPlastic : ModelBase {
  static constexpr std::string_view name = "lps_plastic";
  static ModelInfo info();
  static constexpr bool uses_dilatation = true;
  static constexpr int quadrature_moment_power = 2;
  static constexpr int bond_history_arrays = 1;  ///< bond[0] = e^dp
  /// The step's scratch of the return map, per point (MaterialHistory::point[k]).
  enum PointArrayIndex { yield_scale, plastic_strain_increment, deviatoric_moment, released_extension };
  static constexpr std::array<PointArray, 4> point_arrays = {{
      {"yield_scale", 1.0},               ///< r of this step's return map: t^d = r t^d_trial, r ∈ (0, 1]
      {"plastic_strain_increment", 0.0},  ///< Δε̄p of this step
      {"deviatoric_moment", 0.0},         ///< q = Σ ω ξ (e^d − e^dp) V / m over the intact bonds
      {"released_extension", 0.0},        ///< ρ: what θ lost to the bonds that broke in this step (P8)
  }};
  /// What the force of a partner reads of a point's return map (P8, force_scalar): exchanged to ghosts
  /// after prepare.
  static constexpr std::array<int, 3> partner_point_arrays = {released_extension, yield_scale, deviatoric_moment};
  static constexpr int released_extension_array = released_extension;
  static constexpr int point_constant_arrays = 1;  ///< k of (C), ModelContext::point_constants[0]

  struct Params : LpsConstants {
    double yield_stress = 0;       ///< σ_y (Pa)
    double hardening_modulus = 0;  ///< H (Pa): σ_Y = σ_y + H ε̄p
    double yield_calibration = 0;  ///< c of (C1)–(C3)
  };
  static Params resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block);

  /// (P7) θ measures the elastic volume change: e − e^dp (equal to e's sum on a full family).
  static double dilatation_extension(const KernelFields& s, std::uint64_t b, double e, double /*xi*/) {
    return e - s.bond[0][b];
  }

  static double force_scalar(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t b,
                             double e, double xi, double omega) {
    const double theta = s.theta[i];
    const double ed = e - theta * xi * p.inverse_dilatation_factor;
    const double plastic = s.bond[0][b] + s.point[released_extension][i] * xi;  // (P8)
    return omega * s.inverse_m[i] *
           (p.alpha_volumetric * theta * xi +
            p.alpha_deviatoric * (s.point[yield_scale][i] * (ed - plastic) - s.point[deviatoric_moment][i] * xi));
  }
  static double bond_energy(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t b,
                            double e, double xi, double omega) {
    const double plastic = s.bond[0][b] + s.point[released_extension][i] * xi;
    const double elastic = e - s.theta[i] * xi * p.inverse_dilatation_factor - plastic;
    return 0.5 * p.alpha_deviatoric * s.inverse_m[i] * omega * elastic * elastic;
  }
  static double point_energy(const Params& p, const KernelFields& s, std::size_t i) {
    return p.alpha_volumetric * s.theta[i] * s.theta[i] / (2 * p.dilatation_factor);
  }

  /// k of (C) for every point of the block, into ctx.point_constants[0]; needs ctx.inverse_weighted_volume.
  /// Computed once: the sums run over the reference family, like m.
  static void calibrate(ModelContext& ctx, const MaterialParams& block, const Params& p, BlockRange range);
  /// The return map of every point of the block for the current u and θ: yield_scale r, Δε̄p and q (P3–P6).
  /// Reads the history, writes only this step's scratch, so it may run any number of times.
  static void prepare(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                      MaterialHistory& history, const MaterialParams& block, const Params& p, BlockRange range);
  /// The return map of point i from the sums of prepare over its intact bonds: ‖t^d_tr‖² = Σ (t^d_tr)² V,
  /// S = Σ (t^d_tr)²/ω V and Σ ω ξ (e^d − e^dp_n) V. (The vectorised bond loops call it too.)
  static void finish_return_map(const ModelContext& ctx, MaterialHistory& history, const Params& p, std::size_t i,
                                double norm2, double weighted, double along);
  /// What commit does for point i after its bonds' e^dp: ε̄p and W_p advance, the step's scratch is reset.
  static void finish_commit(MaterialHistory& history, const Params& p, std::size_t i);
  /// Makes the step final: e^dp, ε̄p and W_p advance with the scratch of prepare, which is reset.
  static void commit(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                     MaterialHistory& history, const MaterialParams& block, const Params& p, BlockRange range, double dt);
};

/// The constant c of (C1)–(C3): k² = c Σ ω² ξ² V / m².
double plastic_yield_calibration(int dimension, PlaneKind plane);

}  // namespace peridot
