#include "peridot/solvers/velocity_verlet.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "peridot/core/bounding_box.hpp"
#include "peridot/solvers/simulation.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

SolverInfo VelocityVerlet::info() {
  return {.name = name,
          .summary = "dynamics by velocity Verlet",
          .description = "the solver: explicit dynamics (velocity Verlet, the default) or, with type: relaxation "
                         "or implicit, quasi-static load steps (next sections)",
          .keys = {{.key = "end_time", .unit = Unit::time, .range = positive, .description = "simulated time (s); or num_steps",
                    .required = true, .one_of = "duration"},
                   {.key = "num_steps", .type = ValueType::integer, .range = at_least_one, .description = "number of steps; or end_time",
                    .required = true, .one_of = "duration"},
                   {.key = "time_step", .unit = Unit::time, .range = positive,
                    .description = "fixed Δt (s); default safety_factor × stable Δt"},
                   {.key = "safety_factor", .default_yaml = "0.8", .range = {0, 1, true, false},
                    .description = "fraction of the stable time step"},
                   {.key = "damping", .unit = Unit::rate, .default_yaml = "0", .range = {0, infinity, false, true},
                    .description = "mass-proportional viscous damping c (1/s): free velocities decay as e^(−ct); "
                                   "for relaxing to static equilibrium (the energy it removes is not in the history)"},
                   {.key = "bond_failure", .type = ValueType::choice, .default_yaml = "before_force",
                    .description = "when a bond over its critical stretch breaks: before_force, before it carries any force "
                                   "at that stretch (Peridigm's order); after_force, after carrying that step's force, so "
                                   "LPS's dilatation still counts it (LAMMPS PERI's order)",
                    .choices = {"before_force", "after_force"}}}};
}

TimeIntegrator::Schedule VelocityVerlet::schedule(const SolverSpec& solver, double stable_time_step) {
  const Parameters& q = solver.parameters;
  Schedule s;
  if (!q.has("time_step") && !std::isfinite(stable_time_step))
    throw InputError(solver.pos, "solver: no point has a bond, so the stable time step is unbounded; give solver.time_step");
  s.time_step = q.has("time_step") ? q.number("time_step") : q.number("safety_factor") * stable_time_step;
  if (q.has("end_time")) {
    // Whole steps that end exactly at end_time, none longer than the chosen Δt.
    const double end_time = q.number("end_time");
    // Beyond 2^53 steps the count is not an exact integer (and beyond 2^63 not even representable).
    if (const double steps = std::ceil(end_time / s.time_step); !(steps <= 0x1p53))
      throw InputError(q.find("end_time")->pos,
                       fmt::format("solver.end_time: {:g} s takes {:g} steps of {:g} s, more than a run can count; "
                                   "shorten the end time or give a larger time_step",
                                   end_time, steps, s.time_step));
    s.steps = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(end_time / s.time_step * (1 - 1e-12))));
    s.time_step = end_time / static_cast<double>(s.steps);
  } else {
    s.steps = q.has("num_steps") ? q.integer("num_steps") : 0;
  }
  return s;
}

VelocityVerlet::VelocityVerlet(Simulation& sim) : sim_(sim), damping_(sim.problem().solver.parameters.number("damping")) {
  sim.model().bond_failure_after_force = sim.problem().solver.parameters.text("bond_failure") == "after_force";
  // The whole problem's extent (exact minima and maxima over the ranks): the same limit everywhere.
  const Discretization& mine = sim.discretization();
  const Communicator& comm = sim.communicator();
  const BoundingBox box = bounding_box(mine.x.data(), 3, sim.num_owned());
  double extent = 0;
  for (int d = 0; d < 3; ++d) {
    const double lo = comm.min(box.lo[d]), hi = comm.max(box.hi[d]);
    if (hi >= lo) extent = std::max(extent, hi - lo);
  }
  double horizon = 0;
  for (const MaterialParams& p : sim.model().params) horizon = std::max(horizon, p.horizon);
  runaway_ = 100 * (extent + horizon);
  watch_energy_ = !sim.problem().temperature.has_value();
}

void VelocityVerlet::initialize() {
  sim_.apply_initial_state();
  // No time passes at t = 0: the history starts from the initial displacement with Δt = 0 (an initial
  // displacement beyond yield flows plastically at once; a viscous back extension starts at 0).
  std::string failure;
  try {
    sim_.evaluate(0.0, true);
  } catch (const NumericalError& e) {
    failure = e.what();  // every exchange below still runs: the other ranks wait for this rank's messages
  }
  sim_.commit(0.0);
  sim_.agree_on_failure(failure);
  watch_ = EnergyWatch{};
  if (watch_energy_) watch_.initial = sim_.energy_estimate();  // no gathering to rank 0
}

