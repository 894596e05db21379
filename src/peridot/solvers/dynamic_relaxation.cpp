#include "peridot/solvers/dynamic_relaxation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "peridot/deck/map_reader.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/solvers/simulation.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

SolverInfo DynamicRelaxation::info() {
  SolverInfo info{.name = name,
          .summary = "static equilibrium in load steps",
          .description = "adaptive dynamic relaxation (Kilic & Madenci 2010) to static equilibrium in load steps; "
                         "after each equilibrium the bonds over their threshold break and the step is relaxed again "
                         "until none breaks (or once: breaking); one Exodus frame and history row per load step "
                         "(docs/algorithms.md)",
          .keys = load_step_keys("100000", "iterations allowed for one equilibrium; more ends the run with an error "
                                                     "naming the residual reached"),
          .check = &DynamicRelaxation::check};
  info.keys.push_back({.key = "density_factor", .default_yaml = "5", .range = {1, infinity, false, true},
                       .description = "fictitious density as a multiple of the Gerschgorin bound ¼ Σ V c/ξ; raise it "
                                      "if the iterations diverge"});
  return info;
}

void DynamicRelaxation::check(const Problem& problem, DeckContext& context) {
  check_static(problem, context, name);
}

namespace {
/// The damping coefficient's cap: (2 − c) must stay positive for the update to contract (a code
/// heuristic of the Madenci–Oterkus programs; the paper gives none).
constexpr double max_damping = 1.9;
}  // namespace

DynamicRelaxation::DynamicRelaxation(Simulation& sim)
    : QuasiStatic(sim), density_factor_(sim.problem().solver.parameters.number("density_factor")) {
  std::vector<double> k;
  stiffness_bound(sim_.model(), k);
  const double factor = density_factor_;
  density_.resize(sim_.num_owned());
  // Δt = 1: Λ ≥ ¼ Σ_j |K_ij|; a point without bonds gets 1 (it has no stiffness to bound).
  for (std::size_t i = 0; i < density_.size(); ++i) density_[i] = k[i] > 0 ? factor * 0.25 * k[i] : 1.0;
  const std::size_t dofs = 3 * sim_.num_owned();
  velocity_.assign(dofs, 0.0);
  force_.assign(dofs, 0.0);
  previous_force_.assign(dofs, 0.0);
}

void DynamicRelaxation::equilibrate() {
  State& state = sim_.state();
  const auto& kind = sim_.loads().dof_kinds();
  const Communicator& comm = sim_.communicator();
  const std::size_t dofs = 3 * sim_.num_owned();
  double* u = state.u.data();
  evaluate_residual_force(force_);
  const double start = norm(force_);
  for (std::int64_t iteration = 0;; ++iteration) {
    const Residual r = relative_residual(force_, start);
    residual_ = r.relative;
    if (!std::isfinite(residual_)) {
      std::string failure;
      for (std::size_t k = 0; k < dofs && failure.empty(); ++k)
        if (!std::isfinite(u[k]) || !std::isfinite(force_[k])) {
          const std::size_t i = k / 3;
          const Discretization& disc = sim_.discretization();
          const Vec3 x = disc.x.get(i);
          failure = fmt::format(
              "dynamic relaxation diverged in load step {} (time {:.6g} s) at iteration {}: non-finite {} at point {} "
              "(block '{}') at ({:g}, {:g}, {:g}) m; raise solver.density_factor",
              state.step + 1, state.time, iteration, std::isfinite(u[k]) ? "force" : "displacement", disc.input_id[i],
              disc.block_names[disc.block[i]], x.x, x.y, x.z);
        }
      if (comm.first_rank_with(!failure.empty()) < 0) failure = "dynamic relaxation diverged (non-finite residual)";
      sim_.agree_on_failure(failure);
    }
    if (residual_ <= tolerance_) {
      accept_load_scale(r.load);
      return;
    }
    if (iteration >= max_iterations_) {
      std::string apart = unsupported_fragment();
      if (apart.empty()) {
        apart = "raise solver.max_iterations, loosen solver.tolerance or use more load_steps";
        if (const std::string free = free_rigid_motion(); !free.empty()) apart += "; note that " + free;
      }
      throw NumericalError(fmt::format(
          "dynamic relaxation did not converge in load step {} (time {:.6g} s, load factor {:.6g}): relative force "
          "residual {:.3e} after {} iterations, tolerance {:.3e}; {}",
          state.step + 1, state.time, load_factor_, residual_, iteration, tolerance_,
          apart));
    }
    double c = 0;
    if (iteration > 0) {
      // Local Rayleigh quotient over the free dofs that moved (both sums reproducible).
      const double numerator = reproducible_sum(comm, dofs, [&](std::size_t k) {
        if (kind[k] != DofKind::free || velocity_[k] == 0) return 0.0;
        const double stiffness = -(force_[k] - previous_force_[k]) / (density_[k / 3] * velocity_[k]);
        return u[k] * stiffness * u[k];
      });
      const double denominator = reproducible_sum(comm, dofs, [&](std::size_t k) {
        return kind[k] == DofKind::free && velocity_[k] != 0 ? u[k] * u[k] : 0.0;
      });
      if (denominator > 0 && numerator > 0) c = std::min(max_damping, 2 * std::sqrt(numerator / denominator));
    }
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < dofs; ++k) {
      if (kind[k] != DofKind::free) continue;
      const double a = force_[k] / density_[k / 3];
      velocity_[k] = iteration == 0 ? 0.5 * a : ((2 - c) * velocity_[k] + 2 * a) / (2 + c);
      u[k] += velocity_[k];
    }
    sim_.exchange_ghosts(state.u);
    std::swap(previous_force_, force_);
    evaluate_residual_force(force_);
    ++iterations_;
  }
}

std::string DynamicRelaxation::describe() const {
  std::string out;
  out += fmt::format("solver           relaxation (adaptive dynamic relaxation, Kilic & Madenci 2010)\n");
  out += fmt::format("load steps       {} to t = {:.6g} s ({}), Δt = {:.6g} s\n", sim_.total_steps(),
                     sim_.time_step() * static_cast<double>(sim_.total_steps()),
                     ramp_ ? "loads ramped by k/N" : "loads as given at each t_k", sim_.time_step());
  out += fmt::format("equilibrium      relative force residual ≤ {:.3g}, at most {} iterations, density factor {:.3g}\n",
                     tolerance_, max_iterations_, density_factor_);
  return out;
}

void DynamicRelaxation::solver_state_arrays(StateArrays& arrays) {
  const std::size_t owned = sim_.num_owned();
  arrays.points("relaxation.velocity", velocity_, owned, 3);
  arrays.points("relaxation.force", force_, owned, 3);
  arrays.points("relaxation.previous_force", previous_force_, owned, 3);
}

}  // namespace peridot
