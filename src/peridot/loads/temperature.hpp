#pragma once
// The prescribed temperature field of the deck's `temperature` section: T(x, y, z, t) at every point, owned
// and ghost (each rank evaluates its ghosts itself from their reference positions: no exchange). The bond
// loops read the free thermal stretch α (T − T_ref) of each point (ModelContext::thermal_stretch), the
// thermoviscoelastic model T itself (its WLF shift).
#include <cstddef>
#include <vector>

#include "peridot/deck/expression.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

class TemperatureField {
 public:
  TemperatureField(const TemperatureSpec& spec, const Discretization& disc);

  /// T (K) of every point of the discretization at time t, into `temperature` (sized to the points); returns
  /// whether it wrote. A field that does not depend on t is evaluated once; later calls leave `temperature` as it
  /// is and return false.
  bool evaluate(double t, std::vector<double>& temperature);
  /// T_ref (K).
  double reference() const { return reference_; }

 private:
  const Discretization& disc_;
  ScalarFunction value_;
  double reference_;
  bool evaluated_ = false;
};

}  // namespace peridot