std::string VelocityVerlet::watch_energy() {
  const State& state = sim_.state();
  const Communicator& comm = sim_.communicator();
  const Discretization& disc = sim_.discretization();
  const std::size_t owned = sim_.num_owned();
  const double* v = state.v.data();
  auto kinetic = [&](std::size_t i) {
    return 0.5 * sim_.density_of(i) * disc.volume[i] * (v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2]);
  };
  const double energy = reproducible_sum(comm, owned, kinetic);
  const std::vector<double>& work = sim_.external_work();
  const double external = reproducible_sum(comm, owned, [&](std::size_t i) { return work[i]; });
  EnergyWatch& w = watch_;
  std::rotate(w.kinetic.begin(), w.kinetic.begin() + 1, w.kinetic.end());
  w.kinetic.back() = energy;
  w.most_work = std::max(w.most_work, std::abs(external));
  if (++w.checks < static_cast<std::int64_t>(w.kinetic.size())) return {};
  const double supplied = w.initial + w.most_work;
  if (!(energy > 10 * supplied && energy > w.kinetic.front())) return {};
  // The point of largest kinetic energy, on the rank that owns it.
  std::size_t top = 0;
  for (std::size_t i = 1; i < owned; ++i)
    if (kinetic(i) > kinetic(top)) top = i;
  const double mine = owned > 0 ? kinetic(top) : -1.0;
  if (comm.first_rank_with(mine == comm.max(mine)) != comm.rank()) return {};  // agree_on_failure takes the owner's
  const Vec3 x = disc.x.get(top);
  return fmt::format(
      "kinetic energy growing without a source at step {}, time {:.6g} s: {:.6g} J, up from {:.6g} J {} steps before and "
      "{:.0f} times the energy supplied ({:.6g} J: at t = 0 and the largest external work); fastest point {} "
      "(block '{}') at ({:.6g}, {:.6g}, {:.6g}) m, |v| = {:.6g} m/s. The solution is blowing up (a time step above the "
      "stable one, or a density or modulus out of range?); Δt = {:.6g} s, stable Δt = {:.6g} s",
      state.step, state.time, energy, w.kinetic.front(), energy_check_interval * static_cast<std::int64_t>(w.kinetic.size() - 1),
      supplied > 0 ? energy / supplied : INFINITY, supplied, disc.input_id[top], disc.block_names[disc.block[top]], x.x, x.y, x.z,
      std::sqrt(2 * kinetic(top) / (sim_.density_of(top) * disc.volume[top])), sim_.time_step(), sim_.stable_time_step());
}

