#pragma once
// Kinematics of the correspondence (non-ordinary state-based) model, point by point over its CSR bonds.
// Reference: Foster, Silling & Chen, "Viscoplasticity using peridynamics", IJNME 81 (2010) 1242 —
//   shape tensor          K   = Σ_j ω ξ⊗ξ V_j                      (eq 10)
//   deformation gradient  F   = [Σ_j ω Y⟨ξ⟩⊗ξ V_j] K⁻¹              (eq 13)
//   its rate              Ḟ   = [Σ_j ω (v_j − v_i)⊗ξ V_j] K⁻¹       (eq 13 differentiated in time; the
//                                                                   velocity state, docs/algorithms.md §5)
//   velocity gradient     L   = Ḟ F⁻¹                              (eq 14)
// ω here is the influence function times the partial-volume factor of the bond, so K, F, Ḟ and the force
// state (force.hpp) all use the same quadrature and F is exact for every affine deformation, at every
// point, boundaries included (the proof after eq 13). Broken bonds are left out of every sum; the bonds to
// mirror images across a symmetry plane (mirror_bonds.hpp) are in every sum while they are active.
// Only 3D is implemented: in 2D the out-of-plane row of K is empty.
#include <cstdint>
#include <vector>

#include "peridot/correspondence/mirror_bonds.hpp"
#include "peridot/correspondence/tensor.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/state/fields.hpp"

namespace peridot::correspondence {

/// What the kinematics needs to know of one block.
struct BlockGeometry {
  double horizon = 0;  ///< δ (m)
  InfluenceKind influence = InfluenceKind::constant;
};

/// What the correspondence bond loops read that does not change during a run.
struct CorrespondenceContext {
  const Discretization* disc = nullptr;
  const BondList* bonds = nullptr;
  /// Per bond i → j: ω_i(|ξ|) times the partial-volume factor times V_j (m³), ω of i's block: the weight
  /// of the bond in every sum of the kinematics and the force.
  std::vector<double> weighted_volume;
  /// Per block: its horizon and influence function, for ω_j of a bond to another block (pair_weight).
  std::vector<BlockGeometry> blocks;
  double partial_volume_radius = 0;  ///< as NeighborhoodOptions (0: no partial-volume factor)
  /// Per block: hourglass bond stiffness c_hg (N/m⁶), 0 = no control (see force.hpp).
  std::vector<double> hourglass_stiffness;
  /// Per block: hourglass bond dashpot c_hv (N s/m⁶), 0 = no damping (see force.hpp).
  std::vector<double> hourglass_damping;
  /// Per block: the bulk viscosity of shocks (constitutive.hpp, bulk_viscous_pressure): its linear
  /// coefficient b_l = C_l ρ c (kg/(m² s), c the P-wave speed) and quadratic one b_q = C_q ρ (kg/m³); 0 = none.
  /// Empty (as in a context made by hand) counts as none.
  std::vector<double> bulk_viscosity_linear;
  std::vector<double> bulk_viscosity_quadratic;
  /// K is refused when λ_min(K)/λ_max(K) falls below this (dimensionless). At 1e-8 the relative error
  /// that round-off in the bond sums can put into F through K⁻¹ stays near 1e-8.
  double min_reciprocal_condition = 1e-8;
  /// Bonds to mirror images across symmetry planes (mirror_bonds.hpp), in every sum while `active`.
  MirrorBonds mirror;
  /// Damage through the influence function (johnson_cook_damage.hpp), kept by the solver at every commit;
  /// both empty without it. Per bond: the factor 1 − max(D_i, D_j) that weighted_volume already carries,
  /// for ω_j of a bond to another block. Per point: 1 for a failed point (D = 1, every bond broken), which
  /// the kinematics and the stress step pass over: a free particle with no stress.
  std::vector<double> bond_integrity;
  std::vector<std::uint8_t> failed_point;
};

/// Bond weights for a discretization whose blocks are described by `blocks`
/// (indexed by disc.block). `partial_volume_radius` as in NeighborhoodOptions (0: none); the pair horizon
/// for the partial-volume factor is the larger of the two blocks'.
CorrespondenceContext make_correspondence_context(const Discretization& disc, const BondList& bonds,
                                                  const std::vector<BlockGeometry>& blocks,
                                                  double partial_volume_radius = 0);

/// ω⟨ξ⟩ of a bond of length xi from a point of block `own` to one of block `other`, with its partial-volume
/// factor (dimensionless): the weight of weighted_volume, and of the state of the bond's other end.
double pair_weight(const CorrespondenceContext& ctx, std::size_t own, std::size_t other, double xi);

/// Whether point i's shape tensor, with its intact bonds at their current weights (mirror bonds included
/// while active), passes the conditioning check of compute_kinematics (λ_min/λ_max ≥ ctx.min_reciprocal_condition).
bool shape_tensor_well_conditioned(const CorrespondenceContext& ctx, std::size_t i);

/// Per-point kinematic fields.
struct KinematicFields {
  TensorField shape_inverse;              ///< K⁻¹ (m⁻⁵)
  TensorField deformation_gradient;       ///< F at the end of the step (-)
  TensorField deformation_gradient_rate;  ///< Ḟ from the velocities passed (1/s)
};

/// K⁻¹, F(u) and Ḟ(v) of every point. In an explicit step, u is u^{n+1} and v the mid-step velocity
/// v^{n+1/2}, so that Ḟ = (F^{n+1} − F^n)/Δt exactly for a homogeneous motion.
/// Throws NumericalError naming the lowest-numbered point (its index, input id and position) whose K is
/// singular or ill-conditioned (fewer than three non-coplanar intact bonds), rather than producing NaNs.
/// A failed point (ctx.failed_point) keeps its last F, with K⁻¹ = 0 and Ḟ = 0.
void compute_kinematics(const CorrespondenceContext& ctx, const VectorField& u, const VectorField& v,
                        KinematicFields& out);
/// The same for the points of `range` only (one correspondence block of a problem that mixes models); the
/// fields are sized for every point and left untouched outside the range.
void compute_kinematics(const CorrespondenceContext& ctx, const VectorField& u, const VectorField& v,
                        KinematicFields& out, BlockRange range);

/// L = Ḟ F⁻¹ (eq 14) at mid-step, F^{n+1/2} = F^{n+1} − ½Δt Ḟ (1/s), second-order accurate. When F^n and
/// F^{n+1} are both rotations (F^{n+1} = Q F^n), L = (2/Δt)(Q − I)(Q + I)⁻¹ is exactly skew (the Cayley
/// transform of Q), so D = 0 to round-off and a rigid rotation produces no stress.
Mat3 mid_step_velocity_gradient(const Mat3& F_end, const Mat3& F_rate, double dt);

}  // namespace peridot::correspondence
