#include "peridot/solvers/time_integrator.hpp"

#include "peridot/solvers/dynamic_relaxation.hpp"
#include "peridot/solvers/simulation.hpp"
#include "peridot/solvers/velocity_verlet.hpp"

namespace peridot {

std::unique_ptr<TimeIntegrator> make_time_integrator(Simulation& sim) {
  switch (sim.problem().solver.kind) {
    case SolverKind::relaxation: return std::make_unique<DynamicRelaxation>(sim);
    case SolverKind::explicit_dynamics: break;
  }
  return std::make_unique<VelocityVerlet>(sim);
}

}  // namespace peridot
