// Penalty contact of the points with rigid bodies (rigid_body.hpp).
#include "peridot/contact/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <omp.h>

#include "peridot/core/deterministic_sum.hpp"

namespace peridot {

RigidBodies::RigidBodies(const Problem& problem, const ModelContext& model) : dimension_(problem.dimension) {
  for (const RigidWallSpec& s : problem.rigid_walls) {
    RigidBody b;
    b.name = s.name;
    b.wall = true;
    b.shape = RigidShapeKind::plane;
    b.center = s.point;
    b.axis = s.normal;
    b.wall_speed = s.speed;
    b.motion = s.speed != 0 ? RigidMotionKind::prescribed : RigidMotionKind::fixed;
    b.stiffness_factor = s.stiffness_factor;
    bodies_.push_back(std::move(b));
  }
  for (const RigidBodySpec& s : problem.rigid_bodies) {
    RigidBody b;
    b.name = s.name;
    b.shape = s.shape;
    b.center = s.center;
    b.axis = s.axis;
    b.radius = s.radius;
    b.length = s.length;
    if (s.shape == RigidShapeKind::box) b.center = 0.5 * (s.lo + s.hi), b.half = 0.5 * (s.hi - s.lo);
    b.motion = s.motion;
    for (std::size_t c = 0; c < 3; ++c)
      if (s.displacement[c]) b.displacement[c].emplace(*s.displacement[c]).at_start(0, 0, 0);
    b.mass = s.mass;
    b.velocity = s.velocity;
    b.stiffness_factor = s.stiffness_factor;
    b.indenter_stiffness = s.indenter_stiffness;
    bodies_.push_back(std::move(b));
  }
  contacts_.resize(bodies_.size());
  // Σ_j V_j c/ξ over a full family: ∫ 4πξ² (c/ξ) dξ = 2π c δ² in 3D; in 2D, V = h × area and
  // ∫ 2πξ h (c/ξ) dξ = 2π h c δ; in 1D the integral diverges at ξ → 0 and the lattice's sum is
  // 2 A c Σ_{k ≤ δ/Δx} 1/k.
  for (const MaterialParams& p : model.params) {
    const double delta = p.horizon, c = p.stable_micromodulus;
    if (p.dimension == 1) {
      double harmonic = 0;  // point files give no spacing: the nearest neighbours only, then
      const long neighbours = problem.spacing > 0 ? static_cast<long>(std::floor(delta / problem.spacing * (1 + 1e-10))) : 1;
      for (long k = 1; k <= neighbours; ++k) harmonic += 1.0 / static_cast<double>(k);
      point_stiffness_.push_back(2 * problem.area * c * std::max(harmonic, 1.0));
      continue;
    }
    point_stiffness_.push_back(p.dimension == 3 ? 2 * std::numbers::pi * c * delta * delta
                                                : 2 * std::numbers::pi * problem.thickness * c * delta);
  }
  move_to(0.0);
}

void RigidBodies::move_to(double t) {
  for (RigidBody& b : bodies_) {
    if (b.motion != RigidMotionKind::prescribed) continue;
    if (b.wall) {
      b.offset = (b.wall_speed * t) * b.axis;
      b.velocity = b.wall_speed * b.axis;
      continue;
    }
    // The velocity by a central difference of the displacement (exact for motions up to quadratic in t).
    const double h = 1e-6 * std::max(std::abs(t), 1e-3);
    for (std::size_t c = 0; c < 3; ++c) {
      if (!b.displacement[c]) continue;
      const ScalarFunction& d = *b.displacement[c];
      b.offset[static_cast<int>(c)] = d(0, 0, 0, t);
      b.velocity[static_cast<int>(c)] = (d(0, 0, 0, t + h) - d(0, 0, 0, t - h)) / (2 * h);
    }
  }
}

void RigidBodies::kick(double dt) {
  for (RigidBody& b : bodies_)
    if (b.motion == RigidMotionKind::free) b.velocity = b.velocity + (dt / b.mass) * b.force;
}

void RigidBodies::drift(double dt) {
  for (RigidBody& b : bodies_)
    if (b.motion == RigidMotionKind::free) b.offset = b.offset + dt * b.velocity;
}

double RigidBodies::depth(const RigidBody& body, Vec3 y, Vec3& normal) const {
  Vec3 q = y - (body.center + body.offset);
  if (dimension_ <= 2) q.z = 0;
  if (dimension_ == 1) q.y = 0;
  switch (body.shape) {
    case RigidShapeKind::plane: {
      const double gap = dot(q, body.axis);
      normal = body.axis;
      return gap < 0 ? -gap : 0.0;
    }
    case RigidShapeKind::sphere: {
      const double r = norm(q);
      if (r >= body.radius) return 0.0;
      normal = r > 0 ? (1 / r) * q : Vec3{1, 0, 0};
      return body.radius - r;
    }
    case RigidShapeKind::cylinder: {
      const double a = dot(q, body.axis);
      const Vec3 radial = q - a * body.axis;
      const double r = norm(radial);
      if (a <= 0 || a >= body.length || r >= body.radius) return 0.0;
      // The nearest of the side, the base and the top; on the axis, the side is as near in every direction.
      const Vec3 across = std::abs(body.axis.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
      const Vec3 side = r > 0 ? (1 / r) * radial : (1 / norm(across - dot(across, body.axis) * body.axis)) *
                                                       (across - dot(across, body.axis) * body.axis);
      double h = body.radius - r;
      normal = side;
      if (a < h) h = a, normal = -1.0 * body.axis;
      if (body.length - a < h) h = body.length - a, normal = body.axis;
      return h;
    }
    case RigidShapeKind::box: {
      double h = std::numeric_limits<double>::infinity();
      for (int d = 0; d < dimension_; ++d) {
        const double below = q[d] + body.half[d], above = body.half[d] - q[d];
        if (below <= 0 || above <= 0) return 0.0;
        Vec3 n;
        n[d] = below < above ? -1.0 : 1.0;
        if (std::min(below, above) < h) h = std::min(below, above), normal = n;
      }
      return h;
    }
  }
  return 0.0;
}

Vec3 RigidBodies::force_density(const RigidBody& body, const Discretization& disc, const VectorField& u,
                                std::size_t i) const {
  Vec3 n;
  const double h = depth(body, disc.x.get(i) + u.get(i), n);
  if (h == 0) return {};
  return pressure(body, static_cast<std::size_t>(disc.block[i]), h) * n;
}

double RigidBodies::pressure(const RigidBody& body, std::size_t block, double h) const {
  return body.indenter_stiffness > 0 ? body.indenter_stiffness * h * h : body.stiffness_factor * point_stiffness_[block] * h;
}

double RigidBodies::energy_density(const RigidBody& body, std::size_t block, double h) const {
  return body.indenter_stiffness > 0 ? body.indenter_stiffness * h * h * h / 3
                                     : 0.5 * body.stiffness_factor * point_stiffness_[block] * h * h;
}

void RigidBodies::compute(const Discretization& disc, std::size_t n, const VectorField& u, VectorField& b) {
  double* bp = b.data();
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const RigidBody& body = bodies_[k];
    std::vector<BodyContact>& contacts = contacts_[k];
    contacts.clear();
    // A point's force from each body is added in body order. Static scheduling gives each thread one
    // contiguous range, in thread order, so the threads' lists joined in that order are in point order.
    std::vector<std::vector<BodyContact>>& found = thread_contacts_;  // kept between steps: no allocation per step
    found.resize(static_cast<std::size_t>(omp_get_max_threads()));
#pragma omp parallel
    {
      std::vector<BodyContact>& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
      mine.clear();
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        const Vec3 f = force_density(body, disc, u, i);
        if (f.x == 0 && f.y == 0 && f.z == 0) continue;
        for (int d = 0; d < 3; ++d) bp[3 * i + static_cast<std::size_t>(d)] += f[d];
        mine.push_back({static_cast<std::uint32_t>(i), f});
      }
    }
    for (const std::vector<BodyContact>& part : found) contacts.insert(contacts.end(), part.begin(), part.end());
  }
}

Vec3 RigidBodies::force_on(std::size_t k, const Discretization& disc, const VectorField& u) const {
  Vec3 total;
  for (int d = 0; d < 3; ++d)
    total[d] = -deterministic_sum(disc.num_points(), [&](std::size_t i) {
      return force_density(bodies_[k], disc, u, i)[d] * disc.volume[i];
    });
  return total;
}

double RigidBodies::point_energy(const Discretization& disc, const VectorField& u, std::size_t i) const {
  double energy = 0;
  for (const RigidBody& body : bodies_) {
    Vec3 n;
    const double h = depth(body, disc.x.get(i) + u.get(i), n);
    if (h > 0) energy += energy_density(body, static_cast<std::size_t>(disc.block[i]), h) * disc.volume[i];
  }
  return energy;
}

}  // namespace peridot
