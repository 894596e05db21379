#include "peridot/solvers/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "peridot/core/exact_sum.hpp"
#include "peridot/damage/fragments.hpp"
#include "peridot/parallel/contact_candidates.hpp"
#include "peridot/parallel/domain.hpp"
#include "peridot/state/point_fields.hpp"

namespace peridot {

namespace {

/// The isotropic quadrature's direction weight of a body's block (discretization.quadrature: isotropic), fitted
/// to its model's stiffness moment; a model whose sums are not of that form is refused.
IsotropicQuadrature fit_block_quadrature(const Problem& problem, const BodySpec& body, const MaterialParams& p,
                                         const NeighborhoodOptions& neighborhood) {
  const int power = with_model(p.model, [](auto model) { return decltype(model)::quadrature_moment_power; });
  if (power == 0) {
    const std::string_view name = with_model(p.model, [](auto model) { return decltype(model)::name; });
    throw InputError(problem.quadrature_pos,
                     fmt::format("isotropic quadrature applies to pmb and the lps models; body '{}' has model {}",
                                 body.name, name));
  }
  // The fit sums one lattice family, (2δ/Δx + 1)^dimension sites: bounded so that an absurd deck is refused,
  // not left to run (families this large would not fit in memory as bonds anyway).
  constexpr double largest_ratio = 64;
  if (!(body.horizon <= largest_ratio * problem.spacing))
    throw InputError(problem.quadrature_pos,
                     fmt::format("isotropic quadrature: body '{}' has δ/Δx = {:.4g}; the fit is made for at most {:g}",
                                 body.name, body.horizon / problem.spacing, largest_ratio));
  return fit_isotropic_quadrature({.dimension = problem.dimension,
                                   .spacing = problem.spacing,
                                   .horizon = body.horizon,
                                   .influence = p.influence,
                                   .partial_volume_radius = neighborhood.partial_volume_radius,
                                   .bond_beyond_horizon = neighborhood.bond_beyond_horizon,
                                   .moment_power = power});
}

}  // namespace

Simulation::Simulation(const Problem& problem, Communicator comm) : problem_(problem), comm_(comm) {
  const auto setup_start = std::chrono::steady_clock::now();
  const bool partial = problem_.partial_volume != PartialVolumeKind::none;
  model_.partial_volume_radius = partial ? 0.5 * problem_.spacing : 0.0;
  NeighborhoodOptions neighborhood;
  neighborhood.partial_volume_radius = model_.partial_volume_radius;
  neighborhood.bond_beyond_horizon = problem_.partial_volume == PartialVolumeKind::extended;
  neighborhood.precracks = problem_.precracks;
  for (const BodySpec& body : problem_.bodies) {
    model_.add_block(resolve_material(problem_.material_of(body), body.horizon, problem_));
    neighborhood.horizon_of_block.push_back(body.horizon);
    if (problem_.quadrature == QuadratureKind::isotropic)
      model_.params.back().quadrature = fit_block_quadrature(problem_, body, model_.params.back(), neighborhood);
  }
  std::vector<std::uint8_t> no_fail;  // per global point
  auto mark_no_fail = [&](const Discretization& all, const std::vector<NodeSet>& sets) {
    if (problem_.no_fail_sets.empty()) return;
    no_fail.assign(all.num_points(), 0);
    for (const std::string& name : problem_.no_fail_sets)
      for (const NodeSet& set : sets)
        if (set.name == name)
          for (std::uint32_t i : set.points) no_fail[i] = 1;
  };
  // The partner bond j → i: the inelastic models read its history.
  const bool needs_partner_bonds = model_.bond_history_arrays() > 0;
  // Distributed, the points are made (lattice) and read (point files, meshes) piece by piece: no rank holds
  // them all (parallel/domain.hpp).
  Discretization near_walls;  // distributed: the points the symmetry walls' check reads, during the set-up only
  if (comm_.serial()) {
    disc_ = discretize(problem_);
    node_sets_ = build_node_sets(problem_, disc_);
    owned_ = global_points_ = disc_.num_points();
    bonds_ = build_neighborhood(disc_, neighborhood);
    if (needs_partner_bonds) build_reverse_bonds(bonds_);
    mark_no_fail(disc_, node_sets_);
    model_.no_fail = std::move(no_fail);
  } else {
    LocalDomain domain = decompose(comm_, problem_, neighborhood, problem_.partition);
    if (needs_partner_bonds) bond_halo_ = build_partner_bonds(comm_, domain);
    disc_ = std::move(domain.disc);
    bonds_ = std::move(domain.bonds);
    owned_ = domain.owned;
    global_points_ = domain.global_points;
    global_index_ = std::move(domain.global_index);
    halo_ = std::move(domain.halo);
    // The node sets over the owned points and the ghosts (a bond to a protected ghost never breaks); a set is
    // empty when it is on every rank.
    const std::vector<NodeSet> sets = build_node_sets(problem_, disc_, global_points_);
    std::vector<Diagnostic> empty;
    for (std::size_t s = 0; s < sets.size(); ++s) {
      NodeSet mine{sets[s].name, {}};
      for (std::uint32_t i : sets[s].points)
        if (i < owned_) mine.points.push_back(i);
      if (comm_.sum(static_cast<std::uint64_t>(mine.points.size())) == 0) empty.push_back(empty_node_set_error(problem_.node_sets[s]));
      node_sets_.push_back(std::move(mine));
    }
    if (!empty.empty()) throw InputError(empty);
    mark_no_fail(disc_, sets);
    model_.no_fail = std::move(no_fail);
    // The symmetry walls' check reads the points within a horizon of their planes (or behind them), in the
    // global order: those are gathered, on every rank, and no others.
    near_walls = assemble_discretization([&](std::size_t i) {
      const double horizon = model_.params[static_cast<std::size_t>(disc_.block[i])].horizon;
      return std::any_of(problem_.rigid_walls.begin(), problem_.rigid_walls.end(), [&](const RigidWallSpec& w) {
        return w.contact == WallContactKind::symmetry && dot(disc_.x.get(i) - w.point, w.normal) < horizon;
      });
    });
  }
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
  model_.disc = &disc_;
  model_.bonds = &bonds_;
  model_.ranges = block_ranges(disc_, owned_);

  std::optional<InputError> refused;
  try {
    check_symmetry_walls(problem_, comm_.serial() ? disc_ : near_walls, model_.params);
    correspondence_ = std::make_unique<CorrespondenceBlocks>(problem_, model_, &halo_, comm_);
    bodies_ = std::make_unique<RigidBodies>(problem_, model_);
    if (problem_.temperature) temperature_ = std::make_unique<TemperatureField>(*problem_.temperature, disc_);
  } catch (const InputError& e) {
    refused = e;  // found from this rank's bonds or points only: every rank must hear of it
  }
  agree_on_input_error(refused);
  if (problem_.contact) {
    double largest = 0;  // node radius, over the whole problem
    for (std::size_t i = 0; i < owned_; ++i) largest = std::max(largest, ShortRangeContact::node_radius(disc_.volume[i], problem_));
    short_range_ = std::make_unique<ShortRangeContact>(*problem_.contact, problem_, model_.params, model_.any_damage(),
                                                       comm_.max(largest));
    if (model_.any_damage()) contact_opened_.assign(bonds_.num_bonds(), 0.0);
  }

  any_dilatation_ = model_.any_dilatation();
  any_start_step_ = model_.any_start_step();
  any_damage_ = model_.any_damage();
  if (std::any_of(model_.params.begin(), model_.params.end(), [](const MaterialParams& p) { return p.fracture_energy > 0; }))
    energy_failure_ = std::make_unique<EnergyFailure>(model_, problem_.spacing, problem_.cross_section());
  history_arrays_ = model_.bond_history_arrays();
  partner_arrays_ = model_.partner_point_arrays();
  released_arrays_ = model_.released_extension_arrays();
  has_history_ = history_arrays_ > 0 || model_.point_arrays() > 0;

  state_.resize(disc_.num_points());
  if (history_arrays_ > 0) state_.size_history(bonds_.num_bonds() + bonds_.partner_slots, history_arrays_);
  model_.initialize_point_arrays(state_.history);
  compute_weighted_volume(model_, state_.weighted_volume);
  halo_.exchange(state_.weighted_volume);
  model_.inverse_weighted_volume.resize(disc_.num_points());
  for (std::size_t i = 0; i < disc_.num_points(); ++i) {
    const double m = state_.weighted_volume[i];
    model_.inverse_weighted_volume[i] = m > 0 ? 1 / m : 0.0;  // a point without bonds has no dilatation
  }
  calibrate_models(model_);
  surface_correction_ = correct_surfaces(model_, problem_, state_.history, owned_,
                                         [&](std::vector<double>& field) { halo_.exchange(field); }, comm_);
  for (std::vector<double>& constants : model_.point_constants) halo_.exchange(constants);  // a partner's kernel reads them
  if (any_start_step_) {  // what a force or an energy reads of a step before the first one (thermoviscoelastic's w)
    update_temperature();
    try {
      peridot::start_step(model_, state_.history, 0.0);
    } catch (const NumericalError& e) {
      // At t = 0 the field is the deck's as written (a WLF shift undefined at the initial temperature): a deck
      // problem, refused like one; later in the run the same check names the step (exit 3).
      const SourcePos where = problem_.temperature ? problem_.temperature->pos : problem_.solver.pos;
      refused = InputError(where, fmt::format("at t = 0: {}", e.what()));
    }
    agree_on_input_error(refused);
    exchange_partner_bonds();
  }
  try {
    loads_ = std::make_unique<Loads>(problem_, disc_, node_sets_);
  } catch (const InputError& e) {
    refused = e;  // a load that is not finite at this rank's points
  }
  agree_on_input_error(refused);

  work_.assign(disc_.num_points(), 0.0);
  stable_dt_ = comm_.min(peridot::stable_time_step(model_));
  const TimeIntegrator::Schedule schedule = time_schedule(problem_.solver, stable_dt_);
  dt_ = schedule.time_step;
  total_steps_ = schedule.steps;
  integrator_ = make_time_integrator(*this);
}

Simulation::~Simulation() = default;

Discretization Simulation::assemble_discretization(const std::function<bool(std::size_t)>& keep) const {
  std::vector<std::uint32_t> index, input;
  std::vector<double> x, volume;
  std::vector<std::int32_t> block;
  for (std::size_t i = 0; i < owned_; ++i) {
    if (!keep(i)) continue;
    index.push_back(global_index_[i]);
    x.insert(x.end(), disc_.x.data() + 3 * i, disc_.x.data() + 3 * i + 3);
    volume.push_back(disc_.volume[i]);
    block.push_back(disc_.block[i]);
    input.push_back(disc_.input_id[i]);
  }
  index = comm_.all_gather(index), x = comm_.all_gather(x), volume = comm_.all_gather(volume);
  block = comm_.all_gather(block), input = comm_.all_gather(input);
  std::vector<std::size_t> order(index.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return index[a] < index[b]; });
  Discretization all;
  all.dimension = disc_.dimension;
  all.block_names = disc_.block_names;
  all.x.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t t = order[k];
    all.x.set(k, Vec3{x[3 * t], x[3 * t + 1], x[3 * t + 2]});
    all.volume.push_back(volume[t]);
    all.block.push_back(block[t]);
    all.input_id.push_back(input[t]);
  }
  return all;
}

