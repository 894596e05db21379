#pragma once
// The bond loops: weighted volume, dilatation, internal force, strain energy, stable time step.
// All are gathers over the CSR bonds of each point, parallel over points with OpenMP and free of
// atomics, so every result is bitwise independent of the thread count:
//   f_i = Σ_j (T_i⟨ξ_ij⟩ − T_j⟨ξ_ji⟩) V_j = Σ_j (t_ij + t_ji) M_ij V_j,  M_ij = Y_ij/|Y_ij|.
#include <cstdint>
#include <vector>

#include "peridot/geometry/discretize.hpp"
#include "peridot/materials/material.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// What the bond loops need that does not change during a run.
struct ModelContext {
  const Discretization* disc = nullptr;
  BondList* bonds = nullptr;
  std::vector<MaterialParams> params;  ///< per block
  std::vector<BlockRange> ranges;      ///< per block
  double partial_volume_radius = 0;    ///< 0: no partial-volume correction
  std::vector<std::uint8_t> no_fail;   ///< per point: bonds touching it never break (empty = none)
  /// 1/m per point (set once from compute_weighted_volume): the kernels multiply, never divide, by m.
  std::vector<double> inverse_weighted_volume;
  /// LAMMPS PERI's order, for the side-by-side benchmark only: a bond that fails in a step still carries
  /// its force in that step (checked in the force pass, after the force) instead of failing before any
  /// force uses it. With it, Peridot and LAMMPS break the same bonds (bench/README.md).
  bool bond_failure_after_force = false;
  /// lps_plastic: k = √(2ψ0)/σ_Y of every point of its blocks, from its reference family
  /// (materials/lps_plastic.hpp (C)); empty when no block is lps_plastic.
  std::vector<double> yield_norm_factor;
  /// Per block: the volume every point of it has, owned and ghost (lattice blocks), or 0 when they
  /// differ; set by calibrate_models. The AVX-512 PMB loop then broadcasts V_j instead of gathering it
  /// (the same value, so the same bits). Empty: every loop gathers.
  std::vector<double> uniform_volume;
  /// Per block: 1 when no bond of its points leaves it (no interface), set by calibrate_models. The bond
  /// loops then take a point's whole family as its same-block run instead of looking the run's ends up
  /// (find_same_block_run: two dependent loads per point, usually cache misses). Empty: look them up.
  std::vector<std::uint8_t> family_in_block;

  bool any_dilatation() const;
  bool any_damage() const;
  /// The most per-bond history arrays any block's model needs (0: no inelastic model).
  int bond_history_arrays() const;
};

/// Per-point constants a model computes once from its reference families (lps_plastic's yield norm factor),
/// after inverse_weighted_volume is set, and each block's uniform_volume and family_in_block.
void calibrate_models(ModelContext& ctx);

/// The fields the kernels read, from θ and (for inelastic models) the history.
KernelFields kernel_fields(const ModelContext& ctx, const std::vector<double>& theta, const MaterialHistory* history);

/// m_i = Σ_j ω ξ² V_j over all bonds (undamaged reference), for every point (m⁵; 2D m⁴·h).
void compute_weighted_volume(const ModelContext& ctx, std::vector<double>& m);

/// θ_i = (n/m_i) Σ_j ω ξ e V_j over intact bonds, for every point (lps_plastic: e − e^dp in place of e,
/// lps_plastic.hpp (P7)). With fail_bonds, bonds that fail now (damage/critical_stretch.hpp) are marked
/// broken first. The history is required when a model keeps one; with fail_bonds its released_extension
/// receives Σ ω ξ (e − e^dp) V / m over the bonds of each point that broke now.
void compute_dilatation(const ModelContext& ctx, const VectorField& u, std::vector<double>& theta,
                        bool fail_bonds = false, MaterialHistory* history = nullptr);

/// Inelastic models, before the force: this step's return map from the current u and θ (history
/// unchanged; may run any number of times).
void prepare_history(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                     MaterialHistory& history);

/// Internal force density f (N/m³). θ must be current where a model uses it, and, for inelastic models,
/// prepare_history must have run on the same u (history is required then).
/// With fail_bonds, bonds that fail now are marked broken first (when no dilatation pass ran this step).
void compute_internal_force(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                            VectorField& f, bool fail_bonds = false, const MaterialHistory* history = nullptr);

/// Inelastic models, after the force of a step: the history advances to the current u over a step Δt
/// (the Δt of set_time_step).
void commit_history(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                    MaterialHistory& history, double dt);

/// Stored energy density W_i (J/m³) of every point, with the committed history; Σ W_i V_i is the total
/// strain energy, and, for the elastic models and an elastic step, f_i V_i = −∂(Σ W V)/∂u_i.
void compute_strain_energy_density(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                                   std::vector<double>& W, const MaterialHistory* history = nullptr);

/// Per point, the Gerschgorin-type stiffness bound Σ_j V_j c/ξ_ij (N/m⁶ · m² = N/m⁴ per unit
/// displacement) with c the block's stable_micromodulus: the sums of the stable time step, and the
/// fictitious density of dynamic relaxation. Ghosts get 0.
void stiffness_bound(const ModelContext& ctx, std::vector<double>& k);

/// Silling–Askari stable time step min_i √(2ρ_i / Σ_j V_j c/ξ_ij) (s), before any safety factor.
double stable_time_step(const ModelContext& ctx);

}  // namespace peridot
