#pragma once
// Thermoviscoelastic ordinary state-based solid of Madenci & Oterkus (J. Mech. Phys. Solids 2017, "Ordinary
// state-based peridynamics for thermoviscoelastic deformation"; docs/models/thermoviscoelastic.md). Influence
// Ω = δ/|ξ| (their eq 6), stretch s = e/|ξ| of the mechanical extension e (thermal stretch removed by the bond
// loops), and per point
//   (M1) θ = d δ Σ s V,  W = (a_κ − a_μ) θ² + b δ Σ |ξ| s² V,  t = (2δ/|ξ|) [d (a_κ − a_μ) θ + b e]   (eqs 4–8)
// with 3D: a_κ = κ/2, a_μ = 5μ/6, b = 15μ/(2πδ⁵), d = 9/(4πδ⁴); 2D (thickness h): a_κ = κ/2, a_μ = μ,
// b = 6μ/(πhδ⁴), d = 2/(πhδ³), κ the in-plane bulk modulus of K and the glassy μ0; 1D (a bar of area A): a_κ = a_μ
// = 0, b = E/(2δ³A), d = 1/(2δ²A), Young's modulus E relaxing in place of μ (docs/algorithms.md §13 checks
// the calibration; the paper's eq 7b prints a_κ = κ, a_μ = 2μ, twice these, which does not reproduce κ under
// isotropic strain). With surface_correction (the default) d, the scale g of b and r = a_μ/b are each point's own
// (calibrate): exact θ and energy of its family under isotropic strain and simple shear.
// Shear relaxes as a Prony series μ(t) = μ∞ + Σ_k μ_k exp(−t/τ_k); the bulk stays elastic. a_μ and b scale with
// μ, so a_μ/b = r is a constant of the geometry and each branch k is a Maxwell element on the distortional
// form: with e^v_k the viscous extension of branch k per bond (0 at t = 0),
//   (M2) t = (2δ/|ξ|) [d (a_κ − a_μ∞) θ + b∞ e + Σ_k b_k ((e − e^v_k) − r d θ(e − e^v_k))],
//        θ(x) = d δ Σ (x/|ξ|) V, b_k = b(μ_k), b∞ = b(μ∞), a_μ∞ = a_μ(μ∞);
//   (M3) ė^v_k = (e − e^v_k)/τ_k; for e linear over a step, exactly (ε_k = exp(−Δt/τ_k), β_k = 1 − (τ_k/Δt)(1 − ε_k)):
//        e^v_k,n+1 = ε_k e^v_k,n + (1 − ε_k − β_k) e_n + β_k e_n+1,
//        or, `time_integration: second_order` (the paper's eq 24b), ε_k = 1 − Δt/τ_k, β_k = Δt/(2τ_k).
// The paper's viscous stretch γ_k is the distortional stretch of e^v_k, s^μ(e^v_k) = e^v_k/|ξ| − r d θ(e^v_k)/|ξ|,
// and (M3) mapped through s^μ is its eq 23 (eq 24b): the same model, with a history that is local per bond.
// WLF (eq 16, as thermorheologically simple materials shift): τ_k(T) = a_T τ_k, log₁₀ a_T = −c1 (T − T0)/(c2 + T − T0).
// Per step (start_step) the branches' part of (M2) is gathered into per-point P, Q, R and per-bond A:
//   (M4) t = (2δ/|ξ|) [w P e + Q θ + R − w A],  P = g (b0 − B), Q = d (a_κ − r g b0) + r d g B, R = r d g A_i,
//        B = Σ b_k β_k, A = g Σ b_k (ε_k e^v_k,n + (1 − ε_k − β_k) e_n), A_i = Σ b_k (ε_k θ^v_k,n + (1 − ε_k − β_k) θ_n),
// so that an evaluation costs what an lps one does, whatever the number of terms.
// (M5) stored energy W = (a_κ − a_μ∞) θ² + b∞ δ Σ w e²/|ξ| V + Σ_k [b_k δ Σ w (e − e^v_k)²/|ξ| V − r b_k θ(e − e^v_k)²]
//      (every b with the point's g);
// (M6) dissipation Σ_k (2/τ_k) ∫ W_k dt, W_k the k-th bracket of (M5), integrated exactly over the step for
//      e linear in time. The distortional form of (M1) is indefinite (a uniform e gives b δ Σ e²/|ξ| V − a_μ θ² < 0):
//      W_k and the dissipation are non-negative for homogeneous deformations, not for every nonlocal state.
// Lattice anisotropy (surface_correction): on a square or cubic lattice the distortional sum Σ |ξ| s² V is only a
// quadrature, and it is not isotropic: at δ = 3Δx in 2D the shear ε_xx = −ε_yy stores 7.1 % more than the shear
// ε_xy (the continuum's are equal). Each point's bonds therefore carry a weight w = 1 + β c(n) in the distortional
// terms (b and the branches, not θ), c(n) = 1 − 8 n_x² n_y² in 2D (cos 4φ), n_x⁴ + n_y⁴ + n_z⁴ − 3/5 in 3D (the
// cubic harmonic), β per point such that its own family stores the same energy under both shears
// (docs/algorithms.md §13); the b-scale g and r then follow from the weighted sums.
// History: MaterialHistory::bond[0] = w A (the step's, start_step: read by the force), bond[1] = w (start_step,
// from x and the point's β: read by the force and the energy), bond[2] = e_n, bond[3 + k] = e^v_k;
// point[0..2] = P, Q, R (the step's), point[3], point[4] = Σ_k r g b_k θ^v_k and Σ_k r g b_k (θ^v_k)² (committed);
// point constants [0], [1], [2], [3] = d, g, r, β per point.
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "peridot/deck/model_schema.hpp"
#include "peridot/materials/model_base.hpp"

