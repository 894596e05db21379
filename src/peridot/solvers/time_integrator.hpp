#pragma once
// The solver interface: a TimeIntegrator advances a Simulation from one accepted state to the next
// through the force evaluator (Simulation::evaluate, commit, break_bonds) and nothing else of its
// internals. Members: velocity Verlet (velocity_verlet.hpp, solver.type: explicit) and adaptive dynamic
// relaxation in load steps (dynamic_relaxation.hpp, solver.type: relaxation). A solver describes itself in
// its own file pair (`name`, `info()`: its deck keys and checks, `schedule`), and its one registration line is
// in the list of time_integrator.cpp.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "peridot/state/state_arrays.hpp"

namespace peridot {

class Simulation;

class TimeIntegrator {
 public:
  /// The steps of a run: how many, and the time each one advances.
  struct Schedule {
    double time_step = 0;
    std::int64_t steps = 0;
  };

  virtual ~TimeIntegrator() = default;
  /// The state at t = 0 (initial conditions) with its forces evaluated and committed (Δt = 0).
  virtual void initialize() = 0;
  /// One step: state().step grows by one and state().time reaches the step's time. Throws
  /// NumericalError naming step, time and point on a non-finite value (every rank alike).
  virtual void advance() = 0;
  /// Lines `peridot check` and run.log print about the solver (time step, steps, tolerances).
  virtual std::string describe() const = 0;
  /// Extra history columns of this solver and their values at the last step (empty for the explicit one).
  virtual std::vector<std::string> history_columns() const { return {}; }
  virtual std::vector<double> history_values() const { return {}; }
  /// The solver's own state between steps, for checkpoints (state/state_arrays.hpp); none by default.
  virtual void state_arrays(StateArrays&) {}
  /// Whether the stable time step bounds its Δt (explicit: a larger one is warned about).
  virtual bool bounded_by_stable_time_step() const { return false; }
};

struct SolverSpec;

/// The schedule of the deck's solver (its type's `schedule`), given the stable time step.
TimeIntegrator::Schedule time_schedule(const SolverSpec& solver, double stable_time_step);

/// The integrator the deck's solver.type names, bound to `sim` (which outlives it).
std::unique_ptr<TimeIntegrator> make_time_integrator(Simulation& sim);

}  // namespace peridot