void Simulation::apply_initial_state() {
  state_.time = 0;
  state_.step = 0;
  loads_->apply_initial_conditions(state_);
  halo_.exchange(state_.u.data(), 3);
  halo_.exchange(state_.v.data(), 3);
  loads_->update_body_force(0.0, state_.body_force);
}

void Simulation::update_temperature() {
  if (!temperature_ || state_.time == temperature_time_) return;
  temperature_time_ = state_.time;
  if (!temperature_->evaluate(state_.time, model_.temperature)) return;  // a field constant in time: as it is
  const bool expands = std::any_of(model_.params.begin(), model_.params.end(),
                                   [](const MaterialParams& p) { return p.thermal_expansion != 0; });
  if (!expands) return;  // no thermal stretch: the bond loops keep their paths without it
  const std::size_t n = disc_.num_points();
  model_.thermal_stretch.resize(n);
  const double reference = temperature_->reference();
  for (std::size_t i = 0; i < n; ++i)
    model_.thermal_stretch[i] =
        model_.params[static_cast<std::size_t>(disc_.block[i])].thermal_expansion * (model_.temperature[i] - reference);
}

void Simulation::evaluate(double dt, bool break_bonds) {
  update_temperature();
  // Bond failure is checked in the first pass that computes every bond's stretch (on the current u,
  // before any force uses the bond).
  const bool fail = break_bonds && any_damage_;
  const bool fail_in_force_pass = !any_dilatation_ || model_.bond_failure_after_force;
  if (fail && energy_failure_) energy_failure_->break_bonds(model_, state_.u, nullptr);  // the committed work
  if (!fail)  // no bond breaks now: θ lost nothing to one
    for (int k : released_arrays_) std::fill(state_.history.point[k].begin(), state_.history.point[k].end(), 0.0);
  if (any_dilatation_) {
    compute_dilatation(model_, state_.u, state_.dilatation, fail && !fail_in_force_pass, &state_.history);
    halo_.exchange(state_.dilatation);
  }
  if (has_history_) {
    model_.set_time_step(dt);
    if (any_start_step_ && dt != started_dt_) {  // the first evaluation of a step (or a retry with another Δt)
      start_step(model_, state_.history, dt);
      exchange_partner_bonds();
      started_dt_ = dt;
    }
    prepare_history(model_, state_.u, state_.dilatation, state_.history);
    for (int k : partner_arrays_) halo_.exchange(state_.history.point[k]);  // what partners' forces read
  }
  compute_internal_force(model_, state_.u, state_.dilatation, state_.force, fail && fail_in_force_pass,
                         &state_.history);
  compute_contact();
  correspondence_failed_ = false;
  if (!has_correspondence()) return;
  try {
    correspondence_->evaluate(state_.u, state_.v, dt, state_.force);
  } catch (const NumericalError& e) {
    correspondence_failed_ = true;
    throw NumericalError(fmt::format("at step {}, time {:.6g} s: {}", state_.step, state_.time, e.what()));
  }
}

