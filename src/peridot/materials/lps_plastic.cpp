#include "peridot/materials/lps_plastic.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

#include <cmath>
#include <numbers>

#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/model_context.hpp"

namespace peridot {

using namespace bond_loop;

LpsPlastic::Params LpsPlastic::resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams&) {
  Params p{lps_constants(spec.elastic, problem)};
  p.yield_stress = spec.parameters.number("yield_stress");
  p.hardening_modulus = spec.parameters.number("hardening_modulus");
  p.yield_calibration = plastic_yield_calibration(problem.dimension, problem.plane);
  return p;
}

double plastic_yield_calibration(int dimension, PlaneKind plane) {
  if (dimension == 3) return 5.0;                      // (C1)
  return plane == PlaneKind::stress ? 2.0 : 8.0 / 3.0;  // (C2) | (C3)
}

void LpsPlastic::calibrate(ModelContext& ctx, const MaterialParams& block, const Params& p, BlockRange range) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double moment = 0;  // Σ ω² ξ² V over the reference family
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j), omega = influence(block.influence, xi, block.horizon);
        moment += omega * omega * xi * xi * neighbor_volume(ctx, i, j, xi);
      }
      ctx.point_constants[0][i] = std::sqrt(p.yield_calibration * moment) * ctx.inverse_weighted_volume[i];
    }
  });
}

void LpsPlastic::prepare(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                         MaterialHistory& history, const MaterialParams& block, const Params& p, BlockRange range) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  const double* plastic_extension = history.bond[0].data();
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double alpha = p.alpha_deviatoric * ctx.inverse_weighted_volume[i];
      const double released = history.point[released_extension][i];  // (P8)
      double norm2 = 0, weighted = 0;  // ‖t^d_tr‖² and S = Σ (t^d_tr)²/ω V
      double along = 0;                // Σ ω ξ (e^d − e^dp_n) V over the intact bonds (P6)
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double omega = influence(block.influence, g.xi, block.horizon);
        const double ed = mechanical_extension(ctx, i, g) - theta[i] * g.xi * p.inverse_dilatation_factor;
        const double elastic = ed - plastic_extension[b] - released * g.xi;
        const double t = alpha * omega * elastic;
        const double v = neighbor_volume(ctx, i, j, g.xi);
        norm2 += t * t * v;
        weighted += t * t / omega * v;
        along += omega * g.xi * elastic * v;
      }
      finish_return_map(ctx, history, p, i, norm2, weighted, along);
    }
  });
}

void LpsPlastic::finish_return_map(const ModelContext& ctx, MaterialHistory& history, const Params& p, std::size_t i,
                                   double norm2, double weighted, double along) {
  const double H = p.hardening_modulus;
  const double alpha = p.alpha_deviatoric * ctx.inverse_weighted_volume[i];
  const double norm = std::sqrt(norm2);
  const double k = ctx.point_constants[0][i];  // (C)
  const double yield_n = p.yield_stress + H * history.plastic_strain[i];
  if (!(norm > k * yield_n)) {  // elastic (also a point without intact bonds)
    history.point[yield_scale][i] = 1;
    history.point[plastic_strain_increment][i] = 0;
    history.point[deviatoric_moment][i] = along * ctx.inverse_weighted_volume[i];
    return;
  }
  const double g = k * weighted / (alpha * norm);
  const double increment = g * (1 - k * yield_n / norm) / (1 + g * k * H / norm);  // (P5)
  history.point[plastic_strain_increment][i] = increment;
  history.point[yield_scale][i] = k * (yield_n + H * increment) / norm;
  history.point[deviatoric_moment][i] = history.point[yield_scale][i] * along * ctx.inverse_weighted_volume[i];
}

void LpsPlastic::commit(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                        MaterialHistory& history, const MaterialParams&, const Params& p, BlockRange range, double /*dt*/) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  double* plastic_extension = history.bond[0].data();
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double r = history.point[yield_scale][i], released = history.point[released_extension][i];
      if (r == 1 && released == 0) continue;  // elastic step, no bond broke: nothing changes
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, bonds.neighbors[b]);
        const double ed = mechanical_extension(ctx, i, g) - theta[i] * g.xi * p.inverse_dilatation_factor;
        const double plastic = plastic_extension[b] + released * g.xi;  // (P8)
        plastic_extension[b] = plastic + (1 - r) * (ed - plastic);      // (P4)
      }
      finish_commit(history, p, i);
    }
  });
}

void LpsPlastic::finish_commit(MaterialHistory& history, const Params& p, std::size_t i) {
  history.point[released_extension][i] = 0;
  const double increment = history.point[plastic_strain_increment][i];
  history.plastic_strain[i] += increment;
  // W_p increment = σ_Y,n+1 Δε̄p (P5)
  history.dissipation[i] += (p.yield_stress + p.hardening_modulus * history.plastic_strain[i]) * increment;
  history.point[yield_scale][i] = 1;
  history.point[plastic_strain_increment][i] = 0;
}

