#include "peridot/materials/lps_viscoelastic.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

#include <cmath>

#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/maxwell_element.hpp"
#include "peridot/materials/model_context.hpp"

namespace peridot {

using namespace bond_loop;

LpsViscoelastic::Params LpsViscoelastic::resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams&) {
  Params p{lps_constants(spec.elastic, problem)};
  p.relaxing_fraction = spec.parameters.number("relaxing_fraction");
  p.relaxation_time = spec.parameters.number("relaxation_time");
  return p;
}

void LpsViscoelastic::set_time_step(Params& p, double dt) {
  const double x = dt / p.relaxation_time;
  p.viscous_decay = std::exp(-x);
  // β = 1 − (1 − ε)/x, written with expm1 so that a small Δt/τ_b keeps its digits.
  p.viscous_ramp = dt > 0 ? 1 + std::expm1(-x) / x : 0.0;
}

void LpsViscoelastic::commit(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                             MaterialHistory& history, const MaterialParams& block, const Params& p, BlockRange range, double dt) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  KernelFields s;
  s.bond[0] = history.bond[0].data();
  s.bond[1] = history.bond[1].data();
  double* back = history.bond[0].data();
  double* previous = history.bond[1].data();
  const double tau = p.relaxation_time;
  const MaxwellStep maxwell(tau, dt);
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double dashpot = p.relaxing_fraction * p.alpha_deviatoric * ctx.inverse_weighted_volume[i] / tau;
      double dissipated = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double ed = mechanical_extension(ctx, i, g) - theta[i] * g.xi * p.inverse_dilatation_factor;
        if (dt > 0) {  // (V4)
          const double integral = maxwell.integral((ed - previous[b]) / dt, previous[b] - back[b]);
          dissipated += dashpot * influence(block.influence, g.xi, block.horizon) * integral * neighbor_volume(ctx, i, j, g.xi);
        }
        back[b] = back_extension(p, s, b, ed);  // reads bond b only, then overwrites it
        previous[b] = ed;
      }
      history.dissipation[i] += dissipated;
    }
  });
}

// The page of `peridot info --model lps_viscoelastic` (docs/models/lps_viscoelastic.md). The equations
// restate the header comment; keep them in step with the code.
ModelInfo LpsViscoelastic::info() {
  ModelDoc doc{
    .summary = R"(Mitchell's nonlocal standard linear solid: the lps model whose deviatoric response is an equilibrium
spring in parallel with a Maxwell branch (a spring and a dashpot) that carries the fraction λ_i of the
deviatoric stiffness and relaxes with time constant τ_b. Every bond keeps a back extension; it is advanced by
the exact integral of its evolution equation for an extension that varies linearly over the step, so the
viscous part never limits the time step. The bulk response stays elastic.)",
    .equations = R"(Notation as on the lps page; e^b the back extension of a bond (0 at t = 0), λ_i the relaxing fraction,
τ_b the relaxation time, ε = exp(−Δt/τ_b), β = 1 − (τ_b/Δt)(1 − ε).

- (V1) t = (ω/m)[α_v θ ξ + α_d ((1 − λ_i) e^d + λ_i (e^d − e^b))], e^d = e − θξ/n
- (V2) ė^b = (e^d − e^b)/τ_b
- (V3) e^b_{n+1} = ε e^b_n + (1 − ε) e^d_n + β (e^d_{n+1} − e^d_n), exact for e^d linear in time over the step
- (V4) dissipation D = Σ (λ_i α_d ω/(m τ_b)) ∫ (e^d − e^b)² dt V, integrated exactly for the same e^d(t)
- (V5) stored energy W = α_v θ²/(2n) + (α_d/2m) Σ ω [(1 − λ_i)(e^d)² + λ_i (e^d − e^b)²] V

The instantaneous (glassy) deviatoric stiffness is α_d and the relaxed one (1 − λ_i)α_d: under a held
deviatoric extension a bond force relaxes as (1 − λ_i) + λ_i exp(−t/τ_b). The history output `dissipation`
is D per unit volume.)",
    .restrictions = R"(- One relaxation time: a Prony series of several branches is not available.
- The bulk response is elastic (no volumetric relaxation) and the model has no temperature dependence.
- The time step limit is that of lps (the glassy stiffness); the viscous part is unconditionally stable.
- 16 bytes of history (back extension and last deviatoric extension) and 4 bytes of partner-bond index per
  bond, and one more pass over the bonds after the force (the commit).
- Damage, when given, uses the total stretch; m is not updated when bonds break, and, as for lps, the force
  on a damaged family is not the exact gradient of W.)",
    .further_references = {"Mitchell, A non-local, ordinary-state-based viscoelasticity model for peridynamics, SAND2011-8064 (2011)"},
    .example = R"(materials:
  polymer:
    model: lps_viscoelastic
    density: 1.2 g/cm^3
    youngs_modulus: 3 GPa
    poisson_ratio: 0.35
    relaxing_fraction: 0.6
    relaxation_time: 20 us)",
  };
  return {.name = name,
          .description = "viscoelastic ordinary state-based solid (Mitchell standard linear solid)",
          .reference = "Mitchell, SAND2011-8064 (2011)",
          .keys = {{.key = "relaxing_fraction", .range = {0, 1, false, false},
                    .description = "λ_i: share of the deviatoric stiffness that relaxes (Peridigm 'lambda_i')",
                    .required = true},
                   {.key = "relaxation_time", .unit = Unit::time, .range = positive,
                    .description = "τ_b (s): relaxation time of the back extension (Peridigm 'tau b')", .required = true},
                   thermal_expansion_key()},
          .doc = doc};
}

}  // namespace peridot
