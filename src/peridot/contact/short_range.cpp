// Short-range contact between points that are not bonded (short_range.hpp).
#include "peridot/contact/short_range.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <omp.h>

#include "peridot/core/bounding_box.hpp"
#include "peridot/core/error.hpp"

namespace peridot {

namespace {

/// The pair force of short_range.hpp per k_ij V_j (m): d − r, and below the barrier distance r_c = b d
/// (b > 0) its C¹ continuation d − r_c + r_c (r_c − r)/r, which grows without bound as r → 0.
inline double pair_push(double d, double r, double fraction) {
  const double barrier = fraction * d;
  return r >= barrier ? d - r : d - barrier + barrier * (barrier - r) / r;
}

/// The potential of pair_push per k_ij (m²) below r_c (its integral from r to d).
inline double barrier_potential(double d, double r, double barrier) {
  return 0.5 * (d - barrier) * (d - barrier) + (d - barrier) * (barrier - r) +
         barrier * (barrier * std::log(barrier / r) - (barrier - r));
}

/// A cell of the search grid as one integer: 21 bits per coordinate (offset so that negatives fit).
std::uint64_t cell_key(std::int64_t ix, std::int64_t iy, std::int64_t iz) {
  constexpr std::int64_t offset = std::int64_t{1} << 20, mask = (std::int64_t{1} << 21) - 1;
  return (static_cast<std::uint64_t>((ix + offset) & mask) << 42) | (static_cast<std::uint64_t>((iy + offset) & mask) << 21) |
         static_cast<std::uint64_t>((iz + offset) & mask);
}

}  // namespace

void ContactCandidates::add(std::uint32_t g, int rank, const double* deformed, const double* reference, double v,
                            std::int32_t b) {
  global.push_back(g);
  owner.push_back(rank);
  y.insert(y.end(), deformed, deformed + 3);
  x.insert(x.end(), reference, reference + 3);
  volume.push_back(v);
  block.push_back(b);
}

namespace {

double radius_of(double volume, double section, int dimension) {
  const double cell = volume / section;  // Δx^n
  return 0.5 * (dimension == 3 ? std::cbrt(cell) : dimension == 2 ? std::sqrt(cell) : cell);
}

}  // namespace

double ShortRangeContact::node_radius(double volume, const Problem& problem) {
  return radius_of(volume, problem.cross_section(), problem.dimension);
}

ShortRangeContact::ShortRangeContact(const ContactSpec& spec, const Problem& problem,
                                     const std::vector<MaterialParams>& params, bool damage, double largest_radius)
    : blocks_(params.size()),
      section_(problem.cross_section()),
      dimension_(problem.dimension),
      distance_factor_(spec.distance_factor),
      reference_fraction_(spec.reference_fraction),
      barrier_fraction_(spec.barrier_fraction),
      damage_(damage) {
  // k_ij from the softer of the two blocks, so that contact never stiffens a point beyond what its own
  // block's stable time step allows for.
  stiffness_.resize(blocks_ * blocks_);
  for (std::size_t a = 0; a < blocks_; ++a)
    for (std::size_t b = 0; b < blocks_; ++b)
      stiffness_[a * blocks_ + b] = spec.stiffness_factor * std::min(params[a].stable_micromodulus / params[a].horizon,
                                                                     params[b].stable_micromodulus / params[b].horizon);
  if (!spec.friction.empty()) {
    friction_.assign(blocks_ * blocks_, 0.0);
    auto block_of = [&](const std::string& name) {
      for (std::size_t k = 0; k < problem.bodies.size(); ++k)
        if (problem.bodies[k].name == name) return k;
      return blocks_;
    };
    for (const FrictionSpec& f : spec.friction) {
      const std::size_t a = block_of(f.first), b = block_of(f.second);
      if (a == blocks_ || b == blocks_) continue;  // the deck reports unknown bodies
      friction_[a * blocks_ + b] = friction_[b * blocks_ + a] = f.coefficient;
    }
  }
  skin_ = spec.skin * 2 * largest_radius;
  cutoff_ = distance_factor_ * 2 * largest_radius + skin_;
}

bool ShortRangeContact::place(const VectorField& x, const VectorField& u, std::size_t owned, double* y) const {
  const double start = omp_get_wtime();
  const bool built = builds_ > 0 && owned == owned_;
  const double limit = 0.25 * skin_ * skin_;
  const double* a = u.data();
  const double* b = built ? u_built_.data() : a;
  const double* p = x.data();
  bool moved = false;
#pragma omp parallel for schedule(static) reduction(|| : moved)
  for (std::size_t i = 0; i < owned; ++i) {
    const double dx = a[3 * i] - b[3 * i], dy = a[3 * i + 1] - b[3 * i + 1], dz = a[3 * i + 2] - b[3 * i + 2];
    moved = moved || dx * dx + dy * dy + dz * dz > limit;
    for (std::size_t d = 0; d < 3; ++d) y[3 * i + d] = p[3 * i + d] + a[3 * i + d];
  }
  compute_seconds_ += omp_get_wtime() - start;
  return moved || !built;
}

void ShortRangeContact::build(const ContactCandidates& candidates, std::size_t owned, const BondList& bonds,
                              const std::vector<std::uint32_t>& local_global, const VectorField& u) {
  const double start = omp_get_wtime();
  const std::size_t n = candidates.size();
  const std::vector<double>& y = candidates.y;
  owned_ = owned;
  ++builds_;
  u_built_.resize(owned_);
  std::copy(u.data(), u.data() + 3 * owned_, u_built_.data());
  std::vector<double> radius(n);
  for (std::size_t i = 0; i < n; ++i) radius[i] = radius_of(candidates.volume[i], section_, dimension_);

  // The candidate of each local point (owned, then ghosts), for the bonded-pair test: the owned points are
  // the first candidates; a ghost is one when its owner sent it (by global index, the others in increasing
  // order after the owned ones).
  const bool identity = local_global.empty();
  const std::size_t local = identity ? owned_ : local_global.size();
  std::vector<std::uint32_t> candidate_of(local, no_bond);
  for (std::size_t i = 0; i < owned_; ++i) candidate_of[i] = static_cast<std::uint32_t>(i);
  {
    const auto first = candidates.global.begin() + static_cast<std::ptrdiff_t>(owned_), last = candidates.global.end();
    for (std::size_t i = owned_; i < local; ++i) {
      const auto it = std::lower_bound(first, last, local_global[i]);
      if (it != last && *it == local_global[i]) candidate_of[i] = static_cast<std::uint32_t>(it - candidates.global.begin());
    }
  }

  // Cells of size ≥ the largest d_ij + s over the points' bounding box, filled by a counting sort: a point's
  // candidates are in the 27 cells around it. Where the box holds far more cells than points (fragments flown
  // far apart), the cells are the distinct occupied ones, found by binary search.
  const double h = cutoff_;
  const BoundingBox box = n == 0 ? BoundingBox{} : bounding_box(y.data(), 3, n);  // a rank without points lists nothing
  const Vec3 lo = box.lo, hi = box.hi;
  std::int64_t span[3];
  for (int d = 0; d < 3; ++d) span[d] = static_cast<std::int64_t>(std::floor((hi[d] - lo[d]) / h)) + 3;  // a cell of margin each side
  auto cell_of = [&](std::size_t i, int d) {
    return static_cast<std::int64_t>(std::floor((y[3 * i + static_cast<std::size_t>(d)] - lo[d]) / h)) + 1;
  };
  const double cells = static_cast<double>(span[0]) * static_cast<double>(span[1]) * static_cast<double>(span[2]);
  const bool dense = cells <= 8.0 * static_cast<double>(n) + 1024;
  auto key_of = [&](std::int64_t cx, std::int64_t cy, std::int64_t cz) {
    return dense ? static_cast<std::uint64_t>((cx * span[1] + cy) * span[2] + cz) : cell_key(cx, cy, cz);
  };
  std::vector<std::uint64_t> key(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) key[i] = key_of(cell_of(i, 0), cell_of(i, 1), cell_of(i, 2));
  std::vector<std::uint32_t> order(n);
  std::vector<std::uint64_t> first_of;  // dense: cell → its first entry in order (and one past the last cell)
  std::vector<std::uint64_t> sorted_keys;
  if (dense) {
    first_of.assign(static_cast<std::size_t>(cells) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++first_of[key[i] + 1];
    for (std::size_t c = 1; c < first_of.size(); ++c) first_of[c] += first_of[c - 1];
    std::vector<std::uint64_t> fill(first_of.begin(), first_of.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order[fill[key[i]]++] = static_cast<std::uint32_t>(i);  // increasing i per cell
  } else {
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
    sorted_keys.resize(n);
    for (std::size_t k = 0; k < n; ++k) sorted_keys[k] = key[order[k]];
  }
  auto cell_range = [&](std::uint64_t want) -> std::pair<std::size_t, std::size_t> {
    if (dense) return {first_of[want], first_of[want + 1]};
    auto [a, b] = std::equal_range(sorted_keys.begin(), sorted_keys.end(), want);
    return {static_cast<std::size_t>(a - sorted_keys.begin()), static_cast<std::size_t>(b - sorted_keys.begin())};
  };

  // The positions and radii in cell order: the scan below reads them contiguously.
  std::vector<double> sorted_y(3 * n), sorted_radius(n);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    for (std::size_t d = 0; d < 3; ++d) sorted_y[3 * k + d] = y[3 * i + d];
    sorted_radius[k] = radius[i];
  }

  // Each thread lists the pairs of one contiguous range of owned points (static schedule) in its own buffer,
  // in point order; the buffers joined in thread order are the lists in point order.
  struct Pair {
    std::uint32_t global, candidate, bond;
    double distance, coefficient, mu;
  };
  const int threads = omp_get_max_threads();
  std::vector<std::vector<Pair>> found(static_cast<std::size_t>(threads));
  std::vector<std::uint64_t> count(owned_ + 1, 0);
  const std::vector<double>& x = candidates.x;
#pragma omp parallel
  {
    std::vector<Pair>& mine = found[static_cast<std::size_t>(omp_get_thread_num())];
    // The bond i → j of the point at hand, by j's candidate index (set from i's family, cleared after it).
    std::vector<std::uint32_t> bond_to(n, no_bond);
    auto for_each_bond = [&](std::uint64_t begin, std::uint64_t end, auto&& f) {
      for (std::uint64_t b = begin; b < end; ++b) {
        const std::uint32_t c = candidate_of[bonds.neighbors[b]];
        if (c != no_bond) f(c, b);
      }
    };
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < owned_; ++i) {
      const Vec3 yi{y[3 * i], y[3 * i + 1], y[3 * i + 2]};
      const Vec3 xi{x[3 * i], x[3 * i + 1], x[3 * i + 2]};
      const std::size_t bi = static_cast<std::size_t>(candidates.block[i]);
      const std::int64_t cx = cell_of(i, 0), cy = cell_of(i, 1), cz = cell_of(i, 2);
      const std::uint64_t begin = bonds.offsets[i], end = bonds.offsets[i + 1];
      const std::size_t before = mine.size();
      for_each_bond(begin, end, [&](std::uint32_t c, std::uint64_t b) { bond_to[c] = damage_ ? static_cast<std::uint32_t>(b) : 0; });
      for (std::int64_t ox = -1; ox <= 1; ++ox)
        for (std::int64_t oy = -1; oy <= 1; ++oy)
          for (std::int64_t oz = -1; oz <= 1; ++oz) {
            const auto [first, last] = cell_range(key_of(cx + ox, cy + oy, cz + oz));
            for (std::size_t it = first; it < last; ++it) {
              const double dx = sorted_y[3 * it] - yi.x, dy = sorted_y[3 * it + 1] - yi.y, dz = sorted_y[3 * it + 2] - yi.z;
              const double reach = distance_factor_ * (radius[i] + sorted_radius[it]) + skin_;
              const double r2 = dx * dx + dy * dy + dz * dz;
              if (r2 >= reach * reach) continue;
              const std::uint32_t j = order[it];
              if (j == i) continue;
              const Vec3 xj{x[3 * j], x[3 * j + 1], x[3 * j + 2]};
              const double d = std::min(reference_fraction_ * norm(xj - xi), distance_factor_ * (radius[i] + radius[j]));
              if (r2 >= (d + skin_) * (d + skin_)) continue;
              const std::uint32_t bond = bond_to[j];
              if (!damage_ && bond != no_bond) continue;  // a bond that cannot break: never in contact
              const std::size_t bj = static_cast<std::size_t>(candidates.block[j]);
              mine.push_back({candidates.global[j], j, bond, d, stiffness_[bi * blocks_ + bj] * candidates.volume[j],
                              friction_.empty() ? 0.0 : friction_[bi * blocks_ + bj]});
            }
          }
      for_each_bond(begin, end, [&](std::uint32_t c, std::uint64_t) { bond_to[c] = no_bond; });
      std::sort(mine.begin() + static_cast<std::ptrdiff_t>(before), mine.end(),
                [](const Pair& p, const Pair& q) { return p.global < q.global; });
      count[i + 1] = mine.size() - before;
    }
  }

  // Remote partners: grouped by owner rank, increasing global index within a rank; each candidate's slot.
  std::vector<std::uint32_t> slot_of(n, no_bond);
  for (std::size_t i = 0; i < owned_; ++i) slot_of[i] = static_cast<std::uint32_t>(i);
  std::vector<std::uint32_t> partners;  // candidate indices
  for (const std::vector<Pair>& pairs : found)
    for (const Pair& p : pairs)
      if (p.candidate >= owned_) partners.push_back(p.candidate);
  std::sort(partners.begin(), partners.end());
  partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
  std::stable_sort(partners.begin(), partners.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return candidates.owner[a] < candidates.owner[b]; });
  const int ranks = n == 0 ? 1 : 1 + *std::max_element(candidates.owner.begin(), candidates.owner.end());
  remote_.resize(partners.size());
  remote_count_.assign(static_cast<std::size_t>(ranks), 0);
  for (std::size_t k = 0; k < partners.size(); ++k) {
    slot_of[partners[k]] = static_cast<std::uint32_t>(owned_ + k);
    remote_[k] = candidates.global[partners[k]];
    ++remote_count_[static_cast<std::size_t>(candidates.owner[partners[k]])];
  }

