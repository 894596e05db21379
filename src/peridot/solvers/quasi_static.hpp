#pragma once
// Quasi-static load stepping, shared by the static solvers (adaptive dynamic relaxation,
// dynamic_relaxation.hpp; Newton–Krylov, newton_krylov.hpp), which differ only in how one equilibrium
// F(u) = 0 is found (`equilibrate`). F: internal plus body and contact force density on the free dofs.
// Convergence (Peridot's choice): ‖F V‖ over the free dofs ≤ tolerance × the largest of ‖R‖ (the supports'
// reaction, f V on the prescribed dofs), ‖b V‖ (the applied body force), the residual at the start of the
// equilibrium and the largest ‖R‖ or ‖b V‖ of the equilibria before. Every norm is a reproducible_sum.
// Load steps k = 1 … N at times t_k = k·end_time/N (end_time defaults to 1 s): prescribed displacements
// and body forces are evaluated at t_k and, with ramp (the default), scaled by the load factor k/N.
// After each equilibrium the bonds over their critical stretch break and the step is solved again,
// until none breaks (stable crack growth); then the step is committed over the real Δt = t_k − t_{k−1}
// (inelastic and viscous histories advance once per load step; the equilibria run inside each real step).
// The state's velocity is the load step's mean, (u_k − u_{k−1})/Δt (also what the correspondence
// stress update reads as the rate of the step).
// With load_history: steps the loads jump at the load step times and hold between them (a creep or
// relaxation test): t = 0 is solved with no time passing (the instantaneous response), and step k solves
// first over Δt under the loads of t_{k−1} (committed over Δt), then, with no time passing, under those of
// t_k (committed over 0). The temperature field is evaluated at t_k in both.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "peridot/deck/solver_schema.hpp"
#include "peridot/solvers/time_integrator.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

class QuasiStatic : public TimeIntegrator {
 public:
  /// The load-stepping keys every static solver has (load_steps, end_time, ramp, load_history,
  /// creep_substeps, breaking, tolerance), then max_iterations with this default and description.
  static std::vector<KeySpec> load_step_keys(std::string_view max_iterations_default,
                                             std::string_view max_iterations_description);
  /// N load steps of Δt = end_time/N.
  static Schedule schedule(const SolverSpec& solver, double stable_time_step);
  /// Refuses what has no meaning for a static solution (velocities, initial or prescribed, and moving
  /// bodies), naming solver type `type`.
  static void check_static(const Problem& problem, DeckContext& context, std::string_view type);

  void initialize() override;
  void advance() override;
  void state_arrays(StateArrays& arrays) override;
  std::vector<std::string> history_columns() const override;
  std::vector<double> history_values() const override;

  /// Iterations of the last load step in total (all rounds of bond breaking) and the relative residual it
  /// ended at.
  std::int64_t iterations() const { return iterations_; }
  double residual() const { return residual_; }

 protected:
  explicit QuasiStatic(Simulation& sim);
  /// Solves the current loads to equilibrium (no bond breaks, nothing committed), adding its iterations to
  /// iterations_ and leaving residual_ at the relative residual reached. Throws NumericalError when it
  /// cannot (naming the load step, the iteration and the residual).
  virtual void equilibrate() = 0;
  /// Called as each load step starts (the solver's per-step counters).
  virtual void begin_load_step() {}
  /// The solver's own arrays and columns beside the load stepping's.
  virtual void solver_state_arrays(StateArrays&) {}
  virtual std::vector<std::string> solver_history_columns() const { return {}; }
  virtual std::vector<double> solver_history_values() const { return {}; }

  /// The force on the free dofs (internal + body + contact), zero on prescribed ones; evaluates first.
  void evaluate_residual_force(std::vector<double>& F);
  /// Body plus contact force density of dof k (the load factor applied), at the last evaluation.
  double applied_force(std::size_t k) const;
  /// Relative residual of F (see the header) with the supports' reaction from the current force, and the load
  /// norm, the larger of ‖R‖ and ‖b V‖.
  struct Residual {
    double relative, load;
  };
  Residual relative_residual(const std::vector<double>& F, double start_norm) const;
  /// Notes an equilibrium reached with this load norm (the floor of later residuals' reference).
  void accept_load_scale(double load) { load_scale_ = std::max(load_scale_, load); }
  /// Euclidean norm of w_k V over the owned dofs (collective, reproducible).
  double norm(const std::vector<double>& w) const;
  /// Why no equilibrium exists, when a fragment without support along some axis carries a net applied force
  /// along it: a sentence naming the most loaded such fragment, the same on every rank; empty otherwise.
  /// Collective.
  std::string unsupported_fragment();
  /// When a fragment's supports (prescribed dofs, contact) leave a rigid motion of the deck's dimension free, so
  /// that the tangent is singular: a sentence naming the first such fragment and its free motions, the same on
  /// every rank; empty otherwise. Collective.
  std::string free_rigid_motion();
  /// state().v = (u − u at the last accepted load step)/Δt, ghosts included.
  void set_step_velocity();

  Simulation& sim_;
  bool ramp_;                      ///< loads scaled by the load factor k/N
  double tolerance_;               ///< relative force residual at equilibrium
  std::int64_t max_iterations_;    ///< per equilibrium
  double load_factor_ = 0, residual_ = 0;
  std::int64_t iterations_ = 0;
  double solve_dt_ = 0;  ///< the real Δt the equilibrium being solved closes (0: an instantaneous one)

 private:
  template <class Value>
  double weighted_norm(Value&& value) const;
  void set_loads(double t, double factor);
  /// set_loads, and whether any body force or prescribed displacement changed (on any rank).
  bool set_loads_and_compare(double t, double factor);
  /// The creep over [t − Δt, t] under the loads in place: one equilibrium, or creep_substeps of them, each twice
  /// as long as the one before, when the loads jumped at t − Δt.
  void creep(double t, double dt);
  /// Solves, breaks what is over-stretched, solves again until nothing breaks (breaking: once_per_step:
  /// once), and commits over Δt (the real time this equilibrium closes), with the external work of the change
  /// from committed_u_. Throws NumericalError when the breaking has cut a loaded piece loose.
  void solve_and_commit(double dt);

  bool stepped_loads_;             ///< load_history: steps
  bool break_once_per_step_;       ///< breaking: once_per_step
  int creep_substeps_;             ///< equilibria of the creep after a load jump (load_history: steps)
  bool loads_jumped_ = false;      ///< the loads changed at the last load step's time (tracked with creep substeps only)
  VectorField body_force_;       ///< the deck's body force at t_k, before the load factor
  VectorField committed_u_;      ///< u at the last accepted load step
  VectorField accepted_body_force_;  ///< the body force density of the last accepted equilibrium
  /// The largest of the reaction and applied-force norms at the equilibria so far (a floor of the residual's
  /// reference).
  double load_scale_ = 0;
  std::uint64_t broken_ = 0;
};

}  // namespace peridot
