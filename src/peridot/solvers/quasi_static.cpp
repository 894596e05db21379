#include "peridot/solvers/quasi_static.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "peridot/core/bounding_box.hpp"
#include "peridot/deck/map_reader.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/solvers/simulation.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

std::vector<KeySpec> QuasiStatic::load_step_keys(std::string_view max_iterations_default,
                                                 std::string_view max_iterations_description) {
  std::vector<KeySpec> keys = {{.key = "load_steps", .type = ValueType::integer, .default_yaml = "1", .range = at_least_one,
                    .description = "number of load steps N; step k is solved at t_k = k·end_time/N"},
                   {.key = "end_time", .unit = Unit::time, .default_yaml = "1 s", .range = positive,
                    .description = "time of the last load step (s): where time-dependent loads are evaluated, and the "
                                   "real time over which viscous and rate-dependent materials relax"},
                   {.key = "ramp", .type = ValueType::boolean, .default_yaml = "true",
                    .description = "scale prescribed displacements and body forces by the load factor k/N (false: take "
                                   "them as the expressions give them at t_k)"},
                   {.key = "load_history", .type = ValueType::choice, .default_yaml = "continuous",
                    .description = "continuous: each step's loads are those of t_k; steps: the loads jump at the load "
                                   "step times and hold between them (creep and relaxation tests): t = 0 is solved with "
                                   "no time passing, and each step first creeps over Δt under the previous loads, then "
                                   "takes its own with no time passing",
                    .choices = {"continuous", "steps"}},
                   {.key = "creep_substeps", .type = ValueType::integer, .default_yaml = "1", .range = at_least_one,
                    .description = "load_history: steps only: the creep over the step after a load jump is solved in "
                                   "this many equilibria, each twice as long as the one before (the first Δt/(2ⁿ − 1)), "
                                   "so that a relaxation time far below Δt is followed after the jump; the other steps "
                                   "are solved whole, and each load step still gives one output"},
                   {.key = "breaking", .type = ValueType::choice, .default_yaml = "until_stable",
                    .description = "until_stable: after each equilibrium the bonds over their threshold break and the "
                                   "step is solved again until none breaks (the quasi-static answer); once_per_step: "
                                   "one breaking pass per load step, then one more equilibrium, as Madenci & Oterkus "
                                   "do: a crack then advances by a few bonds per step, so how far it runs by a given "
                                   "time depends on the step",
                    .choices = {"until_stable", "once_per_step"}},
                   {.key = "tolerance", .default_yaml = "1e-8", .range = positive,
                    .description = "equilibrium when the force residual on the free dofs is at most this fraction of the "
                                   "largest of the support reactions, the applied body force, the step's initial "
                                   "residual and the largest reaction or body force of the equilibria before "
                                   "(Euclidean norms of f V)"}};
  keys.push_back({.key = "max_iterations", .type = ValueType::integer, .default_yaml = max_iterations_default,
                  .range = at_least_one, .description = max_iterations_description});
  return keys;
}

TimeIntegrator::Schedule QuasiStatic::schedule(const SolverSpec& solver, double /*stable_time_step*/) {
  Schedule s;
  s.steps = solver.parameters.integer("load_steps");
  s.time_step = solver.parameters.number("end_time") / static_cast<double>(s.steps);
  return s;
}

QuasiStatic::QuasiStatic(Simulation& sim)
    : sim_(sim),
      ramp_(sim.problem().solver.parameters.boolean("ramp")),
      tolerance_(sim.problem().solver.parameters.number("tolerance")),
      max_iterations_(sim.problem().solver.parameters.integer("max_iterations")),
      stepped_loads_(sim.problem().solver.parameters.text("load_history") == "steps"),
      break_once_per_step_(sim.problem().solver.parameters.text("breaking") == "once_per_step"),
      creep_substeps_(static_cast<int>(sim.problem().solver.parameters.integer("creep_substeps"))) {}