void Simulation::compute_contact() {
  if (!has_contact()) return;
  const std::size_t n = disc_.num_points();
  if (contact_force_.size() != n) contact_force_.resize(n);
  std::fill(contact_force_.data(), contact_force_.data() + 3 * n, 0.0);
  if (!bodies_->empty()) {
    bodies_->move_to(state_.time);
    bodies_->compute(disc_, owned_, state_.u, contact_force_);
    // A free body moves by the points' reaction, summed exactly: the same bits on every rank and any
    // rank count.
    for (std::size_t k = 0; k < bodies_->size(); ++k) {
      if ((*bodies_)[k].motion != RigidMotionKind::free) continue;
      const std::vector<BodyContact>& contacts = bodies_->contacts(k);
      std::vector<ExactSum> force(3);
      for (const BodyContact& c : contacts)
        for (int d = 0; d < 3; ++d) force[d].add(-c.force_density[d] * disc_.volume[c.point]);
      comm_.sum(force);
      bodies_->set_force(k, Vec3{force[0].value(), force[1].value(), force[2].value()});
    }
  }
  if (!short_range_) return;
  if (contact_y_.size() < 3 * owned_) contact_y_.resize(3 * owned_);
  bool build = short_range_->place(disc_.x, state_.u, owned_, contact_y_.data());
  if (!comm_.serial()) build = comm_.any(build);
  const bool friction = short_range_->has_friction();
  if (build) {
    // The owned points, and on a distributed run the other ranks' points near them, for the search.
    ContactCandidates candidates;
    for (std::size_t i = 0; i < owned_; ++i)
      candidates.add(comm_.serial() ? static_cast<std::uint32_t>(i) : global_index_[i], comm_.rank(), contact_y_.data() + 3 * i,
                     disc_.x.data() + 3 * i, disc_.volume[i], disc_.block[i]);
    candidates = gather_contact_candidates(comm_, std::move(candidates), short_range_->search_reach());
    short_range_->build(candidates, owned_, bonds_, global_index_, state_.u);
    if (!comm_.serial()) {
      std::vector<int> count = short_range_->remote_count();
      count.resize(static_cast<std::size_t>(comm_.size()), 0);
      const auto first = global_index_.begin(), last = global_index_.begin() + static_cast<std::ptrdiff_t>(owned_);
      contact_halo_ = Halo::serve(comm_, owned_, short_range_->remote(), count, 1, [&](const std::uint32_t* g) {
        return static_cast<std::uint32_t>(std::lower_bound(first, last, *g) - first);
      });
    }
    const std::size_t slots = owned_ + short_range_->remote().size();
    contact_y_.resize(3 * slots);  // the owned positions stay
    if (friction) contact_v_.assign(3 * slots, 0.0);
  }
  contact_halo_.exchange(contact_y_.data(), 3);
  if (friction) {
    std::copy(state_.v.data(), state_.v.data() + 3 * owned_, contact_v_.data());
    contact_halo_.exchange(contact_v_.data(), 3);
  }
  short_range_->compute(contact_y_.data(), friction ? contact_v_.data() : nullptr, bonds_.broken,
                        contact_opened_.empty() ? nullptr : contact_opened_.data(), contact_force_);
}

