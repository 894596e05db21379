#pragma once
// Initial conditions, prescribed displacements and velocities (per component, on node sets) and body
// force densities, all as expressions of x, y, z (and t) evaluated at the points' reference positions.
#include <cstdint>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/deck/expression.hpp"
#include "peridot/loads/node_sets.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// How a degree of freedom is driven: by the equation of motion, or prescribed by a boundary condition.
enum class DofKind : std::uint8_t { free = 0, velocity = 1, displacement = 2 };

class Loads {
 public:
  Loads(const Problem& problem, const Discretization& disc, const std::vector<NodeSet>& sets);

  /// u and v at t = 0 from the initial conditions, then the boundary conditions at t = 0.
  void apply_initial_conditions(State& state) const;

  /// Prescribed velocities at time t (the Verlet half step uses t + Δt/2).
  void apply_velocity_conditions(double t, VectorField& v) const;
  /// Prescribed displacements at time t; their velocity becomes (u(t) − u_old)/Δt.
  void apply_displacement_conditions(double t, double dt, VectorField& u, VectorField& v) const;
  /// Prescribed displacements at time t scaled by `factor` (quasi-static load steps); velocities untouched.
  void apply_displacement_conditions(double t, double factor, VectorField& u) const;
  /// Body force density at time t into b, the field of the explicit solver (evaluated once when no
  /// expression depends on t).
  void update_body_force(double t, VectorField& b);
  /// Body force density at time t into b, every call (sized to the points).
  void evaluate_body_force(double t, VectorField& b) const;

  /// Replaces the value of boundary condition k (deck order) from the next step on: a program that drives a run
  /// in pieces (the Python module) changes a load between them. Its kind, component and node set stay. Throws
  /// InputError at value.pos when the expression is malformed or not finite at some point at time t.
  void set_boundary_value(std::size_t k, const Expression& value, double t);
  std::size_t num_boundary_conditions() const { return conditions_.size(); }

  /// Per degree of freedom (3 per point): free or prescribed.
  const std::vector<DofKind>& dof_kinds() const { return dof_kind_; }
  /// The prescribed degrees of freedom (3·i + d), increasing.
  const std::vector<std::uint64_t>& prescribed_dofs() const { return prescribed_; }
  bool has_body_force() const { return !body_forces_.empty(); }

 private:
  struct Prescribed {
    DofKind kind;
    int component;
    const std::vector<std::uint32_t>* points;
    ScalarFunction value;
  };
  struct Field {
    const std::vector<std::uint32_t>* points;
    int component;
    ScalarFunction value;
    double scale = 1;  ///< a traction's 1/d
  };
  const Discretization& disc_;
  std::vector<std::uint32_t> all_points_;
  std::vector<Field> initial_displacement_, initial_velocity_;
  std::vector<Prescribed> conditions_;
  std::vector<Field> body_forces_;
  bool body_force_time_dependent_ = false;
  bool body_force_evaluated_ = false;
  std::vector<DofKind> dof_kind_;
  std::vector<std::uint64_t> prescribed_;
};

}  // namespace peridot
