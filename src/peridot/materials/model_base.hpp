#pragma once
// What a model need not declare: the defaults of a stateless bond model. Every model derives from ModelBase
// and overrides what it has. A model is one struct in its own file pair (materials/NAME.{hpp,cpp}) with
//   - `name`, `info()`: its deck keys, nested sections, cross-key checks and documentation page
//     (deck/model_schema.hpp), and `Params`, its block constants, built by `resolve` from the deck's
//     MaterialSpec;
//   - its kernels: force_scalar, bond_energy, point_energy (static, called per bond: no virtual call);
//   - what it stores: per-bond history arrays, per-point arrays (history or this step's scratch), which of
//     those a partner's force reads (exchanged to ghosts), per-point constants from the reference family;
//   - its hooks: calibrate (once), set_time_step, start_step (once per step, before its first force),
//     prepare (before every force, no side effect on the history), commit (the step is accepted).
// Its one registration line is in materials/models.hpp.
#include <array>
#include <cstdint>
#include <vector>

#include "peridot/geometry/discretize.hpp"
#include "peridot/materials/material.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

struct ModelContext;

struct ModelBase {
  /// A bond kernel (force_scalar, bond_energy, point_energy); the correspondence model has none.
  static constexpr bool has_bond_kernel = true;
  /// Needs θ of every point before the force (a dilatation pass over the bonds).
  static constexpr bool uses_dilatation = false;
  /// Has a start_step that writes per-bond arrays (they are exchanged to the partner-bond slots after it).
  static constexpr bool has_start_step = false;
  /// Applies the surface correction's bond factor G (solvers/surface_correction.hpp) when its block asks for it
  /// (`surface_correction_key()` among its keys): the bond loops then hand its kernels ω G for ω.
  static constexpr bool corrects_surfaces = false;
  /// Per-bond history arrays (MaterialHistory::bond[0 … n−1]); the partner's bond j → i is then indexed too.
  /// A model whose count depends on its parameters gives the most it may need here and the count of a block
  /// in `static int bond_history_count(const Params&)`.
  static constexpr int bond_history_arrays = 0;
  /// Per-point arrays (MaterialHistory::point[k]): history or scratch of the step, with their start values.
  static constexpr std::array<PointArray, 0> point_arrays{};
  /// Which of point_arrays a partner's force reads (exchanged to ghosts after prepare).
  static constexpr std::array<int, 0> partner_point_arrays{};
  /// The point array that the dilatation pass fills with Σ ω ξ (extension) V / m of the bonds breaking in
  /// this evaluation (zero when none breaks); −1: none.
  static constexpr int released_extension_array = -1;
  /// Per-point constants (ModelContext::point_constants[k]) that calibrate fills once.
  static constexpr int point_constant_arrays = 0;
  /// The power p of ξ in the fourth moment Σ ω ξᵖ n⊗n⊗n⊗n V that makes the model's stiffness under a
  /// homogeneous strain (pmb 1, the lps family 2): the isotropic quadrature fits its direction weight to it
  /// (neighbor/quadrature.hpp). 0: the model's sums are not of that form and the deck refuses the quadrature.
  static constexpr int quadrature_moment_power = 0;

  /// The extension a bond adds to the dilatation sum Σ ω ξ ê V (e: its mechanical extension, xi: |ξ|).
  static double dilatation_extension(const KernelFields&, std::uint64_t /*bond*/, double e, double /*xi*/) { return e; }
  /// θ_i from the dilatation sum: (n/m) Σ ω ξ ê V, n the model's dilatation_factor, the dimension for a model
  /// without one (pmb: its θ is only an output, ε₁₁ + ε₂₂ (+ ε₃₃) of a homogeneous strain as for lps).
  template <class Params>
  static double dilatation(const Params& p, const KernelFields& s, std::size_t i, double sum, int dimension) {
    if constexpr (requires { p.dilatation_factor; }) return p.dilatation_factor * sum * s.inverse_m[i];
    else return dimension * sum * s.inverse_m[i];
  }

  template <class Params>
  static void set_time_step(Params&, double /*dt*/) {}
  template <class Params>
  static void calibrate(ModelContext&, const MaterialParams&, const Params&, BlockRange) {}
  /// The step over Δt to the current time starts from the committed history (and the temperature of the
  /// current time): called once per step, before the step's first force evaluation.
  template <class Params>
  static void start_step(const ModelContext&, MaterialHistory&, const MaterialParams&, const Params&, BlockRange,
                         double /*dt*/) {}
  template <class Params>
  static void prepare(const ModelContext&, const VectorField&, const std::vector<double>&, MaterialHistory&,
                      const MaterialParams&, const Params&, BlockRange) {}
  template <class Params>
  static void commit(const ModelContext&, const VectorField&, const std::vector<double>&, MaterialHistory&,
                     const MaterialParams&, const Params&, BlockRange, double /*dt*/) {}
};

}  // namespace peridot