void Simulation::commit(double dt) {
  if (energy_failure_)  // the step's work, with the forces of the last evaluation (before the models commit)
    energy_failure_->accumulate(model_, state_.u, kernel_fields(model_, state_.dilatation, &state_.history));
  if (has_history_) {
    model_.set_time_step(dt);
    commit_history(model_, state_.u, state_.dilatation, state_.history, dt);
    started_dt_ = std::numeric_limits<double>::quiet_NaN();
  }
  // A failed correspondence evaluation is reported by the caller; its collective release decision is
  // skipped, as every rank stops at the next agree_on_failure.
  if (has_correspondence() && !correspondence_failed_) correspondence_->commit(state_.u, state_.v, state_.history);
  exchange_partner_bonds();
}

std::uint64_t Simulation::break_bonds() {
  if (!any_damage_) return 0;
  const auto count = [&] {
    return static_cast<std::uint64_t>(std::count(bonds_.broken.begin(), bonds_.broken.end(), std::uint8_t{1}));
  };
  const std::uint64_t before = count();
  if (energy_failure_) {  // at the last evaluation's u: the committed work and the step's so far
    const KernelFields fields = kernel_fields(model_, state_.dilatation, &state_.history);
    energy_failure_->break_bonds(model_, state_.u, &fields);
  }
  if (any_dilatation_ && !model_.bond_failure_after_force) {
    std::vector<double> theta;
    compute_dilatation(model_, state_.u, theta, true, &state_.history);  // e − e^dp for lps_plastic
  } else {
    VectorField f(disc_.num_points());
    std::vector<double> theta = state_.dilatation;
    compute_internal_force(model_, state_.u, theta, f, true, &state_.history);
  }
  const std::uint64_t broken = comm_.sum(count() - before);
  if (broken > 0) started_dt_ = std::numeric_limits<double>::quiet_NaN();  // the step starts again without them
  return broken;
}

