#pragma once
// Isotropic hypoelastic law in the unrotated frame (Foster, Silling & Chen 2010, eqs 19–22;
// docs/algorithms.md §6, step 5):
//   τ_{n+1} = τ_n + Δt (λ tr(d) I + 2G d),   λ = K − ⅔G,
// with d the unrotated rate of deformation (eq 18). Because τ̇ is objective (eq 21), a rigid rotation
// leaves τ unchanged and only rotates σ = R τ Rᵀ (eq 23). In small strain it is Hooke's law.
#include <string_view>
#include <vector>

#include "peridot/correspondence/constitutive.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/deck/schema.hpp"

namespace peridot::correspondence {

struct Hypoelastic {
  /// constitutive_law: hypoelastic; no keys beyond the elastic constants (correspondence/laws.hpp).
  static constexpr std::string_view name = "hypoelastic";
  static std::vector<KeySpec> keys() { return {}; }
  static Hypoelastic from_parameters(const Parameters&, const ElasticConstants& elastic, double /*density*/) {
    return {elastic.bulk_modulus, elastic.shear_modulus};
  }

  double bulk = 0;   ///< K (Pa)
  double shear = 0;  ///< G (Pa)

  struct History {};  ///< no state beyond τ

  Mat3 update(const Mat3& tau, const Mat3& d, double dt, History& history) const;
  double bulk_modulus() const { return bulk; }
  double shear_modulus() const { return shear; }

  /// From Young's modulus E (Pa) and Poisson's ratio ν (-).
  static Hypoelastic from_young_poisson(double E, double nu);
};

static_assert(ConstitutiveLaw<Hypoelastic>);

}  // namespace peridot::correspondence
