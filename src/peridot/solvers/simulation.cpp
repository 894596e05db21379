#include "peridot/solvers/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "peridot/damage/fragments.hpp"

namespace peridot {

Simulation::Simulation(const Problem& problem) : problem_(problem) {
  disc_ = discretize(problem_);
  node_sets_ = build_node_sets(problem_, disc_);

  model_.disc = &disc_;
  model_.bonds = &bonds_;
  model_.ranges = block_ranges(disc_);
  const bool partial = problem_.partial_volume != PartialVolumeKind::none;
  model_.partial_volume_radius = partial ? 0.5 * problem_.spacing : 0.0;
  NeighborhoodOptions neighborhood;
  neighborhood.partial_volume_radius = model_.partial_volume_radius;
  neighborhood.bond_beyond_horizon = problem_.partial_volume == PartialVolumeKind::extended;
  neighborhood.precracks = problem_.precracks;
  for (const BodySpec& body : problem_.bodies) {
    model_.params.push_back(resolve_material(problem_.material_of(body), body.horizon, problem_));
    neighborhood.horizon_of_block.push_back(body.horizon);
  }
  bonds_ = build_neighborhood(disc_, neighborhood);
  // The partner bond j → i: inelastic models read its history, the correspondence gather its weight.
  const bool correspondence = std::any_of(model_.params.begin(), model_.params.end(),
                                          [](const MaterialParams& p) { return p.model == ModelKind::correspondence; });
  if (model_.bond_history_arrays() > 0 || correspondence) build_reverse_bonds(bonds_);
  correspondence_ = std::make_unique<CorrespondenceBlocks>(problem_, model_);
  walls_ = std::make_unique<RigidWalls>(problem_, model_);

  if (!problem_.no_fail_sets.empty()) {
    model_.no_fail.assign(disc_.num_points(), 0);
    for (const std::string& name : problem_.no_fail_sets)
      for (const NodeSet& set : node_sets_)
        if (set.name == name)
          for (std::uint32_t i : set.points) model_.no_fail[i] = 1;
  }
  any_dilatation_ = model_.any_dilatation();
  any_damage_ = model_.any_damage();
  history_arrays_ = model_.bond_history_arrays();

  state_.resize(disc_.num_points());
  if (history_arrays_ > 0) state_.size_history(bonds_.num_bonds(), history_arrays_);
  compute_weighted_volume(model_, state_.weighted_volume);
  model_.inverse_weighted_volume.resize(disc_.num_points());
  for (std::size_t i = 0; i < disc_.num_points(); ++i) {
    const double m = state_.weighted_volume[i];
    model_.inverse_weighted_volume[i] = m > 0 ? 1 / m : 0.0;  // a point without bonds has no dilatation
  }
  calibrate_models(model_);
  loads_ = std::make_unique<Loads>(problem_, disc_, node_sets_);

  stable_dt_ = peridot::stable_time_step(model_);
  const SolverSpec& solver = problem_.solver;
  dt_ = solver.time_step ? *solver.time_step : solver.safety_factor * stable_dt_;
  if (solver.end_time) {
    // Whole steps that end exactly at end_time, none longer than the chosen Δt.
    total_steps_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(*solver.end_time / dt_ * (1 - 1e-12))));
    dt_ = *solver.end_time / static_cast<double>(total_steps_);
  } else {
    total_steps_ = solver.num_steps.value_or(0);
  }
}

void Simulation::initialize() {
  state_.time = 0;
  state_.step = 0;
  loads_->apply_initial_conditions(state_);
  loads_->update_body_force(0.0, state_.body_force);
  // No time passes at t = 0: the history starts from the initial displacement with Δt = 0 (an initial
  // displacement beyond yield flows plastically at once; a viscous back extension starts at 0).
  set_time_step(model_.params, 0.0);
  compute_forces(0.0);
  if (history_arrays_ > 0) commit_history(model_, state_.u, state_.dilatation, state_.history, 0.0);
  set_time_step(model_.params, dt_);
}

