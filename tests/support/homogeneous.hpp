#pragma once
// A peridynamic "material point" for the constitutive tests: a lattice cube under a prescribed affine
// displacement u = (F − I)x of every point, and the stress of its centre point, whose family is full.
// For a homogeneous deformation the collapsed force state P = Σ_j T⟨ξ_j⟩ ⊗ ξ_j V_j is the (nominal)
// stress of the model (Silling et al. 2007, §15), so the centre behaves as the material point of a
// classical driver, with the model's own kinematics, return map and history.
#include <array>
#include <cmath>
#include <limits>

#include "peridot/materials/bond_loop.hpp"
#include "peridot/solvers/simulation.hpp"
#include "support/problems.hpp"

namespace peridot::testing {

using Mat3 = std::array<std::array<double, 3>, 3>;

class HomogeneousBlock {
 public:
  /// δ = 4.015Δx with partial volumes (interior lattice quadrature within 1 %, lps_patch_test) and a
  /// cube of 11 cells: the centre sits 5.5Δx from every face, beyond δ + ½Δx.
  static BlockSetup setup(const std::string& model) {
    BlockSetup s;
    s.model = model;
    s.horizon_factor = 4.015;
    s.partial_volume = true;
    s.cells[0] = s.cells[1] = s.cells[2] = 11;
    return s;
  }

  explicit HomogeneousBlock(const BlockSetup& s) : HomogeneousBlock(s, box_problem(s)) {}
  /// The block of s with the loads, solver and output of `problem` (built from box_problem(s)).
  HomogeneousBlock(const BlockSetup& s, const Problem& problem) : sim_(problem) {
    const Discretization& disc = sim_.discretization();
    double best = std::numeric_limits<double>::infinity();
    const Vec3 middle = 0.5 * Vec3{s.cells[0] * s.spacing, s.cells[1] * s.spacing, s.cells[2] * s.spacing};
    for (std::size_t i = 0; i < disc.num_points(); ++i)
      if (const double d = norm(disc.x.get(i) - middle); d < best) best = d, centre_ = i;
    sim_.model().set_time_step(0.0);
  }

  Simulation& sim() { return sim_; }
  std::size_t centre() const { return centre_; }
  const VectorField& displacement() const { return sim_.state().u; }
  const MaterialParams& params() const { return sim_.model().params[0]; }
  /// The block's model constants (Model::Params).
  template <class Model>
  const typename Model::Params& model_params() const {
    return sim_.model().model_params_of<Model>(0);
  }
  /// The Δt the history commit integrates over (lps_viscoelastic's ε, β).
  void set_step(double dt) {
    dt_ = dt;
    sim_.model().set_time_step(dt);
  }

  /// u = (F − I)x for every point; θ and the return map for it (the history is not committed).
  void deform(const Mat3& gradient) {
    const Discretization& disc = sim_.discretization();
    VectorField u(disc.num_points());
    for (std::size_t i = 0; i < disc.num_points(); ++i)
      for (int a = 0; a < 3; ++a) {
        double value = 0;
        for (int b = 0; b < 3; ++b) value += (gradient[a][b] - (a == b)) * disc.x(i, b);
        u(i, a) = value;
      }
    apply(u);
  }
  /// Any displacement field (becomes the state's u); θ and the return map for it (history not committed).
  void apply(const VectorField& u) {
    State& state = sim_.state();
    state.u = u;
    sim_.update_temperature();
    compute_dilatation(sim_.model(), state.u, state.dilatation, false, &state.history);
    prepare_history(sim_.model(), state.u, state.dilatation, state.history);
  }
  /// Makes the current deformation the end of a step of length set_step.
  void commit() { commit_history(sim_.model(), sim_.state().u, sim_.state().dilatation, sim_.state().history, dt_); }

  /// Calls body(b, t, g, V) for every intact bond b of point i: its scalar force state t = T_i⟨ξ⟩·M, its
  /// geometry g and its neighbour volume V, for the state's u (and, for lps_viscoelastic, the Δt of
  /// set_step: with Δt = 0 the committed back extension).
  template <class Body>
  void for_each_bond(std::size_t i, Body&& body) {
    const ModelContext& ctx = sim_.model();
    const State& state = sim_.state();
    const KernelFields fields = kernel_fields(ctx, state.dilatation, &state.history);
    const MaterialParams& p = params();
    const BondList& bonds = sim_.bonds();
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      if (bonds.broken[b]) continue;
      const std::uint32_t j = bonds.neighbors[b];
      const auto g = bond_loop::bond_geometry<3>(sim_.discretization().x.data(), state.u.data(), i, j);
      const double omega = influence(p.influence, g.xi, p.horizon);
      const double t = with_model(p.model, [&](auto m) -> double {
        using Model = decltype(m);
        if constexpr (Model::has_bond_kernel)
          return Model::force_scalar(ctx.model_params_of<Model>(0), fields, i, b, bond_loop::mechanical_extension(ctx, i, g),
                                     g.xi, omega);
        else
          throw std::logic_error("HomogeneousBlock: the model has no bond kernel");
      });
      body(b, t, g, bond_loop::neighbor_volume(ctx, i, j, g.xi));
    }
  }

  /// P = Σ_j t M ⊗ ξ V of the centre (Pa).
  Mat3 stress() {
    Mat3 P{};
    const Discretization& disc = sim_.discretization();
    for_each_bond(centre_, [&](std::uint64_t b, double t, const bond_loop::BondGeometry<3>& g, double V) {
      const Vec3 xi = disc.x.get(sim_.bonds().neighbors[b]) - disc.x.get(centre_);
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) P[a][c] += t * g.y[a] / g.length * xi[c] * V;
    });
    return P;
  }

 private:
  Simulation sim_;
  std::size_t centre_ = 0;
  double dt_ = 0;
};

inline Mat3 diagonal(double a, double b, double c) { return {{{a, 0, 0}, {0, b, 0}, {0, 0, c}}}; }

}  // namespace peridot::testing