Halo::Traffic Simulation::communication() const {
  Halo::Traffic t = halo_.traffic();
  t.seconds += bond_halo_.traffic().seconds + collective_seconds_;
  t.messages += bond_halo_.traffic().messages;
  t.bytes += bond_halo_.traffic().bytes;
  return t;
}

StateArrays Simulation::state_arrays() {
  StateArrays arrays;
  const std::size_t n = disc_.num_points(), nnz = bonds_.num_bonds();
  arrays.global("time", &state_.time);
  arrays.global("step", &state_.step);
  arrays.points("u", state_.u, n);
  arrays.points("v", state_.v, n);
  arrays.points("force", state_.force, n);
  arrays.points("body_force", state_.body_force, n);
  arrays.points("damage", state_.damage, n);
  arrays.points("dilatation", state_.dilatation, n);
  MaterialHistory& history = state_.history;
  for (std::size_t k = 0; k < history.bond.size(); ++k) arrays.bonds("history.bond" + std::to_string(k), history.bond[k], nnz);
  for (std::size_t k = 0; k < history.point.size(); ++k) arrays.points("history.point" + std::to_string(k), history.point[k], n);
  arrays.points("history.plastic_strain", history.plastic_strain, n);
  arrays.points("history.dissipation", history.dissipation, n);
  arrays.bonds("broken", bonds_.broken, nnz);
  arrays.points("external_work", work_, n);
  arrays.points("contact_force", contact_force_, contact_force_.size());
  arrays.points("contact_energy", contact_energy_, contact_energy_.size());
  arrays.bonds("contact_opened", contact_opened_, nnz);
  if (energy_failure_) energy_failure_->state_arrays(arrays);
  if (correspondence_) correspondence_->state_arrays(arrays);
  bodies_->state_arrays(arrays);
  integrator_->state_arrays(arrays);
  return arrays;
}

void Simulation::restored() {
  exchange_partner_bonds();
  if (correspondence_) correspondence_->restored();
  fragments_step_ = -1;
  temperature_time_ = std::numeric_limits<double>::quiet_NaN();
}

void Simulation::exchange_partner_bonds() {
  for (std::vector<double>& array : state_.history.bond)
    if (!array.empty()) bond_halo_.exchange(array);
}

void Simulation::agree_on_input_error(const std::optional<InputError>& error) const {
  // Diagnostics travel as text: file, line, column and message per diagnostic, unit and record separators.
  std::string text;
  if (error)
    for (const Diagnostic& d : error->diagnostics())
      text += fmt::format("{}\x1f{}\x1f{}\x1f{}\x1e", d.pos.file, d.pos.line, d.pos.column, d.message);
  const int failing = comm_.first_rank_with(error.has_value());
  if (failing < 0) return;
  if (comm_.serial()) throw *error;
  std::vector<Diagnostic> diagnostics;
  std::istringstream records(comm_.broadcast(text, failing));
  for (std::string record; std::getline(records, record, '\x1e');) {
    std::istringstream fields(record);
    std::string file, line, column, message;
    std::getline(fields, file, '\x1f');
    std::getline(fields, line, '\x1f');
    std::getline(fields, column, '\x1f');
    std::getline(fields, message);
    diagnostics.push_back({{file, std::stoi(line), std::stoi(column)}, message});
  }
  throw InputError(diagnostics);
}

