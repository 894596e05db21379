#pragma once
// Short-range contact (Silling & Askari 2005): two points that are not bonded (never bonded, or their
// bond broke), of one body or of two, repel each other when their distance r = |y_j − y_i| falls below
//   d_ij = min(reference_fraction |x_j − x_i|, distance_factor (r_i + r_j)),
// r_i the node radius (half the spacing: ½ V^(1/3) in 3D, ½ √(V/h) in 2D, ½ V/A in 1D). The pair force
// density on i is
//   b_i = −k_ij (d_ij − r) V_j e_ij,   e_ij = (y_j − y_i)/r,   k_ij = stiffness_factor × min(c_i/δ_i, c_j/δ_j),
// c the block's stable (PMB) micromodulus, so that c_S = 15 c by default as in LAMMPS and EMU; the pair
// stores ½ k_ij (d_ij − r)² V_i V_j. The reference fraction keeps neighbours at rest apart from the
// contact: a pair is never compressed at t = 0. A bond that breaks while its points are closer than d_ij
// (a point failing under compression) would otherwise hand the pair ½ k (d_ij − r)² of energy at once and
// fire its points apart; so the pair's contact distance starts at the distance r_b it had when the bond
// broke, grows with the largest distance since, and is d_ij once the pair has been that far apart:
//   d_ij(t) = min(d_ij, max over the time since the break of r). The force then only resists approach.
// With friction (coefficient μ per pair of bodies), i also gets μ k_ij (d_ij − r) V_j along the tangential part of v_j − v_i (Coulomb, against the sliding).
// The linear force is finite at r = 0, so a pair driven together head-on hard enough meets, and coincident points
// have no direction between them (docs/algorithms.md §17). With a barrier fraction b > 0
// the force below r_c = b d_ij continues C¹ as a barrier that no finite energy crosses:
//   |b_i| = k_ij (d_ij − r_c + r_c (r_c − r)/r) V_j,  stored ½ k (d − r_c)² + k (d − r_c)(r_c − r) + k r_c (r_c ln(r_c/r) − r_c + r).
//
// The search costs little when nothing touches: a Verlet list of the pairs within d_ij + s, s the skin,
// over the deformed positions, rebuilt only when some point has moved s/2 since the last build (then no
// pair outside the list can be within d_ij). A pair that is bonded keeps its bond's index and is skipped
// while the bond is intact (a byte read); without damage anywhere, bonded pairs are left out at the build.
//
// Indices: the owned points' pairs are built over candidates (ContactCandidates): the owned points, then, on a
// distributed run, the other ranks' points whose deformed positions lie within the search reach of this
// rank's own (parallel/contact_candidates.hpp); no rank reads the whole problem. The partners are slots: the
// owned points (0 … owned − 1), then the remote partners (remote(), grouped by owner rank) whose positions
// the caller copies in from their owners each step. Each point's pairs are in increasing global index, and a
// point's force is gathered from its own pairs only, so every owned force is the same bits for any thread
// and rank count.
#include <cstdint>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/materials/model_context.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// The points one rank's contact search looks at: its owned points first, in local order, then other ranks'
/// points near them in increasing global index.
struct ContactCandidates {
  std::vector<std::uint32_t> global;  ///< index in the whole problem
  std::vector<int> owner;             ///< rank that owns the point
  std::vector<double> y, x;           ///< deformed and reference positions, 3 per point (m)
  std::vector<double> volume;         ///< m³
  std::vector<std::int32_t> block;
  std::size_t size() const { return global.size(); }
  /// Appends one point.
  void add(std::uint32_t g, int rank, const double* deformed, const double* reference, double v, std::int32_t b);
};

