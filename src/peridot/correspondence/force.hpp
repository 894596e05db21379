#pragma once
// Internal force of the correspondence model, with optional hourglass (zero-energy mode) control.
// Reference: Foster, Silling & Chen, IJNME 81 (2010) 1242, eqs 4 and 25; hourglass force of Peridigm
// (Littlewood), restated in docs/algorithms.md §7.
//   force state      T_i⟨ξ⟩ = ω P_i K_i⁻¹ ξ                                                 (eq 25)
//   hourglass state  T_i^hg⟨ξ⟩ = ω (c_hg/|ξ|) (z_i · n) n,  z_i = Y − F_i ξ,  n = Y/|Y|     (§7)
//                    c_hg = 18 C_HG K/(π δ⁴) (N/m⁶): C_HG times the 3D PMB micromodulus of bulk modulus K,
//                    so the control is a weak bond on the non-affine part of each bond's stretch. Peridigm's
//                    examples use C_HG = 0.02–0.05; tests/unit/correspondence_hourglass_test.cpp measures
//                    what 0.05 does. An affine deformation has z = 0, so the control adds no force there
//                    and leaves the patch tests exact.
//   hourglass damping T_i^hv⟨ξ⟩ = ω (c_hv/|ξ|) (ż_i · n) n,  ż_i = (v_j − v_i) − Ḟ_i ξ, the rate of z_i
//                    c_hv = 18 C_HV √(ρK)/(π δ³) (N s/m⁶): the same bond with the bulk modulus replaced by
//                    the viscosity C_HV ρ c δ, c = √(K/ρ) (a linear artificial viscosity over the horizon). The
//                    springs alone leave a zero-energy mode that an impact excites ringing at its own
//                    frequency (the springs store the energy and give it back); the dashpot dissipates it.
//                    Both c_hv/√c_hg and the mode's geometry are independent of K, ρ and Δx at fixed δ/Δx, so
//                    its damping ratio is ζ ≈ 2.1 C_HV/√C_HG (about 0.3 measured at C_HV = C_HG = 0.02 in
//                    tests/unit/correspondence_hourglass_test.cpp). A rigid or any homogeneous motion has
//                    ż = 0, so the dashpots too leave the patch tests exact.
//   gather           f_i = Σ_j (T_i⟨ξ_ij⟩ − T_j⟨ξ_ji⟩) V_j                                    (eq 4)
// ω is the bond weight of the context (influence function times partial-volume factor) of the state's
// owner; broken bonds carry no force. Active bonds to mirror images (mirror_bonds.hpp) are gathered like
// the others, with the partner's state reflected. OpenMP over points, no atomics: bitwise independent of threads.
// Since Σ_j ω Y⊗(P K⁻¹ ξ) V_j = F Pᵀ = J σ is symmetric, the correspondence force conserves angular
// as well as linear momentum; the hourglass force is central and conserves both too.
#include "peridot/correspondence/constitutive.hpp"
#include "peridot/correspondence/kinematics.hpp"

namespace peridot::correspondence {

/// Dimensionless hourglass coefficient C_HG used when none is chosen (see above).
inline constexpr double default_hourglass_coefficient = 0.05;

/// c_hg = 18 C_HG K/(π δ⁴) (N/m⁶) from C_HG (-), the bulk modulus K (Pa) and the horizon δ (m).
double hourglass_stiffness(double coefficient, double bulk_modulus, double horizon);
/// c_hv = 18 C_HV √(ρK)/(π δ³) (N s/m⁶) from C_HV (-), the density ρ (kg/m³), K (Pa) and δ (m).
double hourglass_damping(double coefficient, double density, double bulk_modulus, double horizon);

/// Internal force density f (N/m³) of every point from the force tensors P K⁻¹ of s (update_block_stress)
/// and, where ctx.hourglass_stiffness is non-zero, the hourglass force of u and the F of kin, and where
/// ctx.hourglass_damping is non-zero, the hourglass damping of v and the Ḟ of kin. u and v must be the
/// displacement and velocity the kinematics was computed from.
void compute_correspondence_force(const CorrespondenceContext& ctx, const KinematicFields& kin,
                                  const StressFields& s, const VectorField& u, const VectorField& v, VectorField& f);
/// The same for the points of `range` only (f is left untouched outside it). When `hourglass` is given
/// (sized for every point), it receives the hourglass part of f (springs and dashpots) in the range, so
/// that its work can be measured. When `mirror_force` is given, it receives the part of f from the bonds
/// to mirror images (ctx.mirror; zero for a point without them): the symmetry plane's force on the point.
void compute_correspondence_force(const CorrespondenceContext& ctx, const KinematicFields& kin,
                                  const StressFields& s, const VectorField& u, const VectorField& v, VectorField& f,
                                  BlockRange range, VectorField* hourglass = nullptr,
                                  VectorField* mirror_force = nullptr);

}  // namespace peridot::correspondence
