#include "peridot/loads/temperature.hpp"

#include <omp.h>

namespace peridot {

TemperatureField::TemperatureField(const TemperatureSpec& spec, const Discretization& disc)
    : disc_(disc), value_(spec.value), reference_(spec.reference) {
  for (std::size_t i = 0; i < disc.num_points(); ++i) value_.at_start(disc.x(i, 0), disc.x(i, 1), disc.x(i, 2));
}

bool TemperatureField::evaluate(double t, std::vector<double>& temperature) {
  if (evaluated_ && !value_.depends_on_time()) return false;
  const std::size_t n = disc_.num_points();
  temperature.resize(n);
  // muParser keeps state: each thread evaluates its own copy. Every point's value is the same whatever the
  // thread that computes it.
#pragma omp parallel
  {
    const ScalarFunction value = value_;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) temperature[i] = value(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), t);
  }
  evaluated_ = true;
  return true;
}

}  // namespace peridot
