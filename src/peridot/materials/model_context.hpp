#pragma once
// What every bond loop needs of a problem besides the state: the points, the bonds, each block's resolved
// material and point range (fixed during a run), and the prescribed temperature of the current time. Built
// by the solver (solvers/simulation.cpp), read by the materials' kernels, damage, contact and the solvers'
// bond loops.
#include <cstdint>
#include <vector>

#include "peridot/geometry/discretize.hpp"
#include "peridot/materials/material.hpp"
#include "peridot/materials/models.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// What the bond loops need besides the state.
struct ModelContext {
  const Discretization* disc = nullptr;
  BondList* bonds = nullptr;
  std::vector<MaterialParams> params;     ///< per block: what every model has
  std::vector<ModelParams> model_params;  ///< per block: its model's own constants (Params)
  std::vector<BlockRange> ranges;         ///< per block
  double partial_volume_radius = 0;       ///< 0: no partial-volume correction
  std::vector<std::uint8_t> no_fail;      ///< per point: bonds touching it never break (empty = none)
  /// 1/m per point (set once from compute_weighted_volume): the kernels multiply, never divide, by m.
  std::vector<double> inverse_weighted_volume;
  /// LAMMPS PERI's order, for the side-by-side benchmark only: a bond that fails in a step still carries
  /// its force in that step (checked in the force pass, after the force) instead of failing before any
  /// force uses it. With it, Peridot and LAMMPS break the same bonds (bench/README.md).
  bool bond_failure_after_force = false;
  /// Per-point constants the models calibrate once from the reference family (point_constant_arrays,
  /// each model's meaning; lps_plastic: k of (C)); as many arrays as the most any present model declares.
  std::vector<std::vector<double>> point_constants;
  /// Per block: the volume every point of it has, owned and ghost (lattice blocks), or 0 when they
  /// differ; set by calibrate_models. The AVX-512 PMB loop then broadcasts V_j instead of gathering it
  /// (the same value, so the same bits). Empty: every loop gathers.
  std::vector<double> uniform_volume;
  /// Per block: 1 when no bond of its points leaves it (no interface), set by calibrate_models. The bond
  /// loops then take a point's whole family as its same-block run instead of looking the run's ends up
  /// (find_same_block_run: two dependent loads per point, usually cache misses). Empty: look them up.
  std::vector<std::uint8_t> family_in_block;
  /// Per point (owned and ghost), with a temperature field (deck `temperature`): T (K) at the time of the
  /// force being computed; empty without one. Set by the solver before each force evaluation.
  std::vector<double> temperature;
  /// Per point (owned and ghost): α (T − T_ref), the stretch of free thermal expansion, which every bond of
  /// the point subtracts from its stretch (bond_loop::mechanical_extension); empty when no point has one (no
  /// temperature field, or α = 0 everywhere), and then the bond loops take their paths without it.
  std::vector<double> thermal_stretch;
  /// Per bond: the surface correction's factor G (solvers/surface_correction.hpp), 1 for the bonds of a block
  /// without it; empty when no block has one, and then the bond loops take their paths without it.
  std::vector<double> bond_scale;

  /// Adds a block (in block order).
  void add_block(ResolvedMaterial material);
  /// The Params of block b, whose model is Model.
  template <class Model>
  const typename Model::Params& model_params_of(std::size_t b) const {
    return params_of<Model>(model_params[b]);
  }

  bool any_dilatation() const;
  /// Whether a block's model has a start_step (Model::has_start_step).
  bool any_start_step() const;
  bool any_damage() const;
  /// The most per-bond history arrays any block's model needs (0: no inelastic model).
  int bond_history_arrays() const;
  /// The most per-point arrays any block's model declares (MaterialHistory::point).
  int point_arrays() const;
  /// The most per-point constant arrays any block's model calibrates (point_constants).
  int point_constant_arrays() const;
  /// Sizes the history's point arrays and sets them to the start value each point's model declares.
  void initialize_point_arrays(MaterialHistory& history) const;
  /// The point arrays the present models declare that a partner's force reads, each once.
  std::vector<int> partner_point_arrays() const;
  /// The point arrays the present models fill with what θ lost to the bonds breaking now.
  std::vector<int> released_extension_arrays() const;
  /// Sets the Δt-dependent constants of every block's model (lps_viscoelastic's ε and β).
  void set_time_step(double dt);
};

}  // namespace peridot