void Simulation::compute_forces(double dt) {
  // Bond failure is checked in the first pass that computes every bond's stretch (on u^{n+1}, before any
  // force uses the bond).
  const bool fail_in_force_pass = !any_dilatation_ || model_.bond_failure_after_force;
  if (any_dilatation_)
    compute_dilatation(model_, state_.u, state_.dilatation, any_damage_ && !fail_in_force_pass, &state_.history);
  if (history_arrays_ > 0) prepare_history(model_, state_.u, state_.dilatation, state_.history);
  compute_internal_force(model_, state_.u, state_.dilatation, state_.force, any_damage_ && fail_in_force_pass,
                         &state_.history);
  if (!walls_->empty()) walls_->compute(state_.u, state_.time, wall_force_);
  if (!has_correspondence()) return;
  try {
    correspondence_->compute_force(state_.u, state_.v, dt, state_.force, state_.history);
  } catch (const NumericalError& e) {
    throw NumericalError(fmt::format("at step {}, time {:.6g} s: {}", state_.step, state_.time, e.what()));
  }
}

void Simulation::kick(double half_dt) {
  const auto& kind = loads_->dof_kinds();
  double* v = state_.v.data();
  const double* f = state_.force.data();
  const double* b = state_.body_force.data();
  const double* c = walls_->empty() ? nullptr : wall_force_.data();
  for (std::size_t block = 0; block < model_.ranges.size(); ++block) {
    const BlockRange range = model_.ranges[block];
    const double scale = half_dt / model_.params[block].density;
    const double decay = std::exp(-problem_.solver.damping * half_dt);
    if (c) {
#pragma omp parallel for schedule(static)
      for (std::size_t k = 3 * range.begin; k < 3 * range.end; ++k)
        if (kind[k] == DofKind::free) v[k] = decay * v[k] + scale * (f[k] + b[k] + c[k]);
    } else {
#pragma omp parallel for schedule(static)
      for (std::size_t k = 3 * range.begin; k < 3 * range.end; ++k)
        if (kind[k] == DofKind::free) v[k] = decay * v[k] + scale * (f[k] + b[k]);
    }
  }
}

void Simulation::step() {
  const double dt = dt_;
  const double t = state_.time;
  const std::size_t dofs = 3 * disc_.num_points();
  const auto& prescribed = loads_->prescribed_dofs();
  const auto& kind = loads_->dof_kinds();
  auto dof_mass = [&](std::uint64_t k) { return model_.params[disc_.block[k / 3]].density * disc_.volume[k / 3]; };
  // Work of the supports on prescribed dofs, R = m a − (f + b)V, and of the body force, by the trapezoidal
  // rule over the step; m a·Δu is the change of those dofs' kinetic energy.
  double kinetic_prescribed_before = 0;
  for (std::uint64_t k : prescribed) kinetic_prescribed_before += 0.5 * dof_mass(k) * state_.v.data()[k] * state_.v.data()[k];
  auto work_increment = [&]() {
    const double* v = state_.v.data();  // v^{n+½}: Δu = Δt v^{n+½}
    const double* f = state_.force.data();
    const double* b = state_.body_force.data();
    const double* c = walls_->empty() ? nullptr : wall_force_.data();
    double w = 0;
    for (std::uint64_t k : prescribed) w -= 0.5 * f[k] * disc_.volume[k / 3] * dt * v[k];
    const bool body_force = loads_->has_body_force();
    if (body_force || c)
      w += deterministic_sum(dofs, [&](std::size_t k) {
        const double applied = (body_force ? b[k] : 0.0) + (c ? c[k] : 0.0);
        return kind[k] == DofKind::free ? 0.5 * applied * disc_.volume[k / 3] * dt * v[k] : 0.0;
      });
    return w;
  };

  kick(0.5 * dt);
  loads_->apply_velocity_conditions(t + 0.5 * dt, state_.v);
  double* u = state_.u.data();
  const double* v = state_.v.data();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < dofs; ++k)
    if (kind[k] != DofKind::displacement) u[k] += dt * v[k];
  loads_->apply_displacement_conditions(t + dt, dt, state_.u, state_.v);
  external_work_ += work_increment();

  state_.time = t + dt;
  state_.step += 1;
  loads_->update_body_force(state_.time, state_.body_force);
  compute_forces(dt);
  if (history_arrays_ > 0) commit_history(model_, state_.u, state_.dilatation, state_.history, dt);
  external_work_ += work_increment();

  kick(0.5 * dt);
  loads_->apply_velocity_conditions(state_.time, state_.v);
  double kinetic_prescribed_after = 0;
  for (std::uint64_t k : prescribed) kinetic_prescribed_after += 0.5 * dof_mass(k) * state_.v.data()[k] * state_.v.data()[k];
  external_work_ += kinetic_prescribed_after - kinetic_prescribed_before;

  // A non-finite velocity means the run has failed: name the first such point.
  std::size_t bad = dofs;
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (std::size_t k = 0; k < dofs; ++k)
    if (!std::isfinite(v[k]) || !std::isfinite(u[k])) bad = std::min(bad, k);
  if (bad < dofs) {
    const std::size_t i = bad / 3;
    const Vec3 x = disc_.x.get(i);
    std::ostringstream msg;
    msg.precision(6);
    msg << "non-finite " << (std::isfinite(u[bad]) ? "velocity" : "displacement") << " at step " << state_.step
        << ", time " << state_.time << " s, point " << disc_.input_id[i] << " (block '" << disc_.block_names[disc_.block[i]]
        << "') at (" << x.x << ", " << x.y << ", " << x.z << ") m; Δt = " << dt << " s, stable Δt = " << stable_dt_
        << " s";
    throw NumericalError(msg.str());
  }
}