void QuasiStatic::check_static(const Problem& p, DeckContext& ctx, std::string_view type) {
  if (const Parameters::Entry* substeps = p.solver.parameters.find("creep_substeps");
      substeps && substeps->number > 1 && p.solver.parameters.text("load_history") != "steps")
    ctx.error(substeps->pos, "solver.creep_substeps",
              "creep substeps follow a load jump, which only load_history: steps has; remove creep_substeps or "
              "give load_history: steps");
  for (const InitialConditionSpec& ic : p.initial_conditions)
    if (ic.kind == InitialConditionSpec::Kind::velocity)
      ctx.error(ic.pos, "initial_conditions",
                fmt::format("an initial velocity has no meaning for solver type '{}' (static equilibrium); remove "
                            "it or use the explicit solver",
                            type));
  for (const BoundaryConditionSpec& bc : p.boundary_conditions)
    if (bc.kind == BoundaryConditionSpec::Kind::velocity)
      ctx.error(bc.pos, "boundary_conditions",
                fmt::format("a prescribed velocity has no meaning for solver type '{}' (static equilibrium); "
                            "prescribe the displacement instead",
                            type));
  for (const RigidWallSpec& w : p.rigid_walls)
    if (w.speed != 0)
      ctx.error(w.pos, "rigid_walls." + w.name, fmt::format("a moving wall is not supported with solver type '{}'; give it speed 0", type));
  for (const RigidBodySpec& b : p.rigid_bodies)
    if (b.motion != RigidMotionKind::fixed)
      ctx.error(b.pos, "rigid_bodies." + b.name,
                fmt::format("a moving or free rigid body is not supported with solver type '{}'; remove its "
                            "displacement or mass (a fixed body)",
                            type));
}

void QuasiStatic::set_loads(double t, double factor) {
  State& state = sim_.state();
  Loads& loads = sim_.loads();
  loads.apply_displacement_conditions(t, factor, state.u);
  sim_.exchange_ghosts(state.u);
  if (loads.has_body_force()) {
    loads.evaluate_body_force(t, body_force_);
    const double* b = body_force_.data();
    double* out = state.body_force.data();
    for (std::size_t k = 0; k < 3 * state.u.size(); ++k) out[k] = factor * b[k];
  }
}

bool QuasiStatic::set_loads_and_compare(double t, double factor) {
  State& state = sim_.state();
  const VectorField u_before = state.u, body_before = state.body_force;
  set_loads(t, factor);
  const auto& kind = sim_.loads().dof_kinds();
  bool changed = false;
  for (std::size_t k = 0; k < 3 * sim_.num_owned() && !changed; ++k)
    changed = (kind[k] != DofKind::free && state.u.data()[k] != u_before.data()[k]) ||
              (sim_.loads().has_body_force() && state.body_force.data()[k] != body_before.data()[k]);
  return sim_.communicator().any(changed);
}

void QuasiStatic::creep(double t, double dt) {
  if (!loads_jumped_ || creep_substeps_ == 1) {
    solve_and_commit(dt);
    return;
  }
  State& state = sim_.state();
  const double start = t - dt, first = dt / (std::ldexp(1.0, creep_substeps_) - 1);
  double elapsed = 0;
  for (int s = 0; s < creep_substeps_; ++s) {
    const double h = s + 1 == creep_substeps_ ? dt - elapsed : std::ldexp(first, s);
    elapsed += h;
    state.time = s + 1 == creep_substeps_ ? t : start + elapsed;  // temperatures are those of the substep's end
    solve_and_commit(h);
  }
}

namespace {

/// What unsupported_fragment sums over a fragment's points, as doubles so that ranks can gather it.
struct FragmentSum {
  double label = 0, points = 0;
  double supported[3] = {0, 0, 0};  ///< 1 where some point has a prescribed dof or a contact force along that axis
  double force[3] = {0, 0, 0};      ///< Σ b V
  double magnitude = 0;             ///< Σ |b V|: a balanced load's net force is round-off of this
  double named_here = 0, x[3] = {0, 0, 0};  ///< the point that names it (label = its input id), when counted here
  static constexpr std::size_t fields = 13;

