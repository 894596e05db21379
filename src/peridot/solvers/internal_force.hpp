#pragma once
// The bond loops: weighted volume, dilatation, internal force, strain energy, stable time step.
// All are gathers over the CSR bonds of each point, parallel over points with OpenMP and free of
// atomics, so every result is bitwise independent of the thread count:
//   f_i = Σ_j (T_i⟨ξ_ij⟩ − T_j⟨ξ_ji⟩) V_j = Σ_j (t_ij + t_ji) M_ij V_j,  M_ij = Y_ij/|Y_ij|.
#include <cstdint>
#include <vector>

#include "peridot/geometry/discretize.hpp"
#include "peridot/materials/material.hpp"
#include "peridot/materials/model_context.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// Per-point constants a model computes once from its reference families (lps_plastic's yield norm factor),
/// after inverse_weighted_volume is set, and each block's uniform_volume and family_in_block.
void calibrate_models(ModelContext& ctx);

/// The fields the kernels read, from θ and (for inelastic models) the history.
KernelFields kernel_fields(const ModelContext& ctx, const std::vector<double>& theta, const MaterialHistory* history);

/// m_i = Σ_j ω ξ² V_j over all bonds (undamaged reference), for every point (m⁵; 2D m⁴·h).
void compute_weighted_volume(const ModelContext& ctx, std::vector<double>& m);

/// θ_i = (n/m_i) Σ_j ω ξ e V_j over intact bonds, for every point (lps_plastic: e − e^dp in place of e,
/// lps_plastic.hpp (P7); thermoviscoelastic: its own θ, Model::dilatation_extension and Model::dilatation). With fail_bonds, bonds that fail now (damage/critical_stretch.hpp) are marked
/// broken first. The history is required when a model keeps one; with fail_bonds the point array a model
/// declares as its released_extension_array receives Σ ω ξ (e − e^dp) V / m over the bonds of each point
/// that broke now.
void compute_dilatation(const ModelContext& ctx, const VectorField& u, std::vector<double>& theta,
                        bool fail_bonds = false, MaterialHistory* history = nullptr);

/// Inelastic models, once per step before its first force: what the step's forces need of the committed
/// history over Δt (thermoviscoelastic: the Prony branches' part of the bond force).
void start_step(const ModelContext& ctx, MaterialHistory& history, double dt);

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

/// Per bond i → j, the axial spring V_j c G/ξ_ij of the pmb-like tangent (G the surface correction's factor,
/// V_j with the quadrature's weight), 0 for a broken bond: f_i changes by this times the change of the bond's
/// length along it. c is a pmb block's own micromodulus c0 ω(ξ) (for a bond within the block, the exact axial
/// stiffness of the pair of force states), the block's stable_micromodulus for the other models.
void bond_stiffness(const ModelContext& ctx, std::vector<double>& k);

/// Silling–Askari stable time step min_i √(2ρ_i / Σ_j V_j c/ξ_ij) (s), before any safety factor.
double stable_time_step(const ModelContext& ctx);

}  // namespace peridot
