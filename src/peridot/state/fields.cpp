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
  history.plastic_strain.assign(n, 0.0);
  history.dissipation.assign(n, 0.0);
  history.yield_scale.assign(n, 1.0);
  history.plastic_strain_increment.assign(n, 0.0);
  history.deviatoric_moment.assign(n, 0.0);
  history.released_extension.assign(n, 0.0);
}

void State::size_history(std::size_t nnz, int arrays) {
  for (int k = 0; k < 2; ++k) history.bond[k].assign(k < arrays ? nnz : 0, 0.0);
}

}  // namespace peridot