  void append_to(std::vector<double>& flat) const {
    flat.insert(flat.end(), {label, points, supported[0], supported[1], supported[2], force[0], force[1], force[2],
                             magnitude, named_here, x[0], x[1], x[2]});
  }
  /// Adds another rank's sums of the same fragment (f: fields doubles written by append_to).
  void merge(const double* f) {
    label = f[0];
    points += f[1];
    for (int d = 0; d < 3; ++d) supported[d] = std::max(supported[d], f[2 + d]), force[d] += f[5 + d];
    magnitude += f[8];
    if (f[9] != 0) named_here = 1, x[0] = f[10], x[1] = f[11], x[2] = f[12];
  }
};

}  // namespace

std::string QuasiStatic::unsupported_fragment() {
  sim_.relabel_fragments();
  const State& state = sim_.state();
  const Discretization& disc = sim_.discretization();
  const auto& kind = sim_.loads().dof_kinds();
  const bool body = sim_.loads().has_body_force(), contact = sim_.has_contact();
  std::map<double, FragmentSum> local;
  for (std::size_t i = 0; i < sim_.num_owned(); ++i) {
    FragmentSum& f = local[state.fragment[i]];
    f.label = state.fragment[i];
    f.points += 1;
    for (int d = 0; d < 3; ++d) {
      const std::size_t k = 3 * i + static_cast<std::size_t>(d);
      if (kind[k] != DofKind::free || (contact && sim_.contact_force().data()[k] != 0)) f.supported[d] = 1;
      if (!body) continue;
      f.force[d] += state.body_force.data()[k] * disc.volume[i];
      f.magnitude += std::abs(state.body_force.data()[k]) * disc.volume[i];
    }
    if (static_cast<double>(disc.id_of(i)) == f.label) {
      const Vec3 x = disc.x.get(i);
      f.named_here = 1, f.x[0] = x.x, f.x[1] = x.y, f.x[2] = x.z;
    }
  }
  std::vector<double> flat;
  for (const auto& entry : local) entry.second.append_to(flat);
  const std::vector<double> all = sim_.communicator().all_gather(flat);
  std::map<double, FragmentSum> merged;  // in label order, whatever the ranks
  for (std::size_t at = 0; at + FragmentSum::fields <= all.size(); at += FragmentSum::fields)
    merged[all[at]].merge(&all[at]);
  double total = 0;
  for (const auto& entry : merged) total += entry.second.magnitude;
  const FragmentSum* worst = nullptr;
  double worst_force = 0;
  std::size_t unsupported = 0;
  for (const auto& [label, f] : merged) {
    double free_force = 0;  // the net force along the axes it has no support on
    for (int d = 0; d < 3; ++d)
      if (f.supported[d] == 0) free_force = std::hypot(free_force, f.force[d]);
    if (!(free_force > 1e-9 * total)) continue;
    ++unsupported;
    if (free_force > worst_force) worst_force = free_force, worst = &f;
  }
  if (worst == nullptr) return {};
  return fmt::format(
      "the body has come apart: {} fragment{} without support carr{} a net load, the largest {:.3g} N on {} points "
      "(fragment of point {} at ({:g}, {:g}, {:g}) m), so no equilibrium exists",
      unsupported, unsupported == 1 ? "" : "s", unsupported == 1 ? "ies" : "y", worst_force,
      static_cast<std::uint64_t>(worst->points), static_cast<std::uint64_t>(worst->label), worst->x[0], worst->x[1],
      worst->x[2]);
}

