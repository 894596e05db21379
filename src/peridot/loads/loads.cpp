#include "peridot/loads/loads.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <numeric>

namespace peridot {

Loads::Loads(const Problem& problem, const Discretization& disc, const std::vector<NodeSet>& sets) : disc_(disc) {
  all_points_.resize(disc.num_points());
  std::iota(all_points_.begin(), all_points_.end(), 0u);
  for (const InitialConditionSpec& ic : problem.initial_conditions) {
    auto& target = ic.kind == InitialConditionSpec::Kind::displacement ? initial_displacement_ : initial_velocity_;
    for (int d = 0; d < 3; ++d)
      if (ic.component[d]) target.push_back({&points_of(sets, ic.node_set, all_points_), d, ScalarFunction(*ic.component[d])});
  }
  dof_kind_.assign(3 * disc.num_points(), DofKind::free);
  for (const BoundaryConditionSpec& bc : problem.boundary_conditions) {
    const DofKind kind =
        bc.kind == BoundaryConditionSpec::Kind::velocity ? DofKind::velocity : DofKind::displacement;
    const auto& points = points_of(sets, bc.node_set, all_points_);
    conditions_.push_back({kind, bc.component, &points, ScalarFunction(bc.value)});
    // A dof named by several conditions follows the last one (they are applied in deck order).
    for (std::uint32_t i : points) dof_kind_[3 * i + bc.component] = kind;
  }
  for (std::uint64_t k = 0; k < dof_kind_.size(); ++k)
    if (dof_kind_[k] != DofKind::free) prescribed_.push_back(k);
  for (const BodyForceSpec& bf : problem.body_forces)
    for (int d = 0; d < 3; ++d)
      if (bf.component[d]) {
        body_forces_.push_back({&points_of(sets, bf.node_set, all_points_), d, ScalarFunction(*bf.component[d])});
        body_force_time_dependent_ = body_force_time_dependent_ || body_forces_.back().value.depends_on_time();
      }
  for (const TractionSpec& traction : problem.tractions)
    for (int d = 0; d < 3; ++d)
      if (traction.component[d]) {
        body_forces_.push_back(
            {&points_of(sets, traction.node_set, all_points_), d, ScalarFunction(*traction.component[d]), 1 / traction.depth});
        body_force_time_dependent_ = body_force_time_dependent_ || body_forces_.back().value.depends_on_time();
      }
  // A load that starts as inf or NaN (1/x at x = 0) is a deck error, reported before anything runs.
  auto check_start = [&](const ScalarFunction& f, const std::vector<std::uint32_t>& points) {
    for (std::uint32_t i : points) f.at_start(disc.x(i, 0), disc.x(i, 1), disc.x(i, 2));
  };
  for (const auto* fields : {&initial_displacement_, &initial_velocity_, &body_forces_})
    for (const Field& field : *fields) check_start(field.value, *field.points);
  for (const Prescribed& c : conditions_) check_start(c.value, *c.points);
}

void Loads::set_boundary_value(std::size_t k, const Expression& value, double t) {
  ScalarFunction f(value);
  for (std::uint32_t i : *conditions_.at(k).points) {
    const double v = f(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), t);
    if (!std::isfinite(v))
      throw InputError(value.pos, fmt::format("expression '{}' is {} at t = {:g} at ({:g}, {:g}, {:g}) m", value.text, v, t,
                                              disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2)));
  }
  conditions_[k].value = std::move(f);
}

void Loads::apply_initial_conditions(State& state) const {
  for (const Field& field : initial_displacement_)
    for (std::uint32_t i : *field.points)
      state.u(i, field.component) = field.value(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), 0.0);
  for (const Field& field : initial_velocity_)
    for (std::uint32_t i : *field.points)
      state.v(i, field.component) = field.value(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), 0.0);
  for (const Prescribed& c : conditions_)
    for (std::uint32_t i : *c.points) {
      double value = c.value(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), 0.0);
      (c.kind == DofKind::velocity ? state.v : state.u)(i, c.component) = value;
    }
}

void Loads::apply_velocity_conditions(double t, VectorField& v) const {
  for (const Prescribed& c : conditions_) {
    if (c.kind != DofKind::velocity) continue;
    for (std::uint32_t i : *c.points) v(i, c.component) = c.value(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), t);
  }
}

void Loads::apply_displacement_conditions(double t, double dt, VectorField& u, VectorField& v) const {
  for (const Prescribed& c : conditions_) {
    if (c.kind != DofKind::displacement) continue;
    for (std::uint32_t i : *c.points) {
      const double value = c.value(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), t);
      v(i, c.component) = (value - u(i, c.component)) / dt;
      u(i, c.component) = value;
    }
  }
}

void Loads::apply_displacement_conditions(double t, double factor, VectorField& u) const {
  for (const Prescribed& c : conditions_) {
    if (c.kind != DofKind::displacement) continue;
    for (std::uint32_t i : *c.points)
      u(i, c.component) = factor * c.value(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), t);
  }
}

void Loads::update_body_force(double t, VectorField& b) {
  if (body_forces_.empty() || (body_force_evaluated_ && !body_force_time_dependent_)) return;
  evaluate_body_force(t, b);
  body_force_evaluated_ = true;
}

void Loads::evaluate_body_force(double t, VectorField& b) const {
  if (b.size() != disc_.num_points()) b.resize(disc_.num_points());
  std::fill(b.data(), b.data() + 3 * b.size(), 0.0);
  for (const Field& field : body_forces_)
    for (std::uint32_t i : *field.points)
      b(i, field.component) += field.scale * field.value(disc_.x(i, 0), disc_.x(i, 1), disc_.x(i, 2), t);
}

}  // namespace peridot
