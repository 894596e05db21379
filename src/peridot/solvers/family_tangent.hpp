#pragma once
// The tangent of the internal force family by family, for the implicit solver's assembled Jacobians
// (solvers/newton_krylov.hpp; derivation in docs/algorithms.md "Newton–Krylov static solver").
//   The residual R = −f V of the gather form f_i = Σ_j (t_ij + t_ji) M_ij V_j, regrouped by the point whose force
//   state a term is: the family of i holds t_ij for its intact bonds, which acts on i with weight W_ij = V_i V_j
//   (V_j as point i sees it: quadrature weight, partial volume) and on j with W_ji = V_j V_i. Its part of K = ∂R/∂u
//   depends on the displacements of i and its family only; K is the sum of every family's part.
//   pmb:  t_ij = ½ c0 ω̃ e/ξ: axial stiffness b = ½ c0 ω̃/ξ and the geometric stiffness (t/|y|)(I − M⊗M) of a
//         force that turns with its bond; the blocks couple i and j only.
//   lps:  t_ij = (ω̃/m)[α_v θ ξ + α_d (e − κθξ/n)], θ_i = (n/m) Σ ω̃ ξ e V: the same axial (b = ω̃ α_d/m) and
//         geometric blocks, plus the dilatation's part ∂t_ij/∂θ · ∂θ_i/∂u, an outer product ρ γᵀ over the whole
//         family (ρ_j = W_ji a_j M_j, ρ_i = −Σ W_ij a_j M_j; γ_l = (n/m) ω̃ ξ V_l M_l, γ_i = −Σ γ_l;
//         a_j = (ω̃/m)(α_v − κ α_d/n) ξ): every pair of the family is coupled, so K's stencil is 2δ.
//   ω̃ = ω G (the surface correction's factor), e the mechanical extension (thermal stretch removed).
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "peridot/materials/model_context.hpp"

namespace peridot {

/// Whether the model of this name has a closed-form tangent here (pmb, lps): the deck refuses jacobian: exact
/// for the others.
bool has_exact_tangent(std::string_view model);

/// One family's part of K = ∂R/∂u (N/m), in the compact form above: the bond blocks and, for lps, ρ and γ.
struct FamilyTangent {
  /// Point i first, then the partners of its intact bonds in bond order (slots 0 … n).
  std::vector<std::uint32_t> points;
  /// Per partner slot q ≥ 1 (index q − 1): the deformed direction M (3 each), and D = axial M⊗M + turning I with
  /// the weights of its force on i (on_i) and on the partner (on_j).
  std::vector<double> direction, axial, turning, on_i, on_j;
  /// lps: ρ and γ per slot (3 each); empty for pmb.
  std::vector<double> rho, gamma;

  bool coupled() const { return !rho.empty(); }
  /// Adds the 3×3 block K(r, c) of slots r and c to k (row-major). Nonzero for every pair when coupled, else
  /// for (0, 0), (0, q), (q, 0) and (q, q) only.
  void add_block(std::size_t r, std::size_t c, double k[9]) const;
};

/// Family i's part of K at the displacements u (owned and ghost points, 3 per point). i's block's model must
/// have an exact tangent (has_exact_tangent).
void family_tangent(const ModelContext& ctx, const double* u, std::size_t i, FamilyTangent& out);

}  // namespace peridot