namespace {

/// The eigenvalues (ascending) and unit eigenvectors (columns of v, row-major) of a symmetric n × n matrix a,
/// n ≤ 6, by cyclic Jacobi rotations.
void symmetric_eigen(int n, double a[6][6], double values[6], double v[6][6]) {
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) v[r][c] = r == c ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 50; ++sweep) {
    double off = 0, scale = 0;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) (r == c ? scale : off) += a[r][c] * a[r][c];
    if (off <= 1e-30 * scale) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        if (a[p][q] == 0) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < n; ++k) {  // a ← Jᵀ a J, columns then rows
          const double kp = a[k][p], kq = a[k][q];
          a[k][p] = c * kp - s * kq, a[k][q] = s * kp + c * kq;
        }
        for (int k = 0; k < n; ++k) {
          const double pk = a[p][k], qk = a[q][k];
          a[p][k] = c * pk - s * qk, a[q][k] = s * pk + c * qk;
        }
        for (int k = 0; k < n; ++k) {
          const double kp = v[k][p], kq = v[k][q];
          v[k][p] = c * kp - s * kq, v[k][q] = s * kp + c * kq;
        }
      }
  }
  for (int k = 0; k < n; ++k) values[k] = a[k][k];
}

}  // namespace

std::string QuasiStatic::free_rigid_motion() {
  sim_.relabel_fragments();
  const State& state = sim_.state();
  const Discretization& disc = sim_.discretization();
  const Communicator& comm = sim_.communicator();
  const auto& kind = sim_.loads().dof_kinds();
  const bool contact = sim_.has_contact();
  const std::size_t owned = sim_.num_owned();
  const int dimension = sim_.problem().dimension;
  // The rigid motions of the deck's dimension: translations along its axes, rotations about the axes
  // perpendicular to its plane (2D: about z; 1D: none), measured from the centre of the bodies' box, per its size.
  const int modes = dimension == 3 ? 6 : dimension == 2 ? 3 : 1;
  const BoundingBox mine = bounding_box(disc.x.data(), 3, owned);
  double low[3], high[3];
  for (int d = 0; d < 3; ++d) low[d] = comm.min(mine.lo[d]), high[d] = comm.max(mine.hi[d]);
  if (!(high[0] >= low[0])) return {};
  double centre[3], size = 0;
  for (int d = 0; d < 3; ++d) centre[d] = 0.5 * (low[d] + high[d]), size = std::max(size, high[d] - low[d]);
  if (size <= 0) size = 1;
  // Per fragment: label, points, the named point's place, and G = Σ φ φᵀ over its supported dofs (prescribed,
  // or pressed by contact), φ the rigid motions' values at the dof. A motion G does not resist is free.
  const std::size_t fields = 6 + 36;
  std::map<double, std::vector<double>> local;
  for (std::size_t i = 0; i < owned; ++i) {
    std::vector<double>& f = local[state.fragment[i]];
    if (f.empty()) f.assign(fields, 0.0), f[0] = state.fragment[i];
    f[1] += 1;
    const Vec3 x = disc.x.get(i);
    if (static_cast<double>(disc.id_of(i)) == f[0]) f[2] = 1, f[3] = x.x, f[4] = x.y, f[5] = x.z;
    const double r[3] = {(x.x - centre[0]) / size, (x.y - centre[1]) / size, (x.z - centre[2]) / size};
    for (int d = 0; d < dimension; ++d) {
      const std::size_t k = 3 * i + static_cast<std::size_t>(d);
      if (kind[k] == DofKind::free && !(contact && sim_.contact_force().data()[k] != 0)) continue;
      double phi[6] = {0, 0, 0, 0, 0, 0};
      phi[d] = 1;  // translation along d; rotation about axis a moves component d by (e_a × r)_d
      if (dimension == 1) {
        // the translation alone
      } else if (dimension == 3) {
        for (int axis = 0; axis < 3; ++axis) {
          const int next = (axis + 1) % 3, last = (axis + 2) % 3;
          phi[3 + axis] = d == next ? -r[last] : d == last ? r[next] : 0.0;
        }
      } else {
        phi[2] = d == 0 ? -r[1] : r[0];
      }
      for (int m = 0; m < modes; ++m)
        for (int n = 0; n < modes; ++n) f[6 + 6 * m + n] += phi[m] * phi[n];
    }
  }
  std::vector<double> flat;
  for (const auto& entry : local) flat.insert(flat.end(), entry.second.begin(), entry.second.end());
  const std::vector<double> all = comm.all_gather(flat);
  std::map<double, std::vector<double>> merged;  // in label order, whatever the ranks
  for (std::size_t at = 0; at + fields <= all.size(); at += fields) {
    std::vector<double>& f = merged[all[at]];
    if (f.empty()) f.assign(fields, 0.0), f[0] = all[at];
    f[1] += all[at + 1];
    if (all[at + 2] != 0) f[2] = 1, f[3] = all[at + 3], f[4] = all[at + 4], f[5] = all[at + 5];
    for (std::size_t k = 6; k < fields; ++k) f[k] += all[at + k];
  }
  static constexpr const char* axes = "xyz";
  std::size_t free_fragments = 0;
  std::string first;
  for (const auto& [label, f] : merged) {
    if (f[1] < 2) continue;  // a point without intact bonds has no stiffness: both solvers hold it where it is
    double g[6][6], values[6], vectors[6][6], largest = 0;
    for (int m = 0; m < modes; ++m)
      for (int n = 0; n < modes; ++n) g[m][n] = f[6 + 6 * m + n], largest = std::max(largest, g[m][n]);
    std::vector<std::string> motions;
    if (largest == 0) {
      motions.push_back(dimension == 1 ? "translate along x (no support at all)" : "translate and rotate (no support at all)");
    } else {
      for (int m = 0; m < modes; ++m)
        for (int n = 0; n < modes; ++n) g[m][n] /= largest;
      symmetric_eigen(modes, g, values, vectors);
      for (int k = 0; k < modes; ++k) {
        if (values[k] > 1e-9) continue;
        int dominant = 0;  // the rigid motion that weighs most in the free one names it
        for (int m = 1; m < modes; ++m)
          if (std::abs(vectors[m][k]) > std::abs(vectors[dominant][k])) dominant = m;
        if (dominant < dimension)
          motions.push_back(fmt::format("translate along {}", axes[dominant]));
        else
          motions.push_back(fmt::format("rotate about an axis along {}", dimension == 3 ? axes[dominant - 3] : 'z'));
      }
    }
    if (motions.empty()) continue;
    if (free_fragments++ > 0) continue;
    std::string list;
    for (std::size_t k = 0; k < motions.size(); ++k)
      list += (k == 0 ? "" : k + 1 == motions.size() ? " and " : ", ") + motions[k];
    first = fmt::format("{} points (fragment of point {} at ({:g}, {:g}, {:g}) m) are free to {}",
                        static_cast<std::uint64_t>(f[1]), static_cast<std::uint64_t>(label), f[3], f[4], f[5], list);
  }
  if (free_fragments == 0) return {};
  return fmt::format("the supports do not hold every rigid motion, so the tangent is singular: {}{}; prescribe "
                     "displacements that hold them",
                     first, free_fragments > 1 ? fmt::format(" ({} such fragments)", free_fragments) : "");
}

