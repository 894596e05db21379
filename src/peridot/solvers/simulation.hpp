#pragma once
// A problem set up and ready to integrate: points, bonds, per-block materials, loads and the state.
// The explicit solver is velocity Verlet (papers/003, "Temporal discretization"):
//   v^{n+½} = v^n + (Δt/2) a^n,  u^{n+1} = u^n + Δt v^{n+½},  v^{n+1} = v^{n+½} + (Δt/2) a^{n+1},
// with bond failure evaluated on u^{n+1} before the force, as Peridigm does. Inelastic models solve their
// return map on u^{n+1} before the force and commit their history after it, once per step. Correspondence
// blocks update their stress over the step from u^{n+1} and v^{n+1/2} (correspondence_blocks.hpp). Rigid
// walls add their penalty force density to the internal and body forces in both kicks, and their work to
// the external work (trapezoidal, like the body force).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "peridot/contact/rigid_wall.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/loads/loads.hpp"
#include "peridot/loads/node_sets.hpp"
#include "peridot/neighbor/neighborhood.hpp"
#include "peridot/damage/critical_stretch.hpp"
#include "peridot/solvers/correspondence_blocks.hpp"
#include "peridot/solvers/internal_force.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// Global quantities of one instant; sums taken in a fixed order, so identical for any thread count.
struct Totals {
  double kinetic_energy = 0;  ///< J
  double strain_energy = 0;   ///< J, stored (elastic) energy
  double dissipated_energy = 0;  ///< J, plastic work or viscous dissipation since t = 0
  double hourglass_work = 0;  ///< J, work of the correspondence hourglass forces since t = 0 (stored-energy sign)
  Vec3 momentum;              ///< kg·m/s
  double max_damage = 0;
  std::size_t fragments = 0;  ///< connected sets of points through intact bonds
};

class Simulation {
 public:
  /// Discretizes, builds bonds, node sets, materials and loads. Throws InputError for problems only
  /// visible once the points exist (an empty node set, an unreadable point file).
  explicit Simulation(const Problem& problem);
  Simulation(const Simulation&) = delete;  // the model context points into this object
  Simulation& operator=(const Simulation&) = delete;

  const Problem& problem() const { return problem_; }
  const Discretization& discretization() const { return disc_; }
  const BondList& bonds() const { return bonds_; }
  const std::vector<NodeSet>& node_sets() const { return node_sets_; }
  const ModelContext& model() const { return model_; }
  ModelContext& model() { return model_; }  ///< for drivers and tests that evaluate the kernels directly
  State& state() { return state_; }
  const State& state() const { return state_; }

  double stable_time_step() const { return stable_dt_; }  ///< without safety factor (s)
  double time_step() const { return dt_; }                ///< the Δt the run uses (s)
  std::int64_t total_steps() const { return total_steps_; }
  double external_work() const { return external_work_; }  ///< J, accumulated since t = 0

  /// Applies the initial conditions and computes the forces at t = 0.
  void initialize();
  /// One Verlet step. Throws NumericalError naming step, time, point and position on a non-finite value.
  void step();

  /// The rigid walls of the deck (contact/rigid_wall.hpp); empty() when none.
  const RigidWalls& walls() const { return *walls_; }

  /// Whether some block uses the correspondence model (its history has an hourglass_work column).
  bool has_correspondence() const { return correspondence_ && !correspondence_->empty(); }

  /// Refreshes damage and dilatation of every point, and the correspondence fields (for output; the step
  /// keeps only what it needs).
  void update_output_fields();
  Totals totals();
  /// Reaction force on a node set: −Σ f_i V_i over its points (N).
  Vec3 reaction(const NodeSet& set) const;
  /// Bytes held by points and bonds (an estimate for `peridot check`).
  std::size_t memory_bytes() const;

 private:
  /// Internal force at the current u (and, for correspondence blocks, the stress update over dt with the
  /// current, mid-step, velocity).
  /// Labels state_.fragment (once per step) and returns the number of fragments.
  std::size_t fragments();
  void compute_forces(double dt);
  void kick(double half_dt);

  Problem problem_;
  Discretization disc_;
  BondList bonds_;
  std::vector<NodeSet> node_sets_;
  ModelContext model_;
  std::unique_ptr<Loads> loads_;
  std::unique_ptr<CorrespondenceBlocks> correspondence_;
  std::unique_ptr<RigidWalls> walls_;
  VectorField wall_force_;  ///< penalty force density of the walls (N/m³), at the time of the last force
  State state_;
  std::vector<double> energy_density_;
  double stable_dt_ = 0, dt_ = 0;
  std::int64_t total_steps_ = 0;
  double external_work_ = 0;
  bool any_dilatation_ = false, any_damage_ = false;
  int history_arrays_ = 0;  ///< per-bond history arrays of the inelastic models (0: none)
  std::int64_t fragments_step_ = -1;  ///< the step state_.fragment was labelled at (-1: never)
  std::size_t fragment_count_ = 0;
};

/// Sum of term(i) over i < n in chunks of fixed size, chunk results added in order: bitwise the same for
/// any number of threads.
template <class Term>
double deterministic_sum(std::size_t n, Term&& term) {
  constexpr std::size_t chunk = 4096;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::vector<double> partial(chunks, 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t c = 0; c < chunks; ++c) {
    double sum = 0;
    const std::size_t end = std::min(n, (c + 1) * chunk);
    for (std::size_t i = c * chunk; i < end; ++i) sum += term(i);
    partial[c] = sum;
  }
  double total = 0;
  for (double p : partial) total += p;
  return total;
}

}  // namespace peridot
