#pragma once
// Exodus II output of a point cloud: one node per point, each point also a 1-node SPHERE element so that
// ParaView / VisIt draw it, and nodal fields per time step.
//
// File layout (what a reader sees):
//  - num_dim = disc.dimension (2 or 3); coordinates coordx, coordy[, coordz] = reference positions disc.x.
//  - Node k+1 (Exodus numbering is 1-based) is point k. The node number map (node_num_map) holds
//    disc.input_id[k] + 1, the order of generation before the space-filling-curve reorder, when input_id is set.
//  - One element block per distinct value b of disc.block, in ascending b: block id b + 1, block name
//    disc.block_names[b] (or "block_<b>" where no name is given), element type "SPHERE", 1 node per element,
//    one attribute "radius" (see equivalent_radius()). Elements are grouped by block, and within a block in
//    ascending point index; element_points() gives the point of every element in that order, and the element
//    number map (elem_num_map) holds the node id of each element's point so that element ids = node ids.
//  - Node sets: ids 1, 2, … in the order given, with their names, 0-based point indices stored as node k+1.
//  - Nodal variables: the fields of the point-field registry (state/point_fields.hpp) in its order, with its
//    names (a vector field as name_x, name_y[, name_z]; 2D: no *_z): first every field of scope `always`,
//      displacement_x, displacement_y, displacement_z, velocity_x, velocity_y, velocity_z,
//      force_density_x, force_density_y, force_density_z, damage, dilatation, weighted_volume, volume
//    then the optional fields the writer was made with (extra_fields), in the order given (the runner
//    gives them in registry order): equivalent_plastic_strain, dissipation, the correspondence fields
//    (deformation_gradient_xx … von_mises_stress … green_lagrange_strain_zx), temperature, fragment.
//    force_density is State::force (internal force density). volume is constant, yet written every frame:
//    an Exodus nodal variable has a value per time step, and a reader looking at frame k of a variable
//    written only at frame 1 would see fill values. The cost is one double per point per frame.
//  - Numbers are 8-byte doubles; the file is netCDF "64-bit offset" (Exodus large model), which keeps every
//    nodal variable in its own netCDF variable vals_nod_var1, vals_nod_var2, …
//
// Distributed runs write one file per rank, the Nemesis "spread" convention that ParaView, VisIt and SEACAS
// (epu) read as one data set: rank r of N writes NAME.N.r (r zero-padded to the width of N, piece_path()), with
// the points it owns and, per piece, what the same file written serially holds of them: coordinates, node ids
// (input id + 1, the same in every piece set and in the serial file), radius, values. Besides:
//  - every piece lists every element block and node set of the whole problem, the empty ones included, so that
//    block and set ids mean the same in every piece; node set members are the piece's own points;
//  - a named node map "point_index" holds each point's index in the whole problem + 1 (the serial file's node
//    number), which is how `peridot join` (output/exodus_join.hpp) puts the pieces back in the serial order;
//  - the Nemesis global parameters (ex_put_init_info / init_global / eb_info_global / ns_param_global and
//    load-balance maps with every point internal: points own no shared nodes).
//
// Crash safety: see write_frame(). The writer always creates a new file; appending to an existing one through
// ex_open would lose the whole-frame guarantee (this Exodus opens existing files in netCDF share mode).
// Side effect: the constructor sets ex_opts(EX_DEFAULT), process-wide, so that Exodus neither prints nor
// aborts on an error; every failure here becomes an exception carrying Exodus' message instead.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "peridot/state/fields.hpp"
#include "peridot/state/point_fields.hpp"

namespace peridot {

struct NodeSetOutput {
  std::string name;
  std::vector<std::uint32_t> points;  ///< 0-based point indices
};

/// An Exodus file's mesh as arrays, point by point (ExodusWriter makes one from a Discretization;
/// `peridot join` from the pieces of a distributed run).
struct ExodusMesh {
  int dimension = 3;
  std::string title;
  std::vector<double> coord[3];         ///< reference positions, coord[d][i]; dimension of them
  std::vector<int> node_id;             ///< per point: its node id (input id + 1)
  std::vector<std::int32_t> block;      ///< per point: its block index (≥ 0)
  std::vector<double> radius;           ///< per point: the sphere drawn for it
  std::vector<std::string> block_names; ///< by block index; "block_<b>" where missing or empty
  std::vector<NodeSetOutput> node_sets;
  std::size_t num_points() const { return node_id.size(); }
};

/// This file is one rank's piece of a distributed run's output (see the file comment).
struct ExodusPiece {
  int rank = 0, ranks = 1;
  /// Per point of the piece (the discretization's first point_index.size() points): its index in the whole
  /// problem.
  std::vector<std::uint32_t> point_index;
  std::uint64_t global_points = 0;
  std::vector<std::int32_t> blocks;          ///< every block with points in the whole problem, ascending
  std::vector<std::uint64_t> block_sizes;    ///< their points in the whole problem
  std::vector<std::uint64_t> node_set_sizes; ///< every node set's points in the whole problem
};

class ExodusWriter {
 public:
  /// Creates (clobbers) the file and writes the mesh. cross_section (the thickness in 2D, the bar's area in
  /// 1D) is used for the sphere radius only.
  /// Throws std::runtime_error naming the path and the Exodus/netCDF message on any failure of the library,
  /// std::logic_error on inconsistent input (a node set naming a point that does not exist, …).
  /// With a `piece`, the file is that piece: the discretization's first piece->point_index.size() points,
  /// node_sets by those points' indices.
  ExodusWriter(const std::string& path, const Discretization& disc, const std::vector<NodeSetOutput>& node_sets,
               const std::string& title, double cross_section = 1.0, const std::vector<std::string>& extra_fields = {},
               const ExodusPiece* piece = nullptr);
  /// The same from the mesh's arrays (`peridot join`).
  ExodusWriter(const std::string& path, const ExodusMesh& mesh, const std::vector<std::string>& extra_fields,
               const ExodusPiece* piece = nullptr);
  ExodusWriter(const ExodusWriter&) = delete;
  ExodusWriter& operator=(const ExodusWriter&) = delete;
  ExodusWriter(ExodusWriter&& other) noexcept;
  ExodusWriter& operator=(ExodusWriter&& other) noexcept;
  ~ExodusWriter();

