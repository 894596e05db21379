#include "peridot/state/fields.hpp"

namespace peridot {

void State::resize(std::size_t n) {
  u.resize(n);
  v.resize(n);
  force.resize(n);
  body_force.resize(n);
  damage.assign(n, 0.0);
  dilatation.assign(n, 0.0);
  weighted_volume.assign(n, 0.0);
}

}  // namespace peridot
