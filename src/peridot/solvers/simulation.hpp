#pragma once
// A problem set up and ready to solve: points, bonds, per-block materials, loads and the state, and the
// force evaluator every solver calls:
//   evaluate(Δt, break_bonds): internal force density (and the contact force density) at the current
//       u, from the committed history plus a trial update over Δt; nothing committed changes, except that
//       with break_bonds the bonds over their critical stretch at this u are marked broken first.
//   commit(Δt): the last evaluation is accepted; every history (plastic and back extensions,
//       correspondence stress and J2 history, dissipation, hourglass work, symmetry-plane release)
//       advances to it.
// The solver itself is a TimeIntegrator (time_integrator.hpp) chosen by the deck's solver.type:
// velocity Verlet (velocity_verlet.hpp) or adaptive dynamic relaxation (dynamic_relaxation.hpp);
// initialize() and step() run it.
//
// Distributed (mpirun): each rank integrates its owned points, its ghosts refreshed from their owners
// after every pass that changes what a bond loop reads of a partner (u after the drift, θ after the
// dilatation, m once); parallel/domain.hpp says why every owned value is then bitwise the serial one.
// History totals are exact sums over each rank's owned points and over the ranks (output_totals), the same
// bits for any rank count; each rank writes its owned points' piece of an Exodus frame (exodus_piece), nothing
// is gathered. External work is kept per point, to be summed the same way.
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "peridot/contact/rigid_body.hpp"
#include "peridot/contact/rigid_wall.hpp"
#include "peridot/contact/short_range.hpp"
#include "peridot/core/deterministic_sum.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/loads/loads.hpp"
#include "peridot/loads/node_sets.hpp"
#include "peridot/loads/temperature.hpp"
#include "peridot/neighbor/neighborhood.hpp"
#include "peridot/output/exodus_writer.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/parallel/halo.hpp"
#include "peridot/damage/critical_stretch.hpp"
#include "peridot/damage/energy_failure.hpp"
#include "peridot/solvers/correspondence_blocks.hpp"
#include "peridot/solvers/internal_force.hpp"
#include "peridot/solvers/surface_correction.hpp"
#include "peridot/solvers/time_integrator.hpp"
#include "peridot/state/fields.hpp"
#include "peridot/state/state_arrays.hpp"

namespace peridot {

/// Global quantities of one instant; every sum exact and rounded once (core/exact_sum.hpp), so identical for
/// any thread and rank count.
struct Totals {
  double external_work = 0;   ///< J, work of supports, body forces and contact forces since t = 0
  std::vector<Vec3> rigid_force;  ///< N, the points' contact force on each rigid wall and body
  double contact_energy = 0;  ///< J, stored in the contact penalties (rigid bodies and short-range pairs)
  std::vector<Vec3> body_contact_force;  ///< N, Σ b V of the contact forces on each body's points (short-range contact)
  double kinetic_energy = 0;  ///< J
  double strain_energy = 0;   ///< J, stored (elastic) energy
  double dissipated_energy = 0;  ///< J, plastic work or viscous dissipation since t = 0
  double hourglass_work = 0;  ///< J, work of the correspondence hourglass forces since t = 0 (stored-energy sign)
  Vec3 momentum;              ///< kg·m/s
  double max_damage = 0;
  double broken_fraction = 0;  ///< broken bonds / all bonds at t = 0
  std::size_t fragments = 0;  ///< connected sets of points through intact bonds
};

class Simulation {
 public:
  /// Discretizes, builds bonds, node sets, materials and loads. Throws InputError for problems only
  /// visible once the points exist (an empty node set, an unreadable point file); distributed, every rank
  /// throws the same error. Collective over `comm`.
  explicit Simulation(const Problem& problem, Communicator comm = Communicator::world());
  ~Simulation();
  Simulation(const Simulation&) = delete;  // the model context points into this object
  Simulation& operator=(const Simulation&) = delete;