// The page of `peridot info --model lps_plastic` (docs/models/lps_plastic.md). The equations restate the
// header comment; keep them in step with the code.
ModelInfo LpsPlastic::info() {
  ModelDoc doc{
    .summary = R"(Mitchell's ordinary state-based elastic-plastic solid: the lps model whose deviatoric extension splits
into an elastic and a plastic part, the plastic part a history value of every bond. A point yields when the
norm of its deviatoric force state reaches a value calibrated from the uniaxial yield stress; the return to
the yield surface is the backward-Euler radial return of Mitchell's algorithm, solved exactly in one step.
The volumetric response stays elastic. Linear isotropic hardening is optional, with the equivalent plastic
strain defined through the plastic work; critical-stretch damage, when given, acts on the total stretch.)",
    .equations = R"(Notation as on the lps page (n, α_v, α_d = 3, 3K, 15G in 3D; 2, 2K′, 8G in 2D); e^dp the plastic
extension of a bond, ε̄p the equivalent plastic strain of a point, σ_Y = σ_y + H ε̄p; sums run over the
point's intact bonds unless said otherwise.

- (P1) t = (ω/m)[α_v θ ξ + α_d (e^d − e^dp − q ξ)], e^d = e − θξ/n, q = Σ ω ξ (e^d − e^dp) V / m
- (P2) yield function f = ‖t^d‖²/2 − ψ0, t^d = α ω (e^d − e^dp), α = α_d/m, ‖t^d‖² = Σ (t^d)² V; √(2ψ0) = k σ_Y
- (P3) trial state t^d_tr = α ω (e^d_{n+1} − e^dp_n); the step is elastic when ‖t^d_tr‖ ≤ k σ_Y,n
- (P4) otherwise t^d_{n+1} = r t^d_tr, r = kσ_Y,n+1/‖t^d_tr‖, and e^dp_{n+1} = e^dp_n + (1 − r)(e^d_{n+1} − e^dp_n)
  (for ω = 1 exactly Mitchell's Δλ = (‖t^d_tr‖/√(2ψ0) − 1)/α; for another ω the flow rule is ė^dp = λ t^d/ω,
  which keeps the return radial)
- (P5) plastic work ΔW_p = Σ t^d_{n+1} Δe^dp V = r(1 − r)S/α, S = Σ (t^d_tr)²/ω V, and σ_Y,n+1 Δε̄p = ΔW_p,
  solved in closed form: Δε̄p = g(1 − kσ_Y,n/‖t^d_tr‖)/(1 + gkH/‖t^d_tr‖), g = kS/(α‖t^d_tr‖)
- (P6) the q term makes t = ∂W/∂e exactly; q = 0 on a full family, where (P4) keeps Σ ω ξ e^dp V = 0
- (P7) θ = (n/m) Σ ω ξ (e − e^dp) V, the elastic volume change (the lps θ on a full family)
- (P8) in the step a bond breaks, the survivors' e^dp grows by ρξ, ρ = Σ_(broken now) ω ξ (e − e^dp) V / m,
  the share of θ the broken bonds take with them, so that the survivors' elastic state is continuous
- (C) calibration, per point over its whole reference family (like m): k² = c Σ ω² ξ² V / m², which is ψ0 at
  von Mises yield with the direction average of the deviatoric state: c = 5 in 3D (any deviatoric state;
  25σ_Y²/(8πδ⁵) for ω = 1 in the continuum), c = 2 in plane stress (in-plane uniaxial stress) and c = 8/3 in
  plane strain (in-plane pure shear)

The stored energy is W = α_v θ²/(2n) + (α_d/2m) Σ ω (e^d − e^dp)² V; the history output `dissipation` is
W_p per unit volume and `equivalent_plastic_strain` is ε̄p.)",
    .restrictions = R"(- Plasticity is deviatoric only: a pure volumetric strain never yields (no pressure dependence, no
  tension cut-off).
- The yield calibration uses each point's own family, but a point within δ of a free surface has a
  truncated, one-sided family whose deviatoric state differs from the interior's (no surface correction).
- In 2D the deviatoric norm sees the in-plane deviator only; the constant is exact for in-plane uniaxial
  stress (plane stress) or in-plane pure shear (plane strain), not for every stress state.
- One more pass over the bonds per step than lps (the return map), and one more after the force (the commit);
  8 bytes of plastic extension and 4 bytes of partner-bond index per bond.
- Damage, when given, uses the total stretch (the plastic extension is not subtracted), as in Peridigm;
  m is not updated when bonds break. Unlike Peridigm, θ sums the elastic extensions e − e^dp, a breaking
  bond's share of θ moves into the survivors' plastic extension, and the force keeps the q term, so that a
  damaged family stays conservative and breaking bonds only release energy (P6–P8 in the header
  materials/lps_plastic.hpp; without them a fragmenting ring gained 20 % energy).)",
    .further_references = {"Mitchell, A nonlocal, ordinary, state-based plasticity model for peridynamics, SAND2011-3166 (2011)"},
    .example = R"(materials:
  aluminium:
    model: lps_plastic
    density: 2.7 g/cm^3
    youngs_modulus: 69 GPa
    poisson_ratio: 0.33
    yield_stress: 276 MPa
    hardening_modulus: 500 MPa
    damage: {critical_stretch: 0.1})",
  };
  return {.name = name,
          .description = "elastic-plastic ordinary state-based solid (Mitchell), linear hardening",
          .reference = "Mitchell, SAND2011-3166 (2011)",
          .keys = {{.key = "yield_stress", .unit = Unit::pressure, .range = positive,
                    .description = "uniaxial yield stress σ_y (Pa)", .required = true},
                   {.key = "hardening_modulus", .unit = Unit::pressure, .default_yaml = "0", .range = non_negative,
                    .description = "linear hardening H (Pa): σ_Y = σ_y + H ε̄p; 0 = perfectly plastic"},
                   thermal_expansion_key()},
          .doc = doc};
}

}  // namespace peridot
