#include "peridot/solvers/time_integrator.hpp"

#include "peridot/core/error.hpp"
#include "peridot/solvers/dynamic_relaxation.hpp"
#include "peridot/solvers/newton_krylov.hpp"
#include "peridot/solvers/simulation.hpp"
#include "peridot/solvers/velocity_verlet.hpp"

namespace peridot {

namespace {

template <class... Solvers>
struct SolverList {
  static std::vector<SolverInfo> infos() { return {Solvers::info()...}; }
  /// Runs f(Solver*) (a null pointer of the type) for the solver named `name`; false when none is.
  template <class F>
  static bool with(std::string_view name, F&& f) {
    return ((Solvers::name == name ? (f(static_cast<Solvers*>(nullptr)), true) : false) || ...);
  }
};

// The registration list: one line per solver; the first is the default type.
// clang-format off
using Solvers = SolverList<
    VelocityVerlet,
    DynamicRelaxation,
    NewtonKrylov>;
// clang-format on

}  // namespace

// The catalogue the deck reads (declared in deck/solver_schema.hpp).
const std::vector<SolverInfo>& solver_types() {
  static const std::vector<SolverInfo> all = Solvers::infos();
  return all;
}

TimeIntegrator::Schedule time_schedule(const SolverSpec& solver, double stable_time_step) {
  TimeIntegrator::Schedule schedule;
  const bool found = Solvers::with(solver.type, [&](auto* type) {
    schedule = std::remove_pointer_t<decltype(type)>::schedule(solver, stable_time_step);
  });
  PERIDOT_REQUIRE(found, "no solver of type '" + solver.type + "'");
  return schedule;
}

std::unique_ptr<TimeIntegrator> make_time_integrator(Simulation& sim) {
  std::unique_ptr<TimeIntegrator> integrator;
  const std::string& type = sim.problem().solver.type;
  Solvers::with(type, [&](auto* kind) { integrator = std::make_unique<std::remove_pointer_t<decltype(kind)>>(sim); });
  PERIDOT_REQUIRE(integrator != nullptr, "no solver of type '" + type + "'");
  return integrator;
}

}  // namespace peridot