  offsets_.assign(owned_ + 1, 0);
  for (std::size_t i = 0; i < owned_; ++i) offsets_[i + 1] = offsets_[i] + count[i + 1];
  const std::size_t total = offsets_[owned_];
  PERIDOT_REQUIRE(bonds.num_bonds() < no_bond, "too many bonds on one rank for the contact list's bond indices");
  partner_.resize(total);
  bond_.resize(total);
  distance_.resize(total);
  coefficient_.resize(total);
  mu_.resize(friction_.empty() ? 0 : total);
  std::size_t k = 0;
  for (const std::vector<Pair>& pairs : found)
    for (const Pair& p : pairs) {
      partner_[k] = slot_of[p.candidate];
      bond_[k] = p.bond;
      distance_[k] = p.distance;
      coefficient_[k] = p.coefficient;
      if (!mu_.empty()) mu_[k] = p.mu;
      ++k;
    }
  build_seconds_ += omp_get_wtime() - start;
}

void ShortRangeContact::compute(const double* y, const double* v, const std::vector<std::uint8_t>& broken,
                                double* opened, VectorField& b) const {
  const double start = omp_get_wtime();
  double* out = b.data();
  const bool friction = !mu_.empty() && v != nullptr;
#pragma omp parallel for schedule(dynamic, 512)
  for (std::size_t i = 0; i < owned_; ++i) {
    double fx = 0, fy = 0, fz = 0;
    const double xi = y[3 * i], yi = y[3 * i + 1], zi = y[3 * i + 2];
    for (std::uint64_t k = offsets_[i]; k < offsets_[i + 1]; ++k) {
      const std::uint32_t bond = bond_[k];
      if (bond != no_bond && broken[bond] == 0) continue;
      const std::size_t j = partner_[k];
      const double dx = y[3 * j] - xi, dy = y[3 * j + 1] - yi, dz = y[3 * j + 2] - zi;
      const double r2 = dx * dx + dy * dy + dz * dz;
      double d = distance_[k];
      if (bond != no_bond && opened) {
        // The pair of a broken bond: its contact distance is the largest distance since the break, up to d.
        // Only i's thread writes bond i → j; j's bond j → i sees the same r (the same bits of r²).
        double& reach = opened[bond];
        if (reach < d) reach = r2 >= d * d ? d : std::max(reach, std::sqrt(r2));
        d = reach;
      }
      if (r2 >= d * d || r2 == 0) continue;
      const double r = std::sqrt(r2);
      const double push = coefficient_[k] * pair_push(d, r, barrier_fraction_);  // |b| (N/m³)
      const double s = push / r;
      fx -= s * dx, fy -= s * dy, fz -= s * dz;
      if (!friction || mu_[k] == 0) continue;
      // The tangential part of v_j − v_i: i is dragged along with j.
      const double ex = dx / r, ey = dy / r, ez = dz / r;
      double wx = v[3 * j] - v[3 * i], wy = v[3 * j + 1] - v[3 * i + 1], wz = v[3 * j + 2] - v[3 * i + 2];
      const double normal = wx * ex + wy * ey + wz * ez;
      wx -= normal * ex, wy -= normal * ey, wz -= normal * ez;
      const double sliding = std::sqrt(wx * wx + wy * wy + wz * wz);
      if (sliding == 0) continue;
      const double t = mu_[k] * push / sliding;
      fx += t * wx, fy += t * wy, fz += t * wz;
    }
    out[3 * i] += fx, out[3 * i + 1] += fy, out[3 * i + 2] += fz;
  }
  compute_seconds_ += omp_get_wtime() - start;
}

double ShortRangeContact::point_energy_density(std::size_t i, const double* y, const std::vector<std::uint8_t>& broken,
                                               const double* opened) const {
  if (i >= owned_) return 0.0;
  double energy = 0;
  for (std::uint64_t k = offsets_[i]; k < offsets_[i + 1]; ++k) {
    if (bond_[k] != no_bond && broken[bond_[k]] == 0) continue;
    const std::size_t j = partner_[k];
    const double dx = y[3 * j] - y[3 * i], dy = y[3 * j + 1] - y[3 * i + 1], dz = y[3 * j + 2] - y[3 * i + 2];
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double d = bond_[k] != no_bond && opened ? std::min(distance_[k], opened[bond_[k]]) : distance_[k];
    if (r >= d) continue;
    const double barrier = barrier_fraction_ * d;
    energy += r >= barrier ? 0.25 * coefficient_[k] * (d - r) * (d - r)
                           : 0.5 * coefficient_[k] * barrier_potential(d, r, barrier);
  }
  return energy;
}

}  // namespace peridot
