#pragma once
// The implicit static solver (solver.type: implicit): each equilibrium of the quasi-static load steps
// (quasi_static.hpp: loads, residual, bond breaking, commits) by Newton's method with a line search, through
// PETSc (SNES for the nonlinear solve, KSP for the linear one; docs/algorithms.md "Newton–Krylov").
//   Unknowns: the in-plane displacement components (the deck's dimension) of every owned point with a free
//   dof, laid out on Peridot's own partition (rank r owns the rows of its points, in its local order); fully
//   prescribed points are not unknowns. Residual R = −(f + b + contact) V on the free dofs (N); on a
//   prescribed component of a point that has a free one, R = d (x − ū) with d the point's diagonal stiffness,
//   so that the Newton update keeps it where the loads put it.
//   Jacobian: matrix_free (J v = [R(u + h v) − R(u)]/h, h = √ε · max(Δx_min, ‖u‖∞)/‖v‖∞: every model, its
//   inelastic return map included, since R is the trial state of the step), bond_tangent, the assembled
//   tangent K (below) itself (exact for pmb; a modified Newton method for the other models), exact (pmb and
//   lps: the sum of every family's exact part, solvers/family_tangent.hpp, on a 2δ stencil for lps) or
//   finite_difference (any model: the same 2δ stencil by PETSc's colored finite differences of R). The last
//   two are their own preconditioner's matrix.
//   Preconditioner: K, the bond springs V_i V_j c G/ξ (internal_force.hpp bond_stiffness) along each intact
//   bond's deformed direction, plus for pmb the geometric stiffness k (e/|y|)(I − n⊗n) of its turning force;
//   blocks of the deck's dimension in a PETSc AIJ matrix of that block size (GAMG's near-null space its
//   translations); algebraic multigrid (gamg), ILU (block Jacobi with ILU per rank when distributed), Jacobi
//   or none.
// Convergence is quasi_static.hpp's relative residual (reproducible sums), tested by SNES at each Newton
// iterate. Bitwise: the residual evaluations are the same bits for any thread count, and PETSc runs one
// thread per rank, so a deck gives the same bits on any number of threads; across rank counts the Krylov
// reductions and the preconditioner (ILU blocks, GAMG's aggregates) follow the partition, so the answers
// agree to the solver's tolerances, not bitwise.
#include <cstdint>
#include <exception>
#include <memory>
#include <vector>

#include "peridot/solvers/quasi_static.hpp"

struct _p_Vec;  // PETSc's Vec
struct _p_Mat;  // PETSc's Mat

namespace peridot {

class NewtonKrylov final : public QuasiStatic {
 public:
  static constexpr std::string_view name = "implicit";
  /// Its deck keys (solver.type: implicit) and checks (deck/solver_schema.hpp).
  static SolverInfo info();
  static void check(const Problem& problem, DeckContext& context);

  explicit NewtonKrylov(Simulation& sim);
  ~NewtonKrylov() override;
  std::string describe() const override;

  /// The relative residual at each Newton iterate of the last equilibrium (the first: its start).
  const std::vector<double>& newton_residuals() const { return newton_residuals_; }
  /// Krylov iterations of the last load step in total.
  std::int64_t linear_iterations() const { return linear_iterations_; }
  /// jacobian: finite_difference: the colors of the last equilibrium (residuals per Jacobian).
  std::int64_t colors() const { return colors_; }

  struct Petsc;  // the PETSc objects (newton_krylov.cpp)

 private:
  void equilibrate() override;
  void begin_load_step() override;
  /// Starts PETSc (once per process) and builds the vectors, the matrices and the SNES (afresh for every
  /// equilibrium, so that none depends on those before it: restarts give the same bits).
  void setup();
  std::vector<std::string> solver_history_columns() const override { return {"linear_iterations"}; }
  std::vector<double> solver_history_values() const override {
    return {static_cast<double>(linear_iterations_)};
  }

 public:  // called from PETSc's callbacks (newton_krylov.cpp)
  /// R(x) into r (PETSc arrays of the owned dofs); with record, its relative residual becomes the iterate's.
  void evaluate_residual(const double* x, double* r, bool record);
  /// The Jacobian at x: the base point of the matrix-free one (K assembled at the first iterate of the
  /// equilibrium only), or the assembled Jacobian at x.
  void assemble(_p_Vec* x);
  /// The iterate's relative residual and whether it is finite (the last recorded residual()).
  double recorded_residual() const { return recorded_; }
  /// SNES's convergence test at each Newton iterate: sets reason (a SNESConvergedReason; still iterating or why
  /// it stops).
  void converged_or_stop(std::int64_t iteration, int& reason);
  /// y = J v by the finite difference of the residual from the base point of the last assemble.
  void multiply(_p_Vec* v, _p_Vec* y);
  std::exception_ptr error;  ///< an exception thrown inside a callback, rethrown after the solve

 private:
  /// Copies x into u (free, active dofs) and refreshes the ghosts.
  void set_displacement(const double* x);
  /// K at the current u into the preconditioner matrix.
  void assemble_bond_tangent();
  /// Per point, owned and ghost, 1 for each component that is an unknown of the system, 0 for the others.
  VectorField unknown_components() const;
  /// For every point, owned or ghost, the owned families it belongs to (Petsc::member_*).
  void find_family_members();
  /// Every pair of every owned family (the 2δ stencil of the assembled Jacobians) into `graph`, a matrix over the
  /// unknown points, with zeros: one row per point that a family reaches.
  void add_family_stencil(_p_Mat* graph);
  /// Adds every owned family's exact tangent blocks to `target` (ADD_VALUES), the unknowns' rows and columns
  /// only.
  void add_family_blocks(_p_Mat* target);
  bool active(std::size_t k) const;
  /// f(row, k, i) for every unknown of the system: its row in PETSc's local arrays, k = 3i + component in
  /// Peridot's, i the point.
  template <class F>
  void for_each_unknown(F&& f) const {
    const auto w = static_cast<std::size_t>(width_);
    for (std::size_t m = 0; m < unknown_points_.size(); ++m)
      for (std::size_t c = 0; c < w; ++c) f(w * m + c, 3 * std::size_t{unknown_points_[m]} + c, std::size_t{unknown_points_[m]});
  }

  enum class Jacobian { matrix_free, bond_tangent, exact, finite_difference };
  Jacobian jacobian_;
  std::string linear_solver_, preconditioner_;
  double linear_tolerance_;
  std::int64_t max_linear_iterations_;
  bool line_search_, print_iterations_;
  std::unique_ptr<Petsc> petsc_;
  std::vector<double> force_;       ///< per owned dof: the residual force density of the last evaluation
  std::vector<double> diagonal_;    ///< per owned point: d, the diagonal stiffness of K (N/m)
  std::vector<double> bond_k_;      ///< per bond: bond_stiffness
  /// The owned points with a free dof, in local order: the system's block rows, width_ (the deck's
  /// dimension) unknowns each; a fully prescribed point is not in the system.
  std::vector<std::uint32_t> unknown_points_;
  int width_ = 3;
  VectorField target_;              ///< u where the loads put it (prescribed and inactive dofs)
  std::vector<double> newton_residuals_;
  double start_norm_ = 0, recorded_ = 0, recorded_load_ = 0, length_scale_ = 0;
  bool started_ = false;
  std::int64_t linear_iterations_ = 0, colors_ = 0;
};

}  // namespace peridot
