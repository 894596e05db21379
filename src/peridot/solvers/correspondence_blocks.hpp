#pragma once
// The correspondence blocks of a problem inside the explicit solver (docs/models/correspondence.md).
// Each step, after u^{n+1} and with the mid-step velocity v^{n+1/2} (simulation.hpp):
//   kinematics K⁻¹, F^{n+1}, Ḟ (correspondence/kinematics.hpp, Foster et al. 2010 eqs 10, 13)
//   → stress update over Δt (constitutive.hpp: eq 14, Flanagan–Taylor eqs 15–18, the law, eqs 23–24)
//   → force density with hourglass control (force.hpp, eqs 4, 25; docs/algorithms.md §7).
// Bookkeeping for the energy balance (history CSV): the inelastic (plastic) work per point
// (constitutive.hpp inelastic_work_increment, into MaterialHistory::dissipation), the stored elastic
// energy J (p²/2K + S:S/4μ), and the work of the hourglass forces, −Σ ½(f_hg^n + f_hg^{n+1})·Δu V.
// Bonds between a correspondence block and a block of another model are refused at set-up (InputError at
// the body): the force state of a correspondence point needs its whole family in F, and an ordinary
// neighbour's bond force has no counterpart in P K⁻¹. Two correspondence blocks may share bonds.
// Rigid walls with contact: symmetry add bonds to mirror images (correspondence/mirror_bonds.hpp), released
// here when the body leaves the wall.
#include <cstdint>
#include <memory>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/parallel/halo.hpp"
#include "peridot/state/state_arrays.hpp"
#include "peridot/solvers/internal_force.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

class CorrespondenceBlocks {
 public:
  /// The correspondence blocks of `model` (none: empty()). Throws InputError, at the body's position in
  /// the deck, for a bond between a correspondence block and another model's block. Distributed, `halo`
  /// refreshes the ghosts' P K⁻¹ and F between the stress update and the force gather.
  /// `comm`: the ranks that decide together when a symmetry plane is released (mirror_bonds.hpp).
  CorrespondenceBlocks(const Problem& problem, const ModelContext& model, const Halo* halo = nullptr,
                       Communicator comm = Communicator());
  ~CorrespondenceBlocks();
  CorrespondenceBlocks(const CorrespondenceBlocks&) = delete;
  CorrespondenceBlocks& operator=(const CorrespondenceBlocks&) = delete;

  bool empty() const;

  /// Kinematics of (u, v), a trial stress update over Δt from the committed stress (Δt = 0: none) and the
  /// force density f (N/m³) of every correspondence point; other points' f untouched. Changes no
  /// committed state: it may run any number of times for one step (relaxation iterations). Throws
  /// NumericalError naming the point.
  void evaluate(const VectorField& u, const VectorField& v, double dt, VectorField& f);
  /// Accepts the last evaluate(): its stress and J2 history become the committed ones, each point's
  /// inelastic work is added to history.dissipation, the hourglass work over the step (from the last
  /// commit's u to this u) is accumulated, and symmetry planes whose bodies leave them are released (from
  /// v). Collective when there are symmetry planes.
  void commit(const VectorField& u, const VectorField& v, MaterialHistory& history);

  /// After a checkpoint's values are in state_arrays(): the bond weights of the restored damage
  /// (johnson_cook_damage with the influence-function coupling). Collective.
  void restored();

  /// The committed stress (R, V, τ), the laws' histories, the hourglass forces and work, which symmetry
  /// planes still act and, with bond-degrading damage, F (a failed point keeps its last one): for checkpoints.
  void state_arrays(StateArrays& arrays);
  /// Stored elastic energy density (J/m³, per reference volume) into W at every correspondence point.
  void strain_energy_density(std::vector<double>& W) const;
  /// Work done on each point by the hourglass forces since t = 0, with the sign of a stored energy (J):
  /// W_hg,i = −Σ_steps ½(f_hg^n + f_hg^{n+1})·(u^{n+1} − u^n) V_i (Simulation sums it for the history).
  const std::vector<double>& point_hourglass_work() const;
  /// Fills state.point_outputs (names: output_field_names(), and `temperature` (K) when
  /// any_thermal_softening) and history.plastic_strain (ε̄p of J2).
  void write_point_outputs(State& state) const;

  /// The largest equivalent plastic strain and the highest temperature over this rank's points (laws with a
  /// plastic strain; temperatures where the law has thermal softening), each with its point (ties: the smallest
  /// input id), and how many points have heated 99 % of the way to their law's melting temperature (T* ≥ 0.99),
  /// where the flow stress is all but gone (thermal_softening.hpp). For the run's closing summary.
  struct Extremes {
    static constexpr std::size_t none = static_cast<std::size_t>(-1);
    double max_plastic_strain = 0;
    std::size_t plastic_point = none;  ///< local index; none: no point with a plastic strain
    double max_temperature = 0;        ///< K
    std::size_t hot_point = none;      ///< local index; none: no point with a temperature
    std::uint64_t near_melting = 0;
  };
  Extremes extremes() const;

  /// Force density (N/m³, 3 per owned point) of the mirror bonds of rigid wall `wall` (contact: symmetry)
  /// on each point at the last force computation: zero for other walls and once released
  /// (correspondence/mirror_bonds.hpp). The force on the wall is −Σ f V.
  void symmetry_wall_force_density(std::size_t wall, std::vector<double>& out) const;
  /// Whether wall `wall` is a symmetry plane whose mirror bonds still act.
  bool symmetry_wall_active(std::size_t wall) const;

  /// The Exodus fields a problem with correspondence blocks writes, beyond the standard ones.
  static const std::vector<std::string>& output_field_names();

 private:
  /// Releases each symmetry plane whose bodies move away from it (momentum along n > 0, from v) while its
  /// normal force on them is tensile (mirror_bonds.hpp); at every commit.
  void release_mirror_planes(const VectorField& v);

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Whether a correspondence material of the problem has thermal_softening (then `temperature` is output).
bool any_thermal_softening(const ModelContext& model);
/// Whether some correspondence block's law has johnson_cook_damage (the `material_damage` output).
bool any_material_damage(const ModelContext& model);

}  // namespace peridot
