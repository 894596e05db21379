#pragma once
// Explicit dynamics, velocity Verlet (Silling & Askari 2005; as Peridigm integrates):
//   v^{n+½} = v^n + (Δt/2) a^n,  u^{n+1} = u^n + Δt v^{n+½},  v^{n+1} = v^{n+½} + (Δt/2) a^{n+1},
// with bond failure evaluated on u^{n+1} before the force, as Peridigm does. Inelastic models evaluate
// their return map on u^{n+1} and commit once per step. Correspondence blocks update their stress over the
// step from u^{n+1} and v^{n+1/2} (correspondence_blocks.hpp). Rigid walls add their penalty force density
// to the internal and body forces in both kicks, and their work to the external work (trapezoidal, like
// the body force). Optional mass-proportional damping (solver.damping) multiplies free velocities by
// e^{−c Δt/2} in each kick.
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "peridot/deck/solver_schema.hpp"
#include "peridot/solvers/time_integrator.hpp"

namespace peridot {

class VelocityVerlet final : public TimeIntegrator {
 public:
  static constexpr std::string_view name = "explicit";
  /// Its deck keys (solver.type: explicit, the default) (deck/solver_schema.hpp).
  static SolverInfo info();
  /// Δt = time_step or safety_factor × stable; whole steps to end_time, or num_steps.
  static Schedule schedule(const SolverSpec& solver, double stable_time_step);

  explicit VelocityVerlet(Simulation& sim);
  void initialize() override;
  void advance() override;
  std::string describe() const override;
  bool bounded_by_stable_time_step() const override { return true; }
  /// The kinetic-energy watch, for checkpoints.
  void state_arrays(StateArrays& arrays) override { arrays.global("explicit.energy_watch", &watch_); }

 private:
  /// Kinetic energy growing without a source stops the run (a blow-up caught while its displacements are still
  /// small): every energy_check_interval steps, KE = Σ ½ m v² (exact sums: the same on every rank count); the
  /// run fails when KE is more than 10 times the energy supplied (KE and strain energy at t = 0 plus the largest
  /// |external work| so far, which counts supports, body forces and contact) and higher than 8 checks before.
  /// Energy conservation bounds KE by the supplied energy (plus a drift of a percent or so), so only a blow-up
  /// gets there. Off under a temperature field, whose thermal strain supplies energy this does not count.
  static constexpr std::int64_t energy_check_interval = 32;
  struct EnergyWatch {
    double initial = 0;                ///< KE + strain energy at t = 0 (J)
    double most_work = 0;              ///< the largest |external work| at a check (J)
    std::array<double, 9> kinetic{};   ///< KE at the last checks (J), newest last
    std::int64_t checks = 0;
  };
  /// The watch's check after a step: a failure message naming the point of largest KE ("" when none, or on
  /// the ranks that do not own it). Collective.
  std::string watch_energy();
  EnergyWatch watch_;
  bool watch_energy_ = true;
  void kick(double half_dt);
  Simulation& sim_;
  double damping_;  ///< c (1/s) of solver.damping
  /// A displacement beyond this (100 times the problem's extent) is a blow-up still finite: the run stops.
  double runaway_ = 0;
};

}  // namespace peridot