void Simulation::agree_on_failure(const std::string& message) {
  const double start = comm_.serial() ? 0.0 : MPI_Wtime();
  const int failing = comm_.first_rank_with(!message.empty());
  if (!comm_.serial()) collective_seconds_ += MPI_Wtime() - start;
  if (failing < 0) return;
  throw NumericalError(comm_.broadcast(message, failing));
}

void Simulation::prepare_outputs(bool fields, bool totals) {
  compute_damage(model_, state_.damage);
  fragments();
  if (fields) {
    if (!any_dilatation_) compute_dilatation(model_, state_.u, state_.dilatation, false, &state_.history);
    if (has_correspondence()) correspondence_->write_point_outputs(state_);
    if (temperature_) {
      // The prescribed T, except where a J2 law with thermal softening has written its own (it has no 0 K).
      update_temperature();
      std::vector<double>& T = state_.point_outputs["temperature"];
      T.resize(disc_.num_points(), 0.0);
      for (std::size_t i = 0; i < disc_.num_points(); ++i)
        if (T[i] == 0) T[i] = model_.temperature[i];
    }
  }
  if (totals) {
    compute_strain_energy_density(model_, state_.u, state_.dilatation, energy_density_, &state_.history);
    if (has_correspondence()) correspondence_->strain_energy_density(energy_density_);
    if (any_damage_) {
      broken_bonds_ = comm_.sum(static_cast<std::uint64_t>(std::count(bonds_.broken.begin(), bonds_.broken.end(), std::uint8_t{1})));
      if (all_bonds_ == 0) all_bonds_ = global_bond_count();
    }
    if (has_contact()) {
      contact_energy_.assign(disc_.num_points(), 0.0);
      for (std::size_t i = 0; i < owned_; ++i) {
        if (!bodies_->empty()) contact_energy_[i] += bodies_->point_energy(disc_, state_.u, i);
        if (short_range_ && !contact_y_.empty())
          contact_energy_[i] += short_range_->point_energy_density(i, contact_y_.data(), bonds_.broken,
                                                                contact_opened_.empty() ? nullptr : contact_opened_.data()) *
                              disc_.volume[i];
      }
    }
    symmetry_force_density_.resize(problem_.rigid_walls.size());
    for (std::size_t w = 0; w < problem_.rigid_walls.size(); ++w)
      if (problem_.rigid_walls[w].contact == WallContactKind::symmetry && has_correspondence())
        correspondence_->symmetry_wall_force_density(w, symmetry_force_density_[w]);
  }
}

ExodusPiece Simulation::exodus_piece() const {
  ExodusPiece piece;
  piece.rank = comm_.rank();
  piece.ranks = comm_.size();
  piece.global_points = global_points_;
  piece.point_index.assign(global_index_.begin(), global_index_.begin() + static_cast<std::ptrdiff_t>(owned_));
  const std::size_t bodies = std::max<std::size_t>(problem_.bodies.size(), 1);
  std::vector<std::uint64_t> count(bodies, 0);
  for (std::size_t i = 0; i < owned_; ++i) ++count[static_cast<std::size_t>(disc_.block.empty() ? 0 : disc_.block[i])];
  for (std::size_t b = 0; b < bodies; ++b) {
    const std::uint64_t total = comm_.sum(count[b]);
    if (total == 0) continue;
    piece.blocks.push_back(static_cast<std::int32_t>(b));
    piece.block_sizes.push_back(total);
  }
  for (const NodeSet& set : node_sets_) piece.node_set_sizes.push_back(comm_.sum(static_cast<std::uint64_t>(set.points.size())));
  return piece;
}

