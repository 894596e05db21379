#pragma once
// Rigid bodies that the points cannot enter, by penalty contact: spheres, cylinders, boxes and planes, each
// fixed, moved as prescribed (a displacement of t) or free (its mass and velocity, moved by the reaction of
// the points' contact forces). The deck's rigid_walls are planes among them, moving along their normal at
// their speed. A point at y = x + u inside a body, at depth h below its surface, gets the force density
//   b = κ h n,   κ = stiffness_factor × Σ_j V_j c/ξ_j over a full family (N/m⁴),
// n the surface's outward normal at the nearest surface point, c the block's stable micromodulus
// (materials/material.hpp): the point stiffness of the Silling–Askari time step bound, 2π c δ² in 3D
// (∫ 4πξ² c/ξ dξ) and 2π h c δ in 2D. The default factor 0.5 makes a point of a flat surface (about half a
// family) no stiffer than an interior point, so the stable time step estimate still holds. The force is
// normal only (frictionless) and elastic: the penalty stores ½ κ h² V, which contact_energy reports. For
// comparisons with LAMMPS decks a body may instead push with fix indent's K h² (indenter_stiffness). The
// force on a body is −Σ b V over its contacts.
// A wall with `contact: symmetry` is, besides, a symmetry plane for the correspondence points near it
// (correspondence/mirror_bonds.hpp): they are bonded to the mirror images of their neighbours from t = 0
// until the body leaves; its force in the history then adds what those bonds exert.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "peridot/core/vec3.hpp"
#include "peridot/deck/expression.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/materials/model_context.hpp"
#include "peridot/state/fields.hpp"
#include "peridot/state/state_arrays.hpp"

namespace peridot {

struct RigidBody {
  std::string name;
  bool wall = false;  ///< from rigid_walls (history columns wall_<name>_x/_y/_z: its force only)
  RigidShapeKind shape = RigidShapeKind::plane;
  Vec3 center;        ///< at t = 0: sphere centre, cylinder base centre, box centre, a point of a plane (m)
  Vec3 axis{0, 0, 1}; ///< cylinder axis, plane normal (unit)
  double radius = 0, length = 0;
  Vec3 half;          ///< box half extents (m)
  RigidMotionKind motion = RigidMotionKind::fixed;
  std::array<std::optional<ScalarFunction>, 3> displacement;  ///< prescribed
  double wall_speed = 0;  ///< a wall's speed along its normal (m/s)
  double mass = 0;        ///< free (kg)
  double stiffness_factor = 0.5;
  double indenter_stiffness = 0;  ///< K > 0: force density K h² (LAMMPS's fix indent) instead of κ h (N/m⁵)
  // The body's motion: displacement d of its placement at t = 0, velocity, and the points' contact force on
  // it at the last evaluation.
  Vec3 offset, velocity, force;
};

/// A point's force density from one body, for the resultant.
struct BodyContact {
  std::uint32_t point = 0;
  Vec3 force_density;  ///< b (N/m³)
};

class RigidBodies {
 public:
  /// Every rigid wall (as a plane) and rigid body of the deck, in that order.
  RigidBodies(const Problem& problem, const ModelContext& model);
  bool empty() const { return bodies_.empty(); }
  std::size_t size() const { return bodies_.size(); }
  const RigidBody& operator[](std::size_t k) const { return bodies_[k]; }

  /// Moves the walls and the prescribed bodies to time t (offset and velocity); free bodies keep theirs.
  void move_to(double t);
  /// Free bodies: v += Δt F/m (half a velocity Verlet kick with Δt/2).
  void kick(double dt);
  /// Free bodies: d += Δt v.
  void drift(double dt);
  /// Each body's offset, velocity and the points' force on it, for checkpoints.
  void state_arrays(StateArrays& arrays) {
    for (std::size_t k = 0; k < bodies_.size(); ++k) {
      const std::string prefix = "rigid_body" + std::to_string(k) + ".";
      arrays.global(prefix + "offset", &bodies_[k].offset);
      arrays.global(prefix + "velocity", &bodies_[k].velocity);
      arrays.global(prefix + "force", &bodies_[k].force);
    }
  }
  /// Sets body k's contact force (N), the sum over every rank of −Σ b V of contacts(k).
  void set_force(std::size_t k, Vec3 force) { bodies_[k].force = force; }

  /// Adds the penalty force density (N/m³) of every body at its present placement on the points [0, n) of
  /// `disc` at displacement u into b, and lists each body's contacts (contacts(k), in point order).
  void compute(const Discretization& disc, std::size_t n, const VectorField& u, VectorField& b);
  const std::vector<BodyContact>& contacts(std::size_t k) const { return contacts_[k]; }

  /// Force on body k (N), −Σ b V of its contacts with every point of `disc` at displacement u, summed in
  /// point order (for the history, from the gathered state when distributed).
  Vec3 force_on(std::size_t k, const Discretization& disc, const VectorField& u) const;
  /// The force of point i on body k (N), −b V of their contact (zero without one).
  Vec3 force_from_point(std::size_t k, const Discretization& disc, const VectorField& u, std::size_t i) const {
    return -disc.volume[i] * force_density(bodies_[k], disc, u, i);
  }
  /// Energy stored in the penalties, ½ κ h² V, of point i (J).
  double point_energy(const Discretization& disc, const VectorField& u, std::size_t i) const;

 private:
  /// Depth h ≥ 0 of y inside body k at its present placement and the outward normal there (h = 0: outside).
  double depth(const RigidBody& body, Vec3 y, Vec3& normal) const;
  Vec3 force_density(const RigidBody& body, const Discretization& disc, const VectorField& u, std::size_t i) const;
  /// |b| (N/m³) and the stored energy per volume (J/m³) at depth h of a point of `block`.
  double pressure(const RigidBody& body, std::size_t block, double h) const;
  double energy_density(const RigidBody& body, std::size_t block, double h) const;

  int dimension_ = 3;
  std::vector<RigidBody> bodies_;
  std::vector<std::vector<BodyContact>> contacts_;
  std::vector<std::vector<BodyContact>> thread_contacts_;  ///< compute's per-thread lists, reused
  std::vector<double> point_stiffness_;  ///< κ / stiffness_factor per block (N/m⁴)
};

}  // namespace peridot
