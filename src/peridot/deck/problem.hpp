#pragma once
// The validated, fully resolved content of a deck: every default filled in, every unit converted to SI,
// every cross-reference (body → material, boundary condition → node set) checked. The rest of the
// pipeline reads only this; it never sees YAML. Each item keeps the deck position it came from, so that
// errors found later (a node set that selects no point) can still name file:line:col.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "peridot/core/error.hpp"
#include "peridot/core/vec3.hpp"
#include "peridot/core/shape.hpp"

namespace peridot {

enum class InfluenceKind { constant, inverse_distance, gaussian };  ///< ω = 1, δ/ξ, exp(−ξ²/δ²)
enum class PlaneKind { none, stress, strain };                      ///< none in 3D
/// Partial volumes: a neighbour cell cut by the horizon counts in proportion (linear ramp, ½ on the
/// horizon). `extended` also bonds the cells centred just beyond δ (up to δ + ½Δx), which converges
/// to the exact integrals; `horizon` bonds only |ξ| ≤ δ, the convention of LAMMPS PERI.
enum class PartialVolumeKind { none, extended, horizon };
/// How a bond sum weighs a neighbour: its volume (one_point), or times the isotropic direction weight
/// (neighbor/quadrature.hpp).
enum class QuadratureKind { one_point, isotropic };
/// Zoltan's geometric partitioners for a distributed run (parallel/partition.hpp).
enum class PartitionMethod { rcb, rib, hsfc };

/// Isotropic elastic constants, all four resolved from the two (or, for PMB, one) the deck gives.
struct ElasticConstants {
  double bulk_modulus = 0;    ///< K (Pa)
  double shear_modulus = 0;   ///< G (Pa)
  double youngs_modulus = 0;  ///< E (Pa)
  double poisson_ratio = 0;   ///< ν (-)
};

/// What breaks a bond: its stretch (critical_stretch, or the s0 of fracture_energy), or the work done on it
/// (fracture_energy with criterion: energy; damage/energy_failure.hpp).
enum class DamageCriterion { stretch, energy };

struct DamageSpec {
  bool enabled = false;
  std::optional<double> critical_stretch;  ///< s0 (-), given directly
  std::optional<double> fracture_energy;   ///< G0 (J/m²); s0 then follows from K, δ (3D/2D formulas)
  DamageCriterion criterion = DamageCriterion::stretch;  ///< energy: needs fracture_energy (Gc)
};

/// A material model's or a solver's own deck keys (its KeySpecs: deck/model_schema.hpp, solver_schema.hpp),
/// converted to SI: every valid value the deck gives and every default, in the order of the key table. A
/// key of a nested section is stored as "SECTION.KEY". The model or solver reads them when it sets up
/// (materials/NAME.cpp, solvers/NAME.cpp); the resolved deck writes them back in this order.
class Parameters {
 public:
  enum class Kind { number, integer, boolean, text };
  struct Entry {
    std::string key;
    SourcePos pos;     ///< where the value is (the owner's position for a default)
    Kind kind = Kind::number;
    double number = 0;  ///< number, integer (exact below 2⁵³) and boolean (0 or 1) values
    std::string text;   ///< a choice or text value
  };
  void set_number(std::string key, double value, SourcePos pos = {});
  void set_integer(std::string key, std::int64_t value, SourcePos pos = {});
  void set_boolean(std::string key, bool value, SourcePos pos = {});
  void set_text(std::string key, std::string value, SourcePos pos = {});
  bool has(std::string_view key) const;
  void erase(std::string_view key);
  /// The value under `key`; a programming error when absent or of another kind (the schema makes the key
  /// required or defaulted, the parser fills it in).
  double number(std::string_view key) const;
  std::int64_t integer(std::string_view key) const;
  bool boolean(std::string_view key) const;
  const std::string& text(std::string_view key) const;
  /// The number under `key`, or `fallback` where the deck gave none (a key without a default).
  double number_or(std::string_view key, double fallback) const;
  const Entry* find(std::string_view key) const;
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  Entry& slot(std::string key, Kind kind, SourcePos pos);
  const Entry& get(std::string_view key, Kind kind) const;
  std::vector<Entry> entries_;
};

struct MaterialSpec {
  std::string name;
  SourcePos pos;
  std::string model = "pmb";  ///< a name of the model catalogue (deck/model_schema.hpp)
  double density = 0;  ///< ρ (kg/m³)
  ElasticConstants elastic;
  InfluenceKind influence = InfluenceKind::constant;
  DamageSpec damage;
  Parameters parameters;  ///< the model's own keys
};

/// A body's points from a mesh file (geometry/mesh.hpp): one point per element at its centroid with the
/// element's volume, or one per SPHERE element (a node and its volume attribute).
struct MeshSpec {
  SourcePos pos;       ///< the `file` entry: where a problem with the file is reported
  std::string file;    ///< resolved relative to the deck's folder
  std::string format;  ///< exodus, abaqus or gmsh (given, or from the file's extension)
  std::string block;   ///< the element block, element set or physical group taken; empty = every element
  double scale = 1;    ///< coordinates are multiplied by this (1e-3 for a mesh in millimetres)
};

/// Where a body's points come from: a shape filled on the lattice, a text point file with columns
/// x y [z] volume [block] (block rows filtered by `block`, when given), or a mesh.
struct BodySpec {
  std::string name;
  SourcePos pos;
  std::string material;  ///< name of a MaterialSpec
  std::optional<Shape> shape;
  std::optional<MeshSpec> mesh;
  std::string points_file;         ///< resolved relative to the deck's folder
  std::optional<int> block_filter;  ///< keep only rows whose block column equals this
  double horizon = 0;               ///< δ (m), resolved from horizon or horizon_factor × spacing
  /// Thickness (m) of the volume-constraint layer: lattice sites outside the shape within this distance of the
  /// body's own, added to the body as the node set <name>_constraint; 0: none (shape bodies only).
  double volume_constraint = 0;
};

struct PrecrackSpec {
  SourcePos pos;
  // 1D: the position `at` on the bar. 2D: segment from a to b. 3D: parallelogram origin + s·edge1 + t·edge2,
  // s,t ∈ [0,1].
  bool is_point = false;
  double at = 0;
  bool is_segment = true;
  Vec3 a, b;                  ///< segment end points
  Vec3 origin, edge1, edge2;  ///< rectangle
};

struct NodeSetSpec {
  std::string name;
  SourcePos pos;
  std::optional<Shape> shape;  ///< points inside the shape (of the listed bodies, or of all)
  std::vector<std::string> bodies;  ///< restrict to these bodies; empty = all
  std::string ids_file;             ///< or: a text file of 0-based point ids (in input order)
  /// or: a node set, side set or element set of the bodies' meshes (geometry/mesh.hpp, mesh_point_sets)
  std::string mesh_set;
  /// The volume-constraint layer of bodies[0] (a set the deck makes, mesh_set naming the discretization's
  /// record of the layer), not written back to the resolved deck.
  bool generated = false;
};

/// A scalar expression of x, y, z (and t where allowed), checked by muParser at parse time.
struct Expression {
  std::string text;
  SourcePos pos;
  bool depends_on_time = false;
};

struct InitialConditionSpec {
  SourcePos pos;
  enum class Kind { displacement, velocity } kind = Kind::velocity;
  std::string node_set;  ///< empty = every point
  std::optional<Expression> component[3];
};

struct BoundaryConditionSpec {
  SourcePos pos;
  enum class Kind { displacement, velocity } kind = Kind::displacement;
  std::string node_set;
  int component = 0;  ///< 0, 1, 2 = x, y, z
  Expression value;   ///< of x, y, z, t (m or m/s)
};

struct BodyForceSpec {
  SourcePos pos;
  std::string node_set;  ///< empty = every point
  std::optional<Expression> component[3];  ///< force density (N/m³) of x, y, z, t
};

/// A traction (force per area) carried by a layer of points of depth d next to a surface, as Madenci & Oterkus
/// apply it: each point of the node set gets the body force t/d. The layer may be fictitious, an extension of the
/// body beyond the loaded surface (docs/algorithms.md §16).
struct TractionSpec {
  SourcePos pos;
  std::string node_set;
  double depth = 0;                        ///< d (m): the layer's depth normal to the surface
  std::optional<Expression> component[3];  ///< traction (Pa) of x, y, z, t
};

/// How a rigid wall loads the bodies (contact/rigid_wall.hpp): penalty on the points behind it, or, for
/// correspondence bodies that touch it, also as a symmetry plane (correspondence/mirror_bonds.hpp).
enum class WallContactKind { penalty, symmetry };

/// A rigid, frictionless plane that the points cannot cross (a plane among the rigid bodies,
/// contact/rigid_body.hpp): penalty contact on every point behind it. The plane moves along its normal at `speed`.
struct RigidWallSpec {
  std::string name;
  SourcePos pos;
  Vec3 point;                    ///< a point of the plane at t = 0 (m)
  Vec3 normal;                   ///< unit normal, pointing toward the side where the bodies are
  double speed = 0;              ///< velocity of the plane along its normal (m/s)
  double stiffness_factor = 0.5; ///< penalty stiffness as a fraction of a full family's bond stiffness (-)
  WallContactKind contact = WallContactKind::penalty;
};

/// A pair of bodies whose short-range contact has Coulomb friction (contact/short_range.hpp).
struct FrictionSpec {
  SourcePos pos;
  std::string first, second;  ///< body names (the same name twice: within that body)
  double coefficient = 0;     ///< μ (-)
};

/// Short-range forces between points that are not bonded (never bonded, or their bond broke), within and between
/// bodies: the Silling–Askari repulsion (contact/short_range.hpp). Absent: no short-range forces.
struct ContactSpec {
  SourcePos pos;
  double stiffness_factor = 15;     ///< c_S = factor × c, c the softer block's micromodulus (-)
  double distance_factor = 1.35;    ///< d_ij ≤ factor × (r_i + r_j), r the node radius (half the spacing) (-)
  double reference_fraction = 0.9;  ///< d_ij ≤ fraction × |ξ_ij|, the reference distance (-)
  double skin = 0.5;                ///< Verlet skin as a fraction of the largest node diameter (-)
  double barrier_fraction = 0;      ///< below this fraction of d_ij the repulsion grows without bound; 0: linear (-)
  std::vector<FrictionSpec> friction;
};

/// A rigid body's shape (contact/rigid_body.hpp); in 2D sphere and cylinder are discs, box a rectangle.
enum class RigidShapeKind { sphere, cylinder, box, plane };
/// fixed: at rest; prescribed: its centre moves by the displacement expressions of t; free: moved by the contact
/// forces of the points, with its mass and initial velocity.
enum class RigidMotionKind { fixed, prescribed, free };

/// A rigid body that the points cannot enter (contact/rigid_body.hpp): penalty contact with every point inside it.
struct RigidBodySpec {
  std::string name;
  SourcePos pos;
  RigidShapeKind shape = RigidShapeKind::sphere;
  Vec3 center;        ///< sphere: centre; cylinder: centre of the base; plane: a point of it (m)
  Vec3 axis{0, 0, 1}; ///< cylinder: unit axis; plane: unit normal toward the bodies
  double radius = 0, length = 0;  ///< sphere, cylinder (m)
  Vec3 lo, hi;        ///< box: corners (m)
  RigidMotionKind motion = RigidMotionKind::fixed;
  std::optional<Expression> displacement[3];  ///< prescribed: displacement of the body (m) as a function of t
  double mass = 0;    ///< free: mass (kg)
  Vec3 velocity;      ///< free: initial velocity (m/s)
  double stiffness_factor = 0.5;  ///< penalty stiffness as a fraction of a full family's (-)
  double indenter_stiffness = 0;  ///< K > 0: the penalty K h² of LAMMPS's fix indent instead (N/m⁵)
};

/// A prescribed temperature field: the thermal strain α (T − T_ref) of the ordinary models and the WLF shift of
/// the thermoviscoelastic one read it (loads/temperature.hpp).
struct TemperatureSpec {
  SourcePos pos;
  Expression value;      ///< T(x, y, z, t) (K)
  double reference = 0;  ///< T_ref (K): the temperature at which the body is free of thermal strain
};

/// The time integrator (solvers/time_integrator.hpp): its type (a name of deck/solver_schema.hpp's
/// catalogue: explicit, relaxation) and its own keys, which the solver reads (solvers/NAME.cpp).
struct SolverSpec {
  SourcePos pos;
  std::string type = "explicit";
  Parameters parameters;
};

struct ProbeSpec {
  std::string name;
  SourcePos pos;
  Vec3 point;         ///< the nearest point to this position is sampled
  std::string field;  ///< e.g. displacement_x, velocity_y, damage, dilatation
};

struct OutputSpec {
  SourcePos pos;
  std::string directory = "output";  ///< resolved relative to the deck's folder
  std::int64_t exodus_every = 0;      ///< 0 = no Exodus file
  std::string exodus_file = "results.e";
  std::int64_t history_every = 0;     ///< 0 = no history
  std::string history_file = "history.csv";
  std::vector<std::string> reaction_sets;  ///< node sets whose reaction force is recorded
  std::vector<ProbeSpec> probes;
  bool progress = true;
  /// Checkpoints (solvers/checkpoint.hpp), checkpoint_<step>.nc in the output folder: every this many steps
  /// (0: not by steps), every this much wall-clock time (s; 0: not by time), and on a stop signal when either
  /// is set. The last `checkpoint_keep` are kept.
  std::int64_t checkpoint_every = 0;
  double checkpoint_wall_time = 0;
  std::int64_t checkpoint_keep = 2;
  bool checkpoints() const { return checkpoint_every > 0 || checkpoint_wall_time > 0; }
};

struct Problem {
  std::string deck_path;
  std::string deck_dir;
  int dimension = 3;
  PlaneKind plane = PlaneKind::none;
  double thickness = 1;  ///< h (m), 2D only
  double area = 1;       ///< A (m²) of a bar, 1D only
  double spacing = 0;    ///< Δx (m); 0 when every body comes from a point file
  double horizon = 0;    ///< δ (m) of bodies that do not set their own (each BodySpec holds its resolved δ)
  Vec3 lattice_origin;   ///< lattice points sit at origin + (i + ½)Δx
  double jitter = 0;     ///< fraction of Δx, uniform in ±jitter·Δx per coordinate
  std::uint64_t seed = 1;
  PartialVolumeKind partial_volume = PartialVolumeKind::none;
  QuadratureKind quadrature = QuadratureKind::one_point;
  SourcePos quadrature_pos;  ///< where discretization.quadrature is (refusals of a block's model point here)
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  std::vector<PrecrackSpec> precracks;
  std::vector<NodeSetSpec> node_sets;
  std::vector<std::string> no_fail_sets;  ///< bonds touching these points never break
  std::vector<InitialConditionSpec> initial_conditions;
  std::vector<BoundaryConditionSpec> boundary_conditions;
  std::vector<BodyForceSpec> body_forces;
  std::vector<TractionSpec> tractions;
  std::vector<RigidWallSpec> rigid_walls;
  std::vector<RigidBodySpec> rigid_bodies;
  std::optional<ContactSpec> contact;  ///< short-range forces; none: points pass through each other
  std::optional<TemperatureSpec> temperature;  ///< none: no thermal strain, no WLF shift
  SolverSpec solver;
  PartitionMethod partition = PartitionMethod::rcb;  ///< decomposition.method
  OutputSpec output;
  std::vector<Diagnostic> warnings;  ///< deck problems that do not stop the run (e.g. an unusual horizon)
  double memory_limit = 0;  ///< bytes the points and bonds may take (0: the machine's memory); command line

  const MaterialSpec& material_of(const BodySpec& body) const;
  /// What a point's volume has besides its lattice cell Δx^n: the bar's area A (1D), the thickness h (2D), 1 (3D).
  double cross_section() const { return dimension == 1 ? area : dimension == 2 ? thickness : 1.0; }
};

}  // namespace peridot