std::vector<std::string> Simulation::plasticity_summary() const {
  if (!has_correspondence()) return {};
  const CorrespondenceBlocks::Extremes e = correspondence_->extremes();
  constexpr double far = std::numeric_limits<double>::infinity();
  // The global extreme, then the smallest input id holding it, then that point's reference position: each a
  // reduction, taken from the rank that owns the point.
  struct Where {
    bool found = false;
    double value = 0, id = 0;
    Vec3 x;
  };
  auto locate = [&](double value, std::size_t point) {
    const bool have = point != CorrespondenceBlocks::Extremes::none;
    Where w;
    w.found = comm_.any(have);
    if (!w.found) return w;
    w.value = comm_.max(have ? value : -far);
    const double id = have ? static_cast<double>(disc_.id_of(point)) : far;
    const bool candidate = have && value == w.value;
    w.id = comm_.min(candidate ? id : far);
    for (int d = 0; d < 3; ++d) w.x[d] = comm_.min(candidate && id == w.id ? disc_.x(point, d) : far);
    return w;
  };
  const Where plastic = locate(e.max_plastic_strain, e.plastic_point);
  const Where hot = locate(e.max_temperature, e.hot_point);
  const std::uint64_t near_melting = comm_.sum(e.near_melting);
  if (!plastic.found) return {};
  auto at = [](const Where& w) {
    return fmt::format("input id {:.0f}, reference position ({:g}, {:g}, {:g}) m", w.id, w.x.x, w.x.y, w.x.z);
  };
  std::vector<std::string> lines = {
      fmt::format("plasticity: largest equivalent plastic strain {:.6g} at {}", plastic.value, at(plastic))};
  if (hot.found) lines.push_back(fmt::format("plasticity: highest temperature {:.6g} K at {}", hot.value, at(hot)));
  if (near_melting > 0)
    lines.push_back(fmt::format(
        "warning: {} point{} heated to T* ≥ 0.99 (99 % of the way from the reference to the melting temperature), "
        "where the flow stress is all but zero: there the law no longer describes a solid (a thermal runaway: "
        "softening outpacing hardening)",
        near_melting, near_melting == 1 ? "" : "s"));
  return lines;
}

Totals Simulation::totals() {
  prepare_outputs(false, true);
  return output_totals();
}

double Simulation::energy_estimate() {
  compute_strain_energy_density(model_, state_.u, state_.dilatation, energy_density_, &state_.history);
  if (has_correspondence()) correspondence_->strain_energy_density(energy_density_);
  const double* v = state_.v.data();
  return reproducible_sum(comm_, owned_, [&](std::size_t i) {
    const double kinetic = 0.5 * density_of(i) * (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
    return (kinetic + energy_density_[i]) * disc_.volume[i];
  });
}

Totals Simulation::output_totals() const {
  // Every sum exact (core/exact_sum.hpp) over the owned points, then added over the ranks: each total is the
  // correctly rounded sum of its terms, the same bits for any thread and rank count, and nothing is gathered.
  Totals totals;
  const std::size_t n = owned_, bodies = bodies_->size(), blocks = problem_.bodies.size();
  const bool contact_force = short_range_ != nullptr, hourglass = has_correspondence(), contact = has_contact();
  enum : std::size_t { kinetic, strain, dissipated, hourglass_work, external, contact_energy, momentum, fixed = momentum + 3 };
  const std::size_t body_force = fixed, rigid_force = body_force + (contact_force ? 3 * blocks : 0);
  const std::size_t count = rigid_force + 3 * bodies;
  const double* v = state_.v.data();
  const double* dissipation = state_.history.dissipation.data();
  const double* c = contact_force_.data();
  std::vector<ExactSum> sums(count);
  double max_damage = 0;
  std::uint64_t fragments = 0;
#pragma omp parallel
  {
    std::vector<ExactSum> mine(count);
    double most = 0;
    std::uint64_t named = 0;
#pragma omp for schedule(static) nowait
    for (std::size_t i = 0; i < n; ++i) {
      const double V = disc_.volume[i], m = density_of(i) * V;
      mine[kinetic].add(0.5 * m * (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]));
      mine[strain].add(energy_density_[i] * V);
      if (dissipation) mine[dissipated].add(dissipation[i] * V);
      if (hourglass) mine[hourglass_work].add(correspondence_->point_hourglass_work()[i]);
      mine[external].add(work_[i]);
      if (contact) mine[contact_energy].add(contact_energy_[i]);
      for (int d = 0; d < 3; ++d) mine[momentum + static_cast<std::size_t>(d)].add(m * v[3 * i + d]);
      if (contact_force)
        for (int d = 0; d < 3; ++d)
          mine[body_force + 3 * static_cast<std::size_t>(disc_.block[i]) + static_cast<std::size_t>(d)].add(c[3 * i + d] * V);
      for (std::size_t w = 0; w < bodies; ++w) {
        const Vec3 f = bodies_->force_from_point(w, disc_, state_.u, i);
        for (int d = 0; d < 3; ++d) mine[rigid_force + 3 * w + static_cast<std::size_t>(d)].add(f[d]);
        if (w < symmetry_force_density_.size() && !symmetry_force_density_[w].empty())  // the mirror bonds' part
          for (int d = 0; d < 3; ++d) mine[rigid_force + 3 * w + static_cast<std::size_t>(d)].add(-symmetry_force_density_[w][3 * i + d] * V);
      }
      most = std::max(most, state_.damage[i]);
      // A fragment is named by the smallest input id of its points: count the points that name their own.
      if (state_.fragment[i] == static_cast<double>(disc_.id_of(i))) ++named;
    }
#pragma omp critical
    {
      for (std::size_t k = 0; k < count; ++k) sums[k].add(mine[k]);  // exact: the order does not matter
      max_damage = std::max(max_damage, most);
      fragments += named;
    }
  }
  comm_.sum(sums);
  totals.kinetic_energy = sums[kinetic].value();
  totals.strain_energy = sums[strain].value();
  totals.dissipated_energy = sums[dissipated].value();
  totals.hourglass_work = sums[hourglass_work].value();
  totals.external_work = sums[external].value();
  totals.contact_energy = sums[contact_energy].value();
  for (int d = 0; d < 3; ++d) totals.momentum[d] = sums[momentum + static_cast<std::size_t>(d)].value();
  if (contact_force)
    for (std::size_t b = 0; b < blocks; ++b)
      totals.body_contact_force.push_back({sums[body_force + 3 * b].value(), sums[body_force + 3 * b + 1].value(),
                                           sums[body_force + 3 * b + 2].value()});
  for (std::size_t w = 0; w < bodies; ++w)
    totals.rigid_force.push_back({sums[rigid_force + 3 * w].value(), sums[rigid_force + 3 * w + 1].value(),
                                  sums[rigid_force + 3 * w + 2].value()});
  totals.max_damage = comm_.max(max_damage);
  totals.fragments = comm_.sum(fragments);
  if (all_bonds_ > 0) totals.broken_fraction = static_cast<double>(broken_bonds_) / static_cast<double>(all_bonds_);
  return totals;
}