class ShortRangeContact {
 public:
  /// `params`: the blocks'; `damage`: whether any bond may break; `largest_radius`: the largest node radius
  /// of the whole problem (node_radius of its points), which sets the search cells and the skin.
  ShortRangeContact(const ContactSpec& spec, const Problem& problem, const std::vector<MaterialParams>& params,
                    bool damage, double largest_radius);
  /// Half the spacing of a point of this volume: ½ V^(1/3) in 3D, ½ √(V/h) in 2D, ½ V/A in 1D.
  static double node_radius(double volume, const Problem& problem);
  /// The farthest two points can be apart and still be listed as a pair (d_ij + s at most): a rank needs the
  /// other ranks' points within this distance of its own.
  double search_reach() const { return cutoff_; }

  /// Writes the owned points' positions y = x + u into y (3 per point) and returns whether one of them has
  /// moved more than s/2 since the last build (or none was built): one pass over the points.
  bool place(const VectorField& x, const VectorField& u, std::size_t owned, double* y) const;
  /// Builds the pair lists of the `owned` first candidates over all candidates. `bonds`: the local bond list,
  /// neighbours local indices (owned points, then ghosts) whose global indices are `local_global` (empty: the
  /// local index is the global one, one rank); `u`: the owned points' displacement now (the reference for
  /// place's "moved" test).
  void build(const ContactCandidates& candidates, std::size_t owned, const BondList& bonds,
             const std::vector<std::uint32_t>& local_global, const VectorField& u);
  /// Global indices of the remote partners, grouped by owner rank (ascending), increasing within a rank;
  /// their positions go to slots owned + k. remote_count()[r]: how many rank r owns.
  const std::vector<std::uint32_t>& remote() const { return remote_; }
  const std::vector<int>& remote_count() const { return remote_count_; }

  /// Adds the short-range force density on each owned point into b (N/m³), from the slots' positions y and
  /// (with friction) velocities v, 3 values per slot; `broken`: the bonds' flags; `opened`: per bond, the
  /// contact distance of its pair since it broke (0 while intact: set and grown here), or null when no bond
  /// can break. Calling it twice with the same y changes nothing.
  void compute(const double* y, const double* v, const std::vector<std::uint8_t>& broken, double* opened,
               VectorField& b) const;
  /// Energy stored in owned point i's pairs, half of each, per volume of i (J/m³), with the contact distances
  /// of the last compute.
  double point_energy_density(std::size_t i, const double* y, const std::vector<std::uint8_t>& broken,
                              const double* opened) const;
  bool has_friction() const { return !friction_.empty(); }

  /// Pairs in the list, list builds so far, and the seconds spent in builds and in place and compute (for the
  /// run log and the benchmarks).
  std::size_t pairs() const { return partner_.size(); }
  std::size_t builds() const { return builds_; }
  double build_seconds() const { return build_seconds_; }
  double compute_seconds() const { return compute_seconds_; }

 private:
  static constexpr std::uint32_t no_bond = 0xffffffffu;
  std::size_t blocks_ = 0;
  std::vector<double> stiffness_;   ///< k per pair of blocks (blocks_ × blocks_)
  std::vector<double> friction_;    ///< μ per pair of blocks (empty: no friction)
  double section_ = 1;              ///< the problem's cross-section (m² in 1D, thickness in 2D, 1 in 3D)
  int dimension_ = 3;
  double distance_factor_ = 1.35, reference_fraction_ = 0.9, barrier_fraction_ = 0, skin_ = 0, cutoff_ = 0;
  bool damage_ = false;
  std::size_t owned_ = 0, builds_ = 0;
  double build_seconds_ = 0;
  mutable double compute_seconds_ = 0;
  VectorField u_built_;             ///< the owned points' displacement at the last build
  // The pair lists in compressed rows over the owned points (structure of arrays).
  std::vector<std::uint64_t> offsets_;
  std::vector<std::uint32_t> partner_;  ///< slot of j
  std::vector<std::uint32_t> bond_;     ///< bond i → j, or no_bond
  std::vector<double> distance_;        ///< d_ij (m)
  std::vector<double> coefficient_;     ///< k_ij V_j (N/m⁴)
  std::vector<double> mu_;              ///< μ_ij (with friction)
  std::vector<std::uint32_t> remote_;
  std::vector<int> remote_count_;
};

}  // namespace peridot
