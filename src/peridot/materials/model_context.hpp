#pragma once
// What every bond loop needs of a problem and that does not change during a run: the points, the bonds,
// each block's resolved material and point range. Built by the solver (solvers/simulation.cpp), read by the
// materials' kernels, damage, contact and the solvers' bond loops.
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
  /// The per-point scratch arrays the present models declare that a partner's force reads
  /// (partner_point_scratch of each model), each once, in the order the models declare them.
  std::vector<std::vector<double> MaterialHistory::*> partner_point_scratch() const;
};

}  // namespace peridot
