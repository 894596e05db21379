#pragma once
// Rigid, frictionless walls (an anvil): planes that the points cannot cross, by penalty contact.
// A wall is the plane through p(t) = p0 + s t n with unit normal n toward the bodies (speed s along n).
// A point at y = x + u behind it, g = (y − p(t))·n < 0, gets the force density
//   b = κ (−g) n,   κ = stiffness_factor × Σ_j V_j c/ξ_j over a full family (N/m⁴),
// with c the block's stable micromodulus (materials/material.hpp): the point stiffness of the
// Silling–Askari time step bound, 2π c δ² in 3D (∫ 4πξ² c/ξ dξ) and 2π h c δ in 2D. The default factor 0.5
// makes a point of a flat surface (about half a family) no stiffer than an interior point, so the stable
// time step estimate still holds. The force is normal only (frictionless) and elastic: the penalty stores
// ½ κ g² V and gives it back, so the work of a fixed wall over a whole contact is zero. Every wall acts on
// every point. The force on the wall is −Σ b V, summed in a thread-independent order.
// A wall with `contact: symmetry` is, besides, a symmetry plane for the correspondence points near it
// (correspondence/mirror_bonds.hpp): they are bonded to the mirror images of their neighbours from t = 0
// until the body leaves; its force in the history then adds what those bonds exert.
#include <string>
#include <vector>

#include "peridot/core/vec3.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/materials/model_context.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

struct RigidWall {
  std::string name;
  Vec3 point;         ///< p0 (m)
  Vec3 normal;        ///< n, unit, toward the bodies
  double speed = 0;   ///< s (m/s)
  double stiffness_factor = 0.5;
};

/// Refuses (InputError at the wall) a wall with contact: symmetry that the mirror bonds cannot model, from
/// the whole problem's points `disc` and the blocks' `params`: with a point of a non-correspondence body
/// within that body's horizon of it; with a
/// point behind it at t = 0; when no correspondence point is within a horizon of it, or the nearest is not
/// half its spacing (V^(1/3)/2, within 2 %) from it, so that the body's surface is not on the plane and
/// the images would overlap the body or leave a gap; with a point within a horizon of two such walls.
void check_symmetry_walls(const Problem& problem, const Discretization& disc, const std::vector<MaterialParams>& params);

class RigidWalls {
 public:
  RigidWalls(const Problem& problem, const ModelContext& model);
  bool empty() const { return walls_.empty(); }
  const std::vector<RigidWall>& walls() const { return walls_; }

  /// Penalty force density of every wall on every point at time t into b (N/m³; zero where no contact).
  void compute(const VectorField& u, double t, VectorField& b);
  /// Force on wall w (N), −Σ b V of its contacts, from every point of `disc` at displacement u and time t,
  /// summed in point order: computed when the history asks for it (from the gathered state when
  /// distributed), not in every step.
  Vec3 force_on_wall(std::size_t w, const Discretization& disc, const VectorField& u, double t) const;

 private:
  /// κ(−g) ≥ 0 (N/m³) of point i against the wall through `origin`.
  double pressure(const RigidWall& wall, Vec3 origin, const Discretization& disc, const VectorField& u, std::size_t i) const;

  const ModelContext* model_;
  std::vector<RigidWall> walls_;
  std::vector<double> point_stiffness_;  ///< κ / stiffness_factor per block (N/m⁴)
};

}  // namespace peridot
