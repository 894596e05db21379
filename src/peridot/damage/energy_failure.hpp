#pragma once
// Energy-based bond failure (Madenci & Oterkus, J. Mech. Phys. Solids 2017, §6, eqs 26–33; docs/algorithms.md
// §14): every bond keeps the work done on it by the force states of its two ends,
//   W = ∫ (t_ij + t_ji) de   (J/m⁶; e the bond's mechanical extension, thermal stretch removed),
// added up once per accepted step (commit) by the trapezoid rule, W += ½ (T_prev + T)(e − e_prev), exact for a
// linear bond. A bond in tension breaks, irreversibly, once the energy it holds or has dissipated reaches its
// share of the fracture energy of one lattice cell of crack:
//   W V_i V_j ≥ τ = 2 Gc A_c / N_c,   A_c = Δx h (2D), Δx² (3D),
// N_c = 2 × (bonds whose line crosses one cell of a crack plane), each bond counted with its two
// micropotentials (crack_micropotentials). Then the bonds that cross a straight crack take exactly Gc per unit
// crack area with them. Between two blocks the smaller τ applies.
//
// Deterministic: W, T and e of bond i → j and of j → i are computed from the same bits (ghost values, e and
// |ξ| the same from either end, T = t_ij + t_ji commutes), so both directions break in the same step without
// communication, for any thread and rank count.
#include <cstdint>
#include <vector>

#include "peridot/materials/model_context.hpp"
#include "peridot/state/state_arrays.hpp"

namespace peridot {

/// The bonds whose line crosses one lattice cell of a plane crack (a segment of length Δx in 2D, a Δx × Δx
/// square in 3D) placed between two lattice rows, bonds through the cell's edge counted ½ (a corner ¼): for
/// the square (cubic) lattice of spacing Δx and the neighbour rule |ξ| ≤ δ = m Δx (with the neighbour search's
/// round-off allowance). Exactly Σ ξ_⊥/Δx over the lattice vectors ξ of a family with ξ_⊥ > 0 (ξ_⊥ the
/// component normal to the crack): 18 for m = 3 in 2D, 70 in 3D. Continuum limit 2m³/3 (2D), π m⁴/4 (3D).
double crack_crossing_bonds(int dimension, double m);

/// N_c of eq (33b): 2 × crack_crossing_bonds (each bond has two micropotentials, one per end).
inline double crack_micropotentials(int dimension, double m) { return 2 * crack_crossing_bonds(dimension, m); }

/// The work done on every bond and the energy criterion of the blocks that use it
/// (MaterialParams::fracture_energy > 0). Held by the Simulation only when some block does.
class EnergyFailure {
 public:
  /// Thresholds per block from each block's Gc, δ and the lattice spacing Δx (cross_section: h in 2D, A in 1D); per-bond
  /// arrays for the bonds of ctx (all zero: the reference configuration carries no work).
  EnergyFailure(const ModelContext& ctx, double spacing, double cross_section);

  /// N_c of block b (0 for a block without the energy criterion).
  double micropotentials(std::size_t block) const { return count_[block]; }
  /// τ = 2 Gc A_c / N_c (J) of block b; +∞ without the energy criterion.
  double threshold(std::size_t block) const { return threshold_[block]; }
  /// W per bond (J/m⁶), as of the last commit.
  const std::vector<double>& work() const { return work_; }
  /// W, T and e per bond, for checkpoints.
  void state_arrays(StateArrays& arrays) {
    arrays.bonds("energy_failure.work", work_, work_.size());
    arrays.bonds("energy_failure.force", force_, force_.size());
    arrays.bonds("energy_failure.extension", extension_, extension_.size());
  }

  /// Adds the accepted step's work to every intact bond under the criterion: W += ½ (T_prev + T)(e − e_prev),
  /// with T = t_ij + t_ji from the kernels at u with `fields` (the last evaluation's θ and history: call before
  /// the models commit).
  void accumulate(const ModelContext& ctx, const VectorField& u, const KernelFields& fields);
  /// Marks broken every intact bond in tension (e > 0 at u) whose work reaches its threshold, unless an end is
  /// protected (no_fail). Without `trial`, the work of the last commit (before a step's forces: the work of
  /// the steps accepted so far); with it, that plus the step so far, ½ (T_prev + T)(e − e_prev), T from the
  /// kernels with `trial` (after an evaluation at u: dynamic relaxation at equilibrium). Returns how many
  /// bonds of this rank broke.
  std::uint64_t break_bonds(const ModelContext& ctx, const VectorField& u, const KernelFields* trial) const;

 private:
  std::vector<double> count_, threshold_;     ///< per block
  std::vector<double> work_, force_, extension_;  ///< per bond: W, T and e at the last commit
};

}  // namespace peridot