  const Problem& problem() const { return problem_; }
  /// This rank's points: the owned ones (num_owned()), then the ghosts. One rank: every point.
  const Discretization& discretization() const { return disc_; }
  std::size_t num_owned() const { return owned_; }
  const Communicator& communicator() const { return comm_; }
  const Halo& halo() const { return halo_; }
  const BondList& bonds() const { return bonds_; }
  const std::vector<NodeSet>& node_sets() const { return node_sets_; }
  const ModelContext& model() const { return model_; }
  ModelContext& model() { return model_; }  ///< for drivers and tests that evaluate the kernels directly
  State& state() { return state_; }
  const State& state() const { return state_; }

  double stable_time_step() const { return stable_dt_; }  ///< without safety factor (s)
  /// How the surface correction's iteration ended ({0, 0} without one).
  const SurfaceCorrectionResult& surface_correction() const { return surface_correction_; }
  /// Δt (s) of a step: explicit, the deck's time_step or safety_factor × the stable one, shortened so that
  /// whole steps end at end_time; relaxation, the (real) time between load steps.
  double time_step() const { return dt_; }
  /// Steps (explicit) or load steps (relaxation) to the end of the run.
  std::int64_t total_steps() const { return total_steps_; }
  /// The solver the deck chose.
  TimeIntegrator& integrator() { return *integrator_; }
  const TimeIntegrator& integrator() const { return *integrator_; }

  /// Applies the initial conditions and computes the forces at t = 0 (the integrator's initialize).
  void initialize() { integrator_->initialize(); }
  /// One step of the integrator: an explicit time step, or a load step relaxed to equilibrium. Throws
  /// NumericalError naming step, time, point and position on a non-finite value.
  void step() { integrator_->advance(); }

  // -- what integrators call ------------------------------------------------------------------------
  /// State at t = 0: initial conditions, ghosts, body force at t = 0 (no force yet).
  void apply_initial_state();
  /// Internal force density (state().force) and, with rigid bodies or short-range contact, the contact
  /// force density (contact_force()) at the current state().u, with the history updated by trial over Δt (correspondence
  /// blocks: the stress over Δt from the committed one, with state().v as the velocity of the step).
  /// Changes nothing committed, so it may run any number of times for one step, except that with
  /// break_bonds the bonds over their critical stretch are marked broken first (velocity Verlet checks
  /// failure in the same pass, on u^{n+1}, as Peridigm does). Throws NumericalError (with step and time)
  /// on this rank only: call agree_on_failure before the next collective that could diverge.
  void evaluate(double dt, bool break_bonds);
  /// The deck's temperature field at state().time into the model context (T, and α (T − T_ref) per point),
  /// unless it is there already; nothing without a temperature field. evaluate() calls it; tests that call the
  /// bond loops directly call it themselves.
  void update_temperature();
  /// Accepts the last evaluate(): every history advances over Δt, partner-bond copies are refreshed.
  /// Collective.
  void commit(double dt);
  /// Marks every intact bond over its critical stretch at the current u broken, as evaluate(…, true)
  /// would, and returns how many broke on all ranks. Collective.
  std::uint64_t break_bonds();
  /// The loads of the deck (initial and boundary conditions, body forces).
  Loads& loads() { return *loads_; }
  const Loads& loads() const { return *loads_; }
  /// Contact force density (rigid walls and bodies, short-range pairs) at the last evaluate() (N/m³);
  /// meaningless without contact.
  const VectorField& contact_force() const { return contact_force_; }
  bool has_contact() const { return !bodies_->empty() || short_range_; }
  /// Work done on each owned point by the supports, body forces and contact forces since t = 0 (J);
  /// integrators add to it.
  std::vector<double>& external_work() { return work_; }
  /// Refreshes the ghosts' copy of a vector field (u, v) from their owners. Collective.
  void exchange_ghosts(VectorField& field) { halo_.exchange(field.data(), 3); }
  /// Throws, on every rank, the first failing rank's NumericalError (message empty: none). Collective;
  /// its time counts as communication.
  void agree_on_failure(const std::string& message);
  /// ρ of the point's block (kg/m³).
  double density_of(std::size_t point) const { return model_.params[disc_.block[point]].density; }
  /// Whether some material may break bonds.
  bool any_damage() const { return any_damage_; }
  /// The work done on each bond and the energy criterion (damage criterion: energy); null when no block
  /// uses it.
  const EnergyFailure* energy_failure() const { return energy_failure_.get(); }