void QuasiStatic::initialize() {
  sim_.apply_initial_state();
  State& state = sim_.state();
  set_loads(0.0, ramp_ ? 0.0 : 1.0);
  std::fill(state.v.data(), state.v.data() + 3 * state.v.size(), 0.0);
  load_factor_ = ramp_ ? 0.0 : 1.0;
  committed_u_ = state.u;
  accepted_body_force_ = VectorField(state.body_force.size());  // nothing acted before t = 0
  if (stepped_loads_) {  // the loads of t = 0 act at once: the instantaneous equilibrium
    iterations_ = 0;
    begin_load_step();
    broken_ = 0;
    solve_and_commit(0.0);
    loads_jumped_ = true;  // from nothing before t = 0
    return;
  }
  std::string failure;
  try {
    sim_.evaluate(0.0, true);
  } catch (const NumericalError& e) {
    failure = e.what();
  }
  sim_.commit(0.0);
  sim_.agree_on_failure(failure);
  committed_u_ = state.u;
  accepted_body_force_ = state.body_force;
}

void QuasiStatic::evaluate_residual_force(std::vector<double>& F) {
  State& state = sim_.state();
  const std::size_t dofs = 3 * sim_.num_owned();
  if (sim_.has_correspondence()) set_step_velocity();  // the rate the stress update integrates
  std::string failure;
  try {
    sim_.evaluate(solve_dt_, false);
  } catch (const NumericalError& e) {
    failure = e.what();
  }
  sim_.agree_on_failure(failure);
  const auto& kind = sim_.loads().dof_kinds();
  const double* f = state.force.data();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < dofs; ++k) F[k] = kind[k] == DofKind::free ? f[k] + applied_force(k) : 0.0;
}