namespace peridot {

struct Thermoviscoelastic : ModelBase {
  static constexpr std::string_view name = "thermoviscoelastic";
  static ModelInfo info();
  static constexpr bool uses_dilatation = true;
  static constexpr bool has_start_step = true;
  static constexpr int max_terms = 20;
  /// The most a block may need (max_terms + 3); bond_history_count gives a block's.
  static constexpr int bond_history_arrays = max_terms + 3;
  static constexpr std::array<PointArray, 5> point_arrays{{{"branch_stiffness_P", 0},
                                                           {"dilatation_coefficient_Q", 0},
                                                           {"branch_dilatation_R", 0},
                                                           {"branch_dilatation_sum", 0},
                                                           {"branch_dilatation_square_sum", 0}}};
  static constexpr std::array<int, 3> partner_point_arrays{0, 1, 2};
  /// Per point: d, g (the scale of b), r = a_μ/b and β (surface_correction), or the full family's d, 1, r, 0.
  static constexpr int point_constant_arrays = 4;

  struct Params {
    double horizon = 0;            ///< δ
    double dilatation_constant = 0;  ///< d of a full family (per point: point constant 0)
    double volumetric = 0;           ///< a_κ
    double bond_relaxed = 0;         ///< b∞
    double bond_glassy = 0;          ///< b0 = b∞ + Σ b_k
    double shear_ratio = 0;          ///< r = a_μ/b (m^5 in 3D), the same for every μ (a full family's)
    double shear_modulus_relaxed = 0;  ///< μ∞ (the surface correction calibrates b against it)
    bool surface_correction = true;  ///< d, g, r per point from its own family (calibrate)
    int terms = 0;
    std::array<double, max_terms> bond_modulus{};     ///< b_k
    std::array<double, max_terms> relaxation_time{};  ///< τ_k at the WLF reference temperature (s)
    bool second_order = false;  ///< the paper's eq 24b in place of the exact (M3)
    bool wlf = false;
    double wlf_c1 = 0, wlf_c2 = 0, wlf_reference = 0;  ///< c1, c2 (K), T0 (K)
  };
  static Params resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block);
  static int bond_history_count(const Params& p) { return p.terms + 3; }

  static double dilatation_extension(const KernelFields&, std::uint64_t, double e, double xi) { return e / xi; }
  /// (M1): the generic sum is Σ (δ/|ξ|) |ξ| (e/|ξ|) V = δ Σ s V.
  static double dilatation(const Params&, const KernelFields& s, std::size_t i, double sum, int) {
    return s.point_constant[0][i] * sum;
  }
  /// (M4). ω (δ/|ξ| of the block) is not read: the model has its own.
  static double force_scalar(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t b, double e,
                             double xi, double /*omega*/) {
    return 2 * p.horizon / xi * (s.bond[1][b] * s.point[0][i] * e + s.point[1][i] * s.theta[i] + s.point[2][i] - s.bond[0][b]);
  }
  /// (M5), the bond part, with the committed e^v.
  static double bond_energy(const Params& p, const KernelFields& s, std::size_t i, std::uint64_t b, double e,
                            double xi, double /*omega*/) {
    double w = p.bond_relaxed * e * e;
    for (int k = 0; k < p.terms; ++k) {
      const double x = e - s.history->bond[3 + k][b];
      w += p.bond_modulus[k] * x * x;
    }
    return s.bond[1][b] * s.point_constant[1][i] * p.horizon * w / xi;
  }
  /// (M5), the point part: (a_κ − a_μ0) θ² + 2θ Σ r b_k θ^v_k − Σ r b_k (θ^v_k)², a_μ0 = r b0 of the point.
  static double point_energy(const Params& p, const KernelFields& s, std::size_t i) {
    const double theta = s.theta[i];
    const double a_mu = s.point_constant[2][i] * s.point_constant[1][i] * p.bond_glassy;
    return (p.volumetric - a_mu) * theta * theta + 2 * theta * s.point[3][i] - s.point[4][i];
  }

  static void calibrate(ModelContext& ctx, const MaterialParams& block, const Params& p, BlockRange range);
  static void start_step(const ModelContext& ctx, MaterialHistory& history, const MaterialParams& block,
                         const Params& p, BlockRange range, double dt);
  /// e^v advances (M3), e_n becomes this step's e, the dissipation (M6) accumulates.
  static void commit(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                     MaterialHistory& history, const MaterialParams& block, const Params& p, BlockRange range, double dt);

  /// a_T at temperature T (1 without WLF); throws NumericalError where c2 + T − T0 ≤ 0.
  static double shift_factor(const Params& p, double temperature);
  /// ε_k and β_k of every term over Δt for shift factor a_T.
  static void step_factors(const Params& p, double dt, double shift, std::array<double, max_terms>& decay,
                           std::array<double, max_terms>& ramp);
};

}  // namespace peridot