void Simulation::update_output_fields() {
  compute_damage(model_, state_.damage);
  if (any_damage_) fragments();
  if (!any_dilatation_) compute_dilatation(model_, state_.u, state_.dilatation, false, &state_.history);
  if (has_correspondence()) correspondence_->write_point_outputs(state_);
}

Totals Simulation::totals() {
  Totals totals;
  const std::size_t n = disc_.num_points();
  auto density = [&](std::size_t i) { return model_.params[disc_.block[i]].density; };
  const double* v = state_.v.data();
  totals.kinetic_energy = deterministic_sum(n, [&](std::size_t i) {
    return 0.5 * density(i) * disc_.volume[i] * (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
  });
  compute_strain_energy_density(model_, state_.u, state_.dilatation, energy_density_, &state_.history);
  if (has_correspondence()) {
    correspondence_->strain_energy_density(energy_density_);
    totals.hourglass_work = correspondence_->hourglass_work();
  }
  totals.strain_energy = deterministic_sum(n, [&](std::size_t i) { return energy_density_[i] * disc_.volume[i]; });
  const double* dissipation = state_.history.dissipation.data();
  totals.dissipated_energy = deterministic_sum(n, [&](std::size_t i) { return dissipation[i] * disc_.volume[i]; });
  for (int d = 0; d < 3; ++d)
    totals.momentum[d] = deterministic_sum(n, [&](std::size_t i) { return density(i) * disc_.volume[i] * v[3 * i + d]; });
  compute_damage(model_, state_.damage);
  for (double phi : state_.damage) totals.max_damage = std::max(totals.max_damage, phi);
  totals.fragments = fragments();
  return totals;
}

std::size_t Simulation::fragments() {
  // Bonds change only inside step() (and never without damage): one labelling per step serves both the
  // Exodus frame and the history row of that step.
  const std::int64_t step = any_damage_ ? state_.step : 0;
  if (fragments_step_ != step) {
    fragment_count_ = label_fragments(bonds_, disc_.input_id, state_.fragment);
    fragments_step_ = step;
  }
  return fragment_count_;
}

Vec3 Simulation::reaction(const NodeSet& set) const {
  Vec3 r;
  for (std::uint32_t i : set.points)
    for (int d = 0; d < 3; ++d) r[d] -= state_.force(i, d) * disc_.volume[i];
  return r;
}

std::size_t Simulation::memory_bytes() const {
  const std::size_t n = disc_.num_points(), nnz = bonds_.num_bonds();
  const std::size_t per_point =
      sizeof(double) * (3 /*x*/ + 1 /*V*/ + 3 * 4 /*u v f b*/ + 3 /*φ θ m*/ + 2 /*ε̄p, D*/ +
                        (history_arrays_ > 0 ? 4 /*return-map scratch*/ : 0)) +
      4 + 4;
  const std::size_t per_bond = sizeof(std::uint32_t) + sizeof(std::uint8_t) + history_arrays_ * sizeof(double) +
                               (bonds_.reverse.empty() ? 0 : sizeof(std::uint32_t));
  return n * per_point + (n + 1) * sizeof(std::uint64_t) + nnz * per_bond;
}

}  // namespace peridot
