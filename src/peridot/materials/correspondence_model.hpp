#pragma once
// The correspondence (non-ordinary state-based) material as a model of the registry: its deck keys, checks,
// page and block constants (Foster, Silling & Chen 2010). It has no bond kernel: its force is a per-point
// tensor gathered over the bonds (correspondence/force.hpp), driven by solvers/correspondence_blocks.hpp.
// Its constitutive laws describe themselves (correspondence/laws.hpp); their keys join the model's.
#include <string_view>

#include "peridot/correspondence/laws.hpp"
#include "peridot/deck/model_schema.hpp"
#include "peridot/materials/model_base.hpp"

namespace peridot {

struct CorrespondenceModel : ModelBase {
  static constexpr std::string_view name = "correspondence";
  static ModelInfo info();
  static constexpr bool has_bond_kernel = false;

  struct Params {
    correspondence::AnyLaw law;        ///< the constitutive law, with its parameters
    double hourglass_coefficient = 0;  ///< C_HG (-)
    double hourglass_viscosity = 0;    ///< C_HV (-)
    double bulk_viscosity_linear = 0;     ///< C_l (-)
    double bulk_viscosity_quadratic = 0;  ///< C_q (-)
  };
  /// Also sets the block's stable micromodulus and bond dashpot (the stable time step, see the page).
  static Params resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block);
  /// What the model cannot do yet, the keys of another law than the chosen one, the chosen law's required
  /// keys, and the chosen law's own checks.
  static void check(const MapReader& material, const Parameters& parameters, DeckContext& context);
};

}  // namespace peridot