Vec3 Simulation::reaction(const std::string& set_name) const {
  std::vector<ExactSum> sums(3);
  for (const NodeSet& set : node_sets_)
    if (set.name == set_name)
      for (std::uint32_t i : set.points)  // owned points only
        for (int d = 0; d < 3; ++d) sums[d].add(-state_.force(i, d) * disc_.volume[i]);
  comm_.sum(sums);
  return {sums[0].value(), sums[1].value(), sums[2].value()};
}

void Simulation::fragments() {
  // Bonds change only inside step() (and never without damage): one labelling per step serves both the
  // Exodus frame and the history row of that step.
  const std::int64_t step = any_damage_ ? state_.step : 0;
  if (fragments_step_ == step) return;
  if (comm_.serial())
    label_fragments(bonds_, disc_.input_id, state_.fragment);
  else
    label_fragments(bonds_, disc_.input_id, state_.fragment, owned_,
                    [&](std::vector<double>& label) { halo_.exchange(label); },
                    [&](bool changed) { return comm_.any(changed); });
  fragments_step_ = step;
}


std::uint64_t Simulation::global_bond_count() const { return comm_.sum(bonds_.num_bonds()); }

std::size_t Simulation::memory_bytes() const {
  const std::size_t n = disc_.num_points(), nnz = bonds_.num_bonds();
  const std::size_t per_point =
      sizeof(double) * (3 /*x*/ + 1 /*V*/ + 3 * 4 /*u v f b*/ + 3 /*φ θ m*/ + 2 /*ε̄p, D*/ + 1 /*external work*/ +
                        (history_arrays_ > 0 ? 4 /*return-map scratch*/ : 0)) +
      4 + 4;
  const std::size_t per_bond = sizeof(std::uint32_t) + sizeof(std::uint8_t) + history_arrays_ * sizeof(double) +
                               (bonds_.reverse.empty() ? 0 : sizeof(std::uint32_t)) +
                               (model_.bond_scale.empty() ? 0 : sizeof(double)) +
                               (energy_failure_ ? 3 * sizeof(double) : 0);  // W, T, e (energy criterion)
  return n * per_point + (n + 1) * sizeof(std::uint64_t) + nnz * per_bond;
}

}  // namespace peridot