double QuasiStatic::applied_force(std::size_t k) const {
  const double b = sim_.loads().has_body_force() ? sim_.state().body_force.data()[k] : 0.0;
  return sim_.has_contact() ? b + sim_.contact_force().data()[k] : b;
}

void QuasiStatic::set_step_velocity() {
  State& state = sim_.state();
  const double dt = solve_dt_;
  double* v = state.v.data();
  const double* u = state.u.data();
  const double* u0 = committed_u_.data();
  for (std::size_t k = 0; k < 3 * sim_.num_owned(); ++k) v[k] = dt > 0 ? (u[k] - u0[k]) / dt : 0.0;
  sim_.exchange_ghosts(state.v);
}

template <class Value>
double QuasiStatic::weighted_norm(Value&& value) const {
  const double* volume = sim_.discretization().volume.data();
  const double sum = reproducible_sum(sim_.communicator(), 3 * sim_.num_owned(), [&](std::size_t k) {
    const double f = value(k) * volume[k / 3];
    return f * f;
  });
  return std::sqrt(sum);
}

double QuasiStatic::norm(const std::vector<double>& w) const {
  return weighted_norm([&](std::size_t k) { return w[k]; });
}

QuasiStatic::Residual QuasiStatic::relative_residual(const std::vector<double>& F, double start_norm) const {
  const auto& kind = sim_.loads().dof_kinds();
  const double* f = sim_.state().force.data();
  const double reaction = weighted_norm([&](std::size_t k) { return kind[k] == DofKind::free ? 0.0 : f[k]; });
  const double applied = weighted_norm([&](std::size_t k) { return kind[k] == DofKind::free ? applied_force(k) : 0.0; });
  // The loads of earlier steps count too: once they are removed (recovery under no load) the body's remaining
  // forces cancel to a small residual that the round-off of its internal forces, of the scale of those loads,
  // keeps from going lower.
  const double reference = std::max({reaction, applied, start_norm, load_scale_});
  const double residual = norm(F);
  const double load = std::max(reaction, applied);
  if (!std::isfinite(residual) || !std::isfinite(reaction) || !std::isfinite(applied))
    return {std::numeric_limits<double>::quiet_NaN(), load};  // a blow-up anywhere, prescribed dofs included
  return {reference > 0 ? residual / reference : 0.0, load};
}

void QuasiStatic::advance() {
  State& state = sim_.state();
  PERIDOT_REQUIRE(committed_u_.size() == state.u.size(), "Simulation::initialize() must run before the first step");
  const double dt = sim_.time_step();
  const std::int64_t k = state.step + 1;
  const double t = static_cast<double>(k) * dt;
  const double factor = ramp_ ? static_cast<double>(k) / static_cast<double>(sim_.total_steps()) : 1.0;
  state.time = t;
  iterations_ = 0;
  begin_load_step();
  broken_ = 0;
  if (stepped_loads_) {
    creep(t, dt);  // under the loads of t_{k−1}, still in place
    load_factor_ = factor;
    if (creep_substeps_ > 1) {
      loads_jumped_ = set_loads_and_compare(t, factor);
    } else {
      set_loads(t, factor);
    }
    solve_and_commit(0.0);
  } else {
    load_factor_ = factor;
    set_loads(t, factor);
    solve_and_commit(dt);
  }
  state.step = k;
}