  /// Appends one time step with the fields of `state` (sizes must match the discretization; an empty
  /// damage / dilatation / weighted_volume array is written as zeros), then flushes the file to the OS.
  /// Crash safety: see the comment in the implementation; in short, after a kill a reader sees every frame
  /// whose write_frame() returned, and possibly nothing of the frame being written.
  /// A piece's writer writes the first num_points() entries of each field (a rank's state holds its ghosts
  /// after its owned points).
  void write_frame(double time, const State& state);
  /// The same from raw values: column(k) gives the num_points() values of variable k (variable_names()
  /// order); used by `peridot join`.
  void write_frame(double time, const std::function<const double*(std::size_t)>& column);

  /// A restart's continuation (solvers/runner.hpp): appends the frames of the earlier results `earlier` (one
  /// file, or the pieces of a distributed run, with any number of ranks) whose step, round(time / time_step),
  /// is at most last_step and a multiple of every (so that a frame a stopped run wrote off its schedule is not
  /// kept), value for value: each point's values found by its index in the whole problem. Of pieces that a
  /// stopped run left with different frame counts, the frames every piece has. Returns how many. Throws
  /// std::runtime_error when a file cannot be read, or the files have other points or fields than this writer.
  int copy_frames(const std::vector<std::string>& earlier, double time_step, std::int64_t last_step, std::int64_t every);

  /// Closes the file; idempotent. Throws std::runtime_error if the final close fails.
  void close();

  int frames_written() const { return frames_; }
  std::size_t num_points() const { return num_points_; }
  const std::string& path() const { return path_; }
  /// Point index of every element, in Exodus element order (grouped by block; see the file comment).
  const std::vector<std::uint32_t>& element_points() const { return element_points_; }
  /// Nodal variable names as written (13 in 3D, 10 in 2D, then the extra fields).
  const std::vector<std::string>& variable_names() const { return variable_names_; }

  /// The optional fields a writer can be made with.
  static const std::vector<std::string>& optional_fields();

  /// Radius of the sphere drawn for a point of volume V: the sphere of volume V in 3D, (3V/4π)^(1/3); in 2D
  /// the disc of area V/thickness, sqrt(V/(π·thickness)); in 1D half the segment V/area. Either way
  /// neighbouring spheres of a lattice of spacing h just about touch (r ≈ 0.62h in 3D, 0.56h in 2D, 0.5h in 1D).
  static double equivalent_radius(double volume, int dimension, double cross_section);

  /// The file rank `rank` of `ranks` writes for `path`: path.N.r, r zero-padded to the digits of N
  /// (results.e.4.0; results.e.16.03), the Nemesis convention.
  static std::string piece_path(const std::string& path, int rank, int ranks);

 private:
  void create(const ExodusMesh& mesh, const ExodusPiece* piece);
  void check(int status, const char* what) const;  // throws on status < 0
  void release() noexcept;                          // ex_close, ignoring errors (destructor, failed ctor)

  int exoid_ = -1;
  std::string path_;
  int dimension_ = 3;
  std::size_t num_points_ = 0;
  int frames_ = 0;
  std::vector<std::string> extra_fields_;
  std::vector<std::uint32_t> element_points_;
  std::vector<std::uint32_t> point_index_;  // a piece's points' indices in the whole problem
  bool piece_ = false;                      // the file is a piece (ExodusPiece)
  std::uint64_t global_points_ = 0;         // points of the whole problem
  std::vector<std::string> variable_names_;
  std::vector<double> volume_;  // copy of disc.volume: written every frame, the writer keeps no reference
  std::vector<double> buffer_;  // one strided component at a time; reused for every frame
};

}  // namespace peridot
