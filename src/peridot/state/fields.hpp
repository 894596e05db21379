#pragma once
// Point and bond storage: structure of arrays, one contiguous array per field. Vector fields keep their
// three components together (x0 y0 z0 x1 y1 z1 …) behind the accessor v(i, d): a bond loop reads all
// three components of a neighbour from one cache line. 2D problems store z = 0.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "peridot/core/vec3.hpp"

namespace peridot {

class VectorField {
 public:
  VectorField() = default;
  explicit VectorField(std::size_t n) : data_(3 * n, 0.0) {}
  void resize(std::size_t n) { data_.assign(3 * n, 0.0); }
  std::size_t size() const { return data_.size() / 3; }
  double& operator()(std::size_t i, int d) { return data_[3 * i + d]; }
  double operator()(std::size_t i, int d) const { return data_[3 * i + d]; }
  Vec3 get(std::size_t i) const { return {data_[3 * i], data_[3 * i + 1], data_[3 * i + 2]}; }
  void set(std::size_t i, Vec3 v) {
    data_[3 * i] = v.x;
    data_[3 * i + 1] = v.y;
    data_[3 * i + 2] = v.z;
  }
  double* data() { return data_.data(); }
  const double* data() const { return data_.data(); }

 private:
  std::vector<double> data_;
};

/// Where the points are and what they belong to; fixed after set-up.
struct Discretization {
  int dimension = 3;
  std::size_t num_points() const { return volume.size(); }
  VectorField x;                 ///< reference position (m)
  std::vector<double> volume;    ///< V (m³; in 2D, area × thickness)
  std::vector<std::int32_t> block;     ///< body (block) index
  std::vector<std::uint32_t> input_id; ///< order of generation, before the space-filling-curve reorder
  /// Input id of point i: i itself where the points were never reordered (input_id empty).
  std::size_t id_of(std::size_t i) const { return input_id.empty() ? i : std::size_t{input_id[i]}; }
  std::vector<std::string> block_names;
  /// The named sets of the bodies' meshes (node, side and element sets) as the points they select, by input id;
  /// one entry per body and set (geometry/mesh.hpp, mesh_point_sets). Node sets refer to them by name (mesh_set).
  struct MeshSet {
    std::string name;
    std::int32_t block = 0;
    std::vector<std::uint32_t> input_ids;
  };
  std::vector<MeshSet> mesh_sets;
};

/// Bonds in compressed sparse rows: the bonds of point i are offsets[i] … offsets[i+1]−1. Every per-bond
/// quantity is a parallel array indexed by the same bond index. The family is symmetric: j is a neighbour
/// of i exactly when i is a neighbour of j.
struct BondList {
  std::vector<std::uint64_t> offsets;     ///< size N + 1
  std::vector<std::uint32_t> neighbors;   ///< size nnz
  std::vector<std::uint8_t> broken;       ///< 1 once the bond has failed (irreversible)
  /// For bond i → j, the index of bond j → i; built only when a model reads its partner's bond history.
  /// Distributed, when j is a ghost the index is num_bonds() + k: the k-th partner-bond slot, past the end
  /// of this rank's bonds, where the per-bond arrays a model reads of its partner hold copies of the
  /// owner's values (parallel/domain.hpp).
  std::vector<std::uint32_t> reverse;
  std::size_t partner_slots = 0;  ///< distributed: partner-bond slots past num_bonds()
  std::size_t num_bonds() const { return neighbors.size(); }
};

/// The history of the inelastic models: per-bond arrays parallel to BondList and per-point arrays, whose
/// meaning each point's model declares (bond_history_arrays, point_arrays: materials/model_base.hpp), and
/// the two point fields every inelastic model reports. The arrays are empty when no model of the problem
/// declares them; plastic_strain and dissipation (outputs) always exist.
struct MaterialHistory {
  std::vector<std::vector<double>> bond;   ///< per bond (and partner-bond slot), as many as the most any model needs
  std::vector<std::vector<double>> point;  ///< per point (owned and ghost): history or the step's scratch
  std::vector<double> plastic_strain;      ///< ε̄p, equivalent plastic strain (-)
  std::vector<double> dissipation;         ///< dissipated energy density since t = 0 (J/m³)
  bool has_bond_history() const { return !bond.empty(); }
};

/// What changes during a run.
struct State {
  double time = 0;
  std::int64_t step = 0;
  VectorField u;          ///< displacement (m)
  VectorField v;          ///< velocity (m/s)
  VectorField force;      ///< internal force density (N/m³)
  VectorField body_force; ///< applied body force density (N/m³)
  std::vector<double> damage;           ///< φ, volume-weighted fraction of broken bonds (-)
  std::vector<double> dilatation;       ///< θ (-) (LPS; 2D: in-plane θ₂)
  std::vector<double> weighted_volume;  ///< m (m⁵; 2D m⁴·h) (LPS)
  MaterialHistory history;
  std::vector<double> fragment;  ///< fragment label (damage/fragments.hpp), when the problem has damage
  /// Output-only point fields of the correspondence model, by Exodus name (deformation_gradient_xx, …;
  /// solvers/correspondence_blocks.hpp), filled when output is written; zero at other models' points.
  std::map<std::string, std::vector<double>> point_outputs;
  /// Sizes the point fields for n points (zeros); the bond history stays empty until size_history.
  void resize(std::size_t n);
  /// Allocates `arrays` per-bond history arrays of nnz zeros (after resize); the point arrays are the
  /// models' (ModelContext::initialize_point_arrays).
  void size_history(std::size_t nnz, int arrays);
};

/// Names of State::point_outputs: deformation_gradient_xx … _zz (9, row by row), cauchy_stress_xx, _yy, _zz,
/// _xy, _yz, _zx, von_mises_stress, green_lagrange_strain_xx, _yy, _zz, _xy, _yz, _zx.
const std::vector<std::string>& correspondence_output_names();

}  // namespace peridot