void QuasiStatic::solve_and_commit(double dt) {
  State& state = sim_.state();
  const Discretization& disc = sim_.discretization();
  const std::size_t owned = sim_.num_owned();
  const auto& kind = sim_.loads().dof_kinds();
  // The forces of the last accepted state, for the external work (trapezoidal over the change).
  const VectorField force_before = state.force;
  const VectorField& body_before = accepted_body_force_;  // set_loads may have changed state.body_force
  const VectorField contact_before = sim_.has_contact() ? sim_.contact_force() : VectorField();
  solve_dt_ = dt;
  // Solve; break what is over-stretched at equilibrium; solve again until nothing breaks, or, breaking once
  // per step, once.
  for (;;) {
    equilibrate();
    const std::uint64_t broken = sim_.break_bonds();
    broken_ += broken;
    if (broken == 0) break;
    // A piece cut loose under load has no equilibrium: say so now rather than after max_iterations.
    if (const std::string apart = unsupported_fragment(); !apart.empty())
      throw NumericalError(fmt::format("load step {} (time {:.6g} s): {} bonds broke and {}",
                                       state.step + 1, state.time, broken, apart));
    if (break_once_per_step_) {
      equilibrate();
      break;
    }
  }
  set_step_velocity();
  sim_.commit(dt);

  // External work of the change, trapezoidal: the supports' −f V on prescribed dofs, the body and contact
  // forces on free ones.
  double* work = sim_.external_work().data();
  const double* volume = disc.volume.data();
  const double* u = state.u.data();
  const double* u0 = committed_u_.data();
  const bool body = sim_.loads().has_body_force();
  const bool contact = sim_.has_contact();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < owned; ++i)
    for (std::size_t q = 3 * i; q < 3 * i + 3; ++q) {
      const double du = u[q] - u0[q];
      if (kind[q] != DofKind::free) {
        work[i] -= 0.5 * (force_before.data()[q] + state.force.data()[q]) * volume[i] * du;
      } else {
        double applied = 0;
        if (body) applied += body_before.data()[q] + state.body_force.data()[q];
        if (contact) applied += contact_before.data()[q] + sim_.contact_force().data()[q];
        work[i] += 0.5 * applied * volume[i] * du;
      }
    }
  committed_u_ = state.u;
  accepted_body_force_ = state.body_force;
}

void QuasiStatic::state_arrays(StateArrays& arrays) {
  const std::size_t owned = sim_.num_owned();
  arrays.points("load_steps.committed_u", committed_u_, owned);
  arrays.points("load_steps.accepted_body_force", accepted_body_force_, owned);
  arrays.points("load_steps.body_force", body_force_, std::min(owned, body_force_.size()));
  arrays.global("load_steps.loads_jumped", &loads_jumped_);
  arrays.global("load_steps.load_factor", &load_factor_);
  arrays.global("load_steps.residual", &residual_);
  arrays.global("load_steps.load_scale", &load_scale_);
  arrays.global("load_steps.iterations", &iterations_);
  arrays.global("load_steps.broken", &broken_);
  solver_state_arrays(arrays);
}

std::vector<std::string> QuasiStatic::history_columns() const {
  std::vector<std::string> columns = {"load_factor", "residual", "iterations", "bonds_broken"};
  for (std::string& c : solver_history_columns()) columns.push_back(std::move(c));
  return columns;
}

std::vector<double> QuasiStatic::history_values() const {
  std::vector<double> values = {load_factor_, residual_, static_cast<double>(iterations_),
                                static_cast<double>(broken_)};
  for (double v : solver_history_values()) values.push_back(v);
  return values;
}

}  // namespace peridot
