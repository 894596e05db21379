// Isotropic hypoelastic law in the unrotated frame: Foster, Silling & Chen (2010) eqs 19–22.
#include "peridot/correspondence/hypoelastic.hpp"

namespace peridot::correspondence {

Mat3 Hypoelastic::update(const Mat3& tau, const Mat3& d, double dt, History& /*history*/) const {
  const double lambda = bulk - 2.0 * shear / 3.0;
  return tau + dt * (lambda * d.trace() * Mat3::Identity() + 2.0 * shear * d);
}

Hypoelastic Hypoelastic::from_young_poisson(double E, double nu) {
  return Hypoelastic{E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu))};
}

}  // namespace peridot::correspondence