void VelocityVerlet::kick(double half_dt) {
  sim_.rigid_bodies().kick(half_dt);  // free bodies, by the points' reaction at the last evaluation
  const ModelContext& model = sim_.model();
  State& state = sim_.state();
  const auto& kind = sim_.loads().dof_kinds();
  double* v = state.v.data();
  const double* f = state.force.data();
  const double* b = state.body_force.data();
  const double* c = sim_.has_contact() ? sim_.contact_force().data() : nullptr;
  for (std::size_t block = 0; block < model.ranges.size(); ++block) {
    const BlockRange range = model.ranges[block];
    const double scale = half_dt / model.params[block].density;
    const double decay = std::exp(-damping_ * half_dt);
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

void VelocityVerlet::advance() {
  State& state = sim_.state();
  Loads& loads = sim_.loads();
  const Discretization& disc = sim_.discretization();
  const double dt = sim_.time_step();
  const double t = state.time;
  const std::size_t owned = sim_.num_owned();
  const std::size_t dofs = 3 * owned;
  const auto& prescribed = loads.prescribed_dofs();
  const auto& kind = loads.dof_kinds();
  const double* volume = disc.volume.data();
  double* work = sim_.external_work().data();
  auto dof_mass = [&](std::uint64_t k) { return sim_.density_of(k / 3) * volume[k / 3]; };
  // Work of the supports on prescribed dofs, R = m a − (f + b)V, and of the body force, by the trapezoidal
  // rule over the step, kept per point; m a·Δu is the change of those dofs' kinetic energy.
  for (std::uint64_t k : prescribed) work[k / 3] -= 0.5 * dof_mass(k) * state.v.data()[k] * state.v.data()[k];
  auto add_work = [&]() {
    const double* v = state.v.data();  // v^{n+½}: Δu = Δt v^{n+½}
    const double* f = state.force.data();
    const double* b = state.body_force.data();
    const double* c = sim_.has_contact() ? sim_.contact_force().data() : nullptr;
    for (std::uint64_t k : prescribed) work[k / 3] -= 0.5 * f[k] * volume[k / 3] * dt * v[k];
    const bool body_force = loads.has_body_force();
    if (!body_force && !c) return;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < owned; ++i)
      for (std::size_t k = 3 * i; k < 3 * i + 3; ++k) {
        const double applied = (body_force ? b[k] : 0.0) + (c ? c[k] : 0.0);
        if (kind[k] == DofKind::free) work[i] += 0.5 * applied * volume[i] * dt * v[k];
      }
  };

  kick(0.5 * dt);
  loads.apply_velocity_conditions(t + 0.5 * dt, state.v);
  double* u = state.u.data();
  const double* v = state.v.data();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < dofs; ++k)
    if (kind[k] != DofKind::displacement) u[k] += dt * v[k];
  sim_.rigid_bodies().drift(dt);
  loads.apply_displacement_conditions(t + dt, dt, state.u, state.v);
  sim_.exchange_ghosts(state.u);
  if (sim_.has_correspondence()) sim_.exchange_ghosts(state.v);  // Ḟ reads the partners' v^{n+½}
  add_work();

  state.time = t + dt;
  state.step += 1;
  loads.update_body_force(state.time, state.body_force);
  std::string failure;
  try {
    sim_.evaluate(dt, true);
  } catch (const NumericalError& e) {
    // Reported below, once every rank has reached the same point; every exchange until then still runs,
    // since the other ranks wait for this rank's messages.
    failure = e.what();
  }
  sim_.commit(dt);
  add_work();

  kick(0.5 * dt);
  loads.apply_velocity_conditions(state.time, state.v);
  for (std::uint64_t k : prescribed) work[k / 3] += 0.5 * dof_mass(k) * state.v.data()[k] * state.v.data()[k];

  // A non-finite velocity or displacement means the run has failed, and so does a displacement of 100 times
  // the problem's size (a blow-up on its way to inf): name the first such point.
  std::size_t bad = dofs;
  const double runaway = runaway_;
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (std::size_t k = 0; k < dofs; ++k)
    if (!std::isfinite(v[k]) || !(std::abs(u[k]) <= runaway)) bad = std::min(bad, k);
  if (bad < dofs && failure.empty()) {
    const std::size_t i = bad / 3;
    const Vec3 x = disc.x.get(i);
    const bool finite = std::isfinite(u[bad]) && std::isfinite(v[bad]);
    std::ostringstream msg;
    msg.precision(6);
    msg << (finite ? "runaway" : "non-finite") << " " << (std::isfinite(u[bad]) && !finite ? "velocity" : "displacement")
        << " at step " << state.step << ", time " << state.time << " s, point " << disc.input_id[i] << " (block '"
        << disc.block_names[disc.block[i]] << "') at (" << x.x << ", " << x.y << ", " << x.z << ") m";
    if (finite)
      msg << ": |u| = " << std::abs(u[bad]) << " m, more than 100 times the problem's size (" << runaway / 100
          << " m with a horizon); the solution has blown up (a time step above the stable one, or a density or modulus "
             "out of range?)";
    msg << "; Δt = " << dt << " s, stable Δt = " << sim_.stable_time_step() << " s";
    failure = msg.str();
  }
  // Collective: every rank checks at the same steps, whatever it found above.
  if (watch_energy_ && state.step % energy_check_interval == 0) {
    const std::string growing = watch_energy();
    if (failure.empty()) failure = growing;
  }
  sim_.agree_on_failure(failure);
}

std::string VelocityVerlet::describe() const {
  std::string out;
  out += fmt::format("solver           explicit (velocity Verlet)\n");
  out += fmt::format("stable time step {:.6g} s (Silling–Askari)\n", sim_.stable_time_step());
  out += fmt::format("time step        {:.6g} s{}\n", sim_.time_step(),
                     sim_.time_step() > sim_.stable_time_step() ? "  WARNING: above the stable time step" : "");
  out += fmt::format("steps            {} (end time {:.6g} s)\n", sim_.total_steps(),
                     sim_.time_step() * static_cast<double>(sim_.total_steps()));
  return out;
}

}  // namespace peridot
