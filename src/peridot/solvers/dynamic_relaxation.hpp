#pragma once
// Adaptive dynamic relaxation (Kilic & Madenci, Theor. Appl. Fract. Mech. 53 (2010) 194; docs/algorithms.md)
// in quasi-static load steps. The static problem F(u) = 0 (F: internal plus body and wall force density
// on the free dofs) is solved as the steady state of the fictitious damped motion Λ ü + c Λ u̇ = F(u)
// with Δt = 1:
//   Λ: a diagonal fictitious density per point, density_factor × ¼ Σ_j V_j c/ξ_ij (a Gerschgorin bound
//      of the row of the stiffness, c the block's bulk-equivalent micromodulus; stiffness_bound);
//   c^n = 2 √(Σ u_i ¹K_ii u_i / Σ u_i²), ¹K_ii = −(F_i^n − F_i^{n−1}) / (Λ_i u̇_i^{n−½}) over the free
//      dofs whose u̇ ≠ 0 (the local Rayleigh quotient; c = 0 when the quotient is not positive, at most
//      1.9 so that the update below stays a contraction);
//   u̇^{½} = ½ F⁰/Λ, then u̇^{n+½} = [(2 − c) u̇^{n−½} + 2 F^n/Λ] / (2 + c), u^{n+1} = u^n + u̇^{n+½}.
// Every global sum is reproducible_sum (exact integer accumulation), so the iterates are the same bits
// on any number of threads and ranks.
// Convergence (Peridot's choice; the paper runs a fixed count): ‖F V‖ over the free dofs ≤ tolerance ×
// the largest of ‖R‖ (the supports' reaction, f V on the prescribed dofs), ‖b V‖ (the applied body force),
// the residual at the start of the equilibrium and the largest ‖R‖ or ‖b V‖ of the equilibria before. More than max_iterations ends the run with a
// NumericalError naming the load step and the residual reached.
// Load steps k = 1 … N at times t_k = k·end_time/N (end_time defaults to 1 s): prescribed displacements
// and body forces are evaluated at t_k and, with ramp (the default), scaled by the load factor k/N.
// After each equilibrium the bonds over their critical stretch break and the step is relaxed again,
// until none breaks (stable crack growth); then the step is committed over the real Δt = t_k − t_{k−1}
// (inelastic and viscous histories advance once per load step, relaxation runs inside each real step).
// The state's velocity is the load step's mean, (u_k − u_{k−1})/Δt (also what the correspondence
// stress update reads as the rate of the step); the fictitious velocity stays internal.
// With load_history: steps the loads jump at the load step times and hold between them (a creep or
// relaxation test): t = 0 is relaxed with no time passing (the instantaneous response), and step k relaxes
// first over Δt under the loads of t_{k−1} (committed over Δt), then, with no time passing, under those of
// t_k (committed over 0). The temperature field is evaluated at t_k in both.
#include <cstdint>
#include <vector>

#include "peridot/deck/solver_schema.hpp"
#include "peridot/solvers/time_integrator.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

class DynamicRelaxation final : public TimeIntegrator {
 public:
  static constexpr std::string_view name = "relaxation";
  /// Its deck keys (solver.type: relaxation) and checks (deck/solver_schema.hpp).
  static SolverInfo info();
  /// N load steps of Δt = end_time/N.
  static Schedule schedule(const SolverSpec& solver, double stable_time_step);
  /// Refuses what has no meaning for a static solution: velocities (initial, prescribed) and moving walls.
  static void check(const Problem& problem, DeckContext& context);

  explicit DynamicRelaxation(Simulation& sim);
  void initialize() override;
  void advance() override;
  std::string describe() const override;
  void state_arrays(StateArrays& arrays) override;
  std::vector<std::string> history_columns() const override;
  std::vector<double> history_values() const override;

  /// Iterations of the last load step in total (all rounds of bond breaking) and the relative residual it
  /// ended at.
  std::int64_t iterations() const { return iterations_; }
  double residual() const { return residual_; }

 private:
  /// Relaxes the current load to equilibrium from rest (no bond breaks, nothing committed); returns the
  /// iterations. Throws NumericalError past max_iterations.
  std::int64_t relax();
  /// Why no equilibrium exists, when a fragment without support along some axis carries a net applied force
  /// along it: a sentence naming the most loaded such fragment, the same on every rank; empty otherwise.
  /// Collective.
  std::string unsupported_fragment();
  /// The force on the free dofs (internal + body + wall), zero on prescribed ones; evaluates first.
  void evaluate_residual_force(std::vector<double>& F);
  /// Body plus wall force density of dof k (the load factor applied), at the last evaluation.
  double applied_force(std::size_t k) const;
  /// state().v = (u − u at the last accepted load step)/Δt, ghosts included.
  void set_step_velocity();
  /// Relative residual of F (see the header) with the supports' reaction from the current force, and the load
  /// norm, the larger of ‖R‖ and ‖b V‖.
  struct Residual {
    double relative, load;
  };
  Residual relative_residual(const std::vector<double>& F, double start_norm) const;
  /// Euclidean norm of w_k V over the owned dofs (collective, reproducible).
  double norm(const std::vector<double>& w) const;
  template <class Value>
  double weighted_norm(Value&& value) const;
  void set_loads(double t, double factor);
  /// set_loads, and whether any body force or prescribed displacement changed (on any rank).
  bool set_loads_and_compare(double t, double factor);
  /// The creep over [t − Δt, t] under the loads in place: one equilibrium, or creep_substeps of them, each twice
  /// as long as the one before, when the loads jumped at t − Δt.
  void creep(double t, double dt);
  /// Relaxes, breaks what is over-stretched, relaxes again until nothing breaks (breaking: once_per_step:
  /// once), and commits over Δt (the real time this equilibrium closes), with the external work of the change
  /// from committed_u_. Throws NumericalError when the breaking has cut a loaded piece loose.
  void solve_and_commit(double dt);

  Simulation& sim_;
  // The deck's settings (solver section).
  bool ramp_;                      ///< loads scaled by the load factor k/N
  double tolerance_;               ///< relative force residual at equilibrium
  std::int64_t max_iterations_;    ///< per equilibrium
  double density_factor_;          ///< fictitious density / the Gerschgorin bound
  bool stepped_loads_;             ///< load_history: steps
  bool break_once_per_step_;       ///< breaking: once_per_step
  int creep_substeps_;             ///< equilibria of the creep after a load jump (load_history: steps)
  bool loads_jumped_ = false;      ///< the loads changed at the last load step's time (tracked with creep substeps only)
  std::vector<double> density_;  ///< Λ per point (kg/m³ with Δt = 1)
  VectorField body_force_;       ///< the deck's body force at t_k, before the load factor
  std::vector<double> velocity_, force_, previous_force_;  ///< per owned dof
  VectorField committed_u_;      ///< u at the last accepted load step
  VectorField accepted_body_force_;  ///< the body force density of the last accepted equilibrium
  double load_factor_ = 0, residual_ = 0;
  double solve_dt_ = 0;  ///< the real Δt the equilibrium being relaxed closes (0: an instantaneous one)
  /// The largest of the reaction and applied-force norms at the equilibria so far (a floor of the residual's
  /// reference).
  double load_scale_ = 0;
  std::int64_t iterations_ = 0;
  std::uint64_t broken_ = 0;
};

}  // namespace peridot