  /// The rigid walls (first) and bodies of the deck (contact/rigid_body.hpp); empty() when none. The
  /// integrators move the free ones.
  const RigidBodies& rigid_bodies() const { return *bodies_; }
  RigidBodies& rigid_bodies() { return *bodies_; }
  /// The short-range contact (contact/short_range.hpp); null without a contact section.
  const ShortRangeContact* short_range() const { return short_range_.get(); }

  /// Whether some block uses the correspondence model (its history has an hourglass_work column).
  bool has_correspondence() const { return correspondence_ && !correspondence_->empty(); }
  /// The correspondence blocks (symmetry walls, fields); meaningful when has_correspondence().
  const CorrespondenceBlocks& correspondence() const { return *correspondence_; }

  /// Lines for the run's log at its end (empty without a plastic correspondence law): the largest equivalent
  /// plastic strain and the highest temperature, each with its point, and a warning when points have heated to
  /// T* ≥ 0.99, 99 % of the way to the melting temperature (CorrespondenceBlocks::extremes). Collective; the
  /// same lines on every rank, for any rank count.
  std::vector<std::string> plasticity_summary() const;

  /// Computes, on each rank for its points, what the outputs read, which the step keeps only as far as it
  /// needs: damage, fragment labels, and with `fields` the dilatation and correspondence fields of an Exodus
  /// frame (in state()), with `totals` the per-point terms of the totals. Nothing is gathered: distributed,
  /// each rank writes its own piece of a frame (exodus_piece()). Collective.
  void prepare_outputs(bool fields, bool totals);
  /// Distributed: this rank's piece of the Exodus output (output/exodus_writer.hpp): its owned points, their
  /// global indices, the whole problem's blocks and node-set sizes. Collective.
  ExodusPiece exodus_piece() const;
  /// The totals, after prepare_outputs(…, true), on every rank: each sum exact over the owned points and the
  /// ranks (core/exact_sum.hpp), so the correctly rounded total, the same bits for any thread and rank count,
  /// with nothing gathered. Collective.
  Totals output_totals() const;
  /// prepare_outputs(false, true), then output_totals(). Collective.
  Totals totals();
  /// Kinetic plus stored energy (J) of the whole problem, on every rank, without gathering anything: the
  /// fixed-point sum of communicator.hpp (the same bits for any rank count, within 4e-19 N² of the largest
  /// term): for decisions, such as the blow-up watch's threshold, not for reported totals. Collective.
  double energy_estimate();
  /// Reaction force on the node set `set_name`: −Σ f_i V_i over its points (N), summed exactly over the ranks'
  /// owned points (the same bits for any rank count). Collective.
  Vec3 reaction(const std::string& set_name) const;
  /// Bytes held by this rank's points and bonds (an estimate for `peridot check`).
  std::size_t memory_bytes() const;
  /// Seconds this rank took to make its points, their bonds and the partition (Simulation()).
  double setup_seconds() const { return setup_seconds_; }
  /// Points of the whole problem.
  std::size_t global_point_count() const { return global_points_; }
  /// Directed bonds of the whole problem (collective).
  std::uint64_t global_bond_count() const;
  /// This rank's communication in the steps so far (benchmarks): the halo exchanges of points and partner
  /// bonds, plus the per-step failure check (one small all-reduce) in seconds.
  Halo::Traffic communication() const;

  /// Everything a trajectory depends on beyond the deck and the set-up (state/state_arrays.hpp): the state,
  /// the histories, broken bonds, the work done, the contact forces, the rigid bodies and the solver's own
  /// state. A checkpoint (checkpoint.hpp) saves these and restores them after initialize().
  StateArrays state_arrays();
  /// After a checkpoint's values are in state_arrays(): refreshes the partner-bond copies and forgets what was
  /// derived from the state before (fragment labels, the temperature's time). Collective.
  void restored();
  /// Local → global point index (serial: empty, the identity).
  const std::vector<std::uint32_t>& global_index() const { return global_index_; }

