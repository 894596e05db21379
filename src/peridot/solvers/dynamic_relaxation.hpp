#pragma once
// Adaptive dynamic relaxation (Kilic & Madenci, Theor. Appl. Fract. Mech. 53 (2010) 194; docs/algorithms.md)
// in quasi-static load steps (quasi_static.hpp: the load stepping, the residual, bond breaking, commits).
// The static problem F(u) = 0 is solved as the steady state of the fictitious damped motion
// Λ ü + c Λ u̇ = F(u) with Δt = 1:
//   Λ: a diagonal fictitious density per point, density_factor × ¼ Σ_j V_j c/ξ_ij (a Gerschgorin bound
//      of the row of the stiffness, c the block's bulk-equivalent micromodulus; stiffness_bound);
//   c^n = 2 √(Σ u_i ¹K_ii u_i / Σ u_i²), ¹K_ii = −(F_i^n − F_i^{n−1}) / (Λ_i u̇_i^{n−½}) over the free
//      dofs whose u̇ ≠ 0 (the local Rayleigh quotient; c = 0 when the quotient is not positive, at most
//      1.9 so that the update below stays a contraction);
//   u̇^{½} = ½ F⁰/Λ, then u̇^{n+½} = [(2 − c) u̇^{n−½} + 2 F^n/Λ] / (2 + c), u^{n+1} = u^n + u̇^{n+½}.
// Every global sum is reproducible_sum (exact integer accumulation), so the iterates are the same bits
// on any number of threads and ranks. The paper runs a fixed count; here the iterations stop at the
// residual of quasi_static.hpp, and more than max_iterations ends the run with a NumericalError naming the
// load step and the residual reached. Each equilibrium restarts the damped motion from rest; the
// fictitious velocity stays internal.
#include <cstdint>
#include <vector>

#include "peridot/solvers/quasi_static.hpp"

namespace peridot {

class DynamicRelaxation final : public QuasiStatic {
 public:
  static constexpr std::string_view name = "relaxation";
  /// Its deck keys (solver.type: relaxation) and checks (deck/solver_schema.hpp).
  static SolverInfo info();
  /// Refuses what has no meaning for a static solution: velocities (initial, prescribed) and moving walls.
  static void check(const Problem& problem, DeckContext& context);

  explicit DynamicRelaxation(Simulation& sim);
  std::string describe() const override;

 private:
  void equilibrate() override;
  void solver_state_arrays(StateArrays& arrays) override;

  double density_factor_;          ///< fictitious density / the Gerschgorin bound
  std::vector<double> density_;  ///< Λ per point (kg/m³ with Δt = 1)
  std::vector<double> velocity_, force_, previous_force_;  ///< per owned dof
};

}  // namespace peridot
