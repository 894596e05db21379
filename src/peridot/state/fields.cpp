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
}

void State::size_history(std::size_t nnz, int arrays) {
  history.bond.assign(static_cast<std::size_t>(arrays), std::vector<double>(nnz, 0.0));
}

const std::vector<std::string>& correspondence_output_names() {
  static const std::vector<std::string> names = [] {
    const std::string axes = "xyz";
    std::vector<std::string> all;
    for (char r : axes)
      for (char c : axes) all.push_back(std::string("deformation_gradient_") + r + c);
    const char* const symmetric[] = {"xx", "yy", "zz", "xy", "yz", "zx"};
    for (const char* rc : symmetric) all.push_back(std::string("cauchy_stress_") + rc);
    all.push_back("von_mises_stress");
    for (const char* rc : symmetric) all.push_back(std::string("green_lagrange_strain_") + rc);
    return all;
  }();
  return names;
}

}  // namespace peridot