  /// Labels state_.fragment now, with the bonds as they are (they may have broken since the step's labelling).
  /// Collective.
  void relabel_fragments() {
    fragments_step_ = -1;
    fragments();
  }

 private:
  /// Labels state_.fragment, once per step (collective).
  void fragments();
  /// The owned points of every rank for which keep(local index) holds (x, V, block, input id), in the
  /// global order, on every rank. Collective.
  Discretization assemble_discretization(const std::function<bool(std::size_t)>& keep) const;
  /// Throws, on every rank, the first failing rank's InputError (none: no error anywhere). Collective.
  void agree_on_input_error(const std::optional<InputError>& error) const;
  /// Copies the owners' per-bond history into the partner-bond slots (after every commit).
  void exchange_partner_bonds();
  /// The contact force density at the current u: rigid bodies (and the free ones' resultants), short-range
  /// pairs (rebuilding their list when a point has moved half the skin). Collective.
  void compute_contact();

  Problem problem_;
  Communicator comm_;
  Discretization disc_;
  std::size_t owned_ = 0, global_points_ = 0;
  double setup_seconds_ = 0;
  SurfaceCorrectionResult surface_correction_;
  std::vector<std::uint32_t> global_index_;
  Halo halo_;
  double collective_seconds_ = 0;  ///< in agree_on_failure
  Halo bond_halo_;  ///< partner-bond slots (BondList::reverse), for models that read their partner's bond
  /// Per rigid wall with contact: symmetry, after prepare_outputs(…, true): its mirror bonds' force density on
  /// each owned point (3 per point; empty for other walls).
  std::vector<std::vector<double>> symmetry_force_density_;
  BondList bonds_;
  std::vector<NodeSet> node_sets_;
  ModelContext model_;
  std::unique_ptr<Loads> loads_;
  std::unique_ptr<CorrespondenceBlocks> correspondence_;
  std::unique_ptr<RigidBodies> bodies_;
  std::unique_ptr<ShortRangeContact> short_range_;
  /// Short-range contact: positions (and with friction velocities) of its slots, the owned points then
  /// the remote partners, which contact_halo_ copies from their owners.
  std::vector<double> contact_y_, contact_v_;
  std::vector<double> contact_opened_;  ///< per bond: its pair's contact distance since it broke (ShortRangeContact)
  Halo contact_halo_;
  std::vector<double> contact_energy_;  ///< J per point, for the totals
  std::uint64_t broken_bonds_ = 0, all_bonds_ = 0;  ///< directed, all ranks, at the last prepare_outputs(…, true)
  std::unique_ptr<EnergyFailure> energy_failure_;  ///< null unless a block breaks bonds by their work
  std::unique_ptr<TemperatureField> temperature_;  ///< the deck's temperature field; null without one
  double temperature_time_ = std::numeric_limits<double>::quiet_NaN();  ///< the time model_.temperature is at
  VectorField contact_force_;  ///< contact force density (N/m³), at the time of the last force
  State state_;
  std::vector<double> energy_density_;
  double stable_dt_ = 0, dt_ = 0;
  std::int64_t total_steps_ = 0;
  std::unique_ptr<TimeIntegrator> integrator_;
  std::vector<double> work_;  ///< J, external work done on each point since t = 0
  bool any_dilatation_ = false, any_damage_ = false, any_start_step_ = false;
  /// The point arrays the present models' partners read (ModelContext::partner_point_arrays).
  std::vector<int> partner_arrays_;
  /// The point arrays that keep what θ lost to breaking bonds (ModelContext::released_extension_arrays).
  std::vector<int> released_arrays_;
  int history_arrays_ = 0;  ///< per-bond history arrays of the inelastic models (0: none)
  bool has_history_ = false;  ///< a model keeps bond or point arrays: prepare and commit run
  bool correspondence_failed_ = false;
  /// The Δt of the step whose start_step ran since the last commit (NaN: none ran).
  double started_dt_ = std::numeric_limits<double>::quiet_NaN();  ///< the last evaluate() failed in a correspondence block
  std::int64_t fragments_step_ = -1;  ///< the step state_.fragment was labelled at (-1: never)
};

}  // namespace peridot
