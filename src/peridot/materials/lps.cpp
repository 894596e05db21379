#include "peridot/materials/lps.hpp"

// KeySpecs and ModelInfo are written with designated initializers that leave the other fields at their
// defaults on purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/model_context.hpp"
#include "peridot/materials/models.hpp"

namespace peridot {

using namespace bond_loop;

LpsConstants lps_constants(const ElasticConstants& elastic, const Problem& problem) {
  if (problem.dimension == 3) return {3 * elastic.bulk_modulus, 15 * elastic.shear_modulus, 3, 1.0 / 3};
  return {2 * planar_bulk_modulus(elastic, problem.plane), 8 * elastic.shear_modulus, 2, 0.5};
}

Lps::Params Lps::resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block) {
  Params p{lps_constants(spec.elastic, problem)};
  p.surface_correction = block.surface_correction;
  return p;
}

void Lps::calibrate(ModelContext& ctx, const MaterialParams& block, const Params& p, BlockRange range) {
  if (!p.surface_correction) return;
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double scaled = 0;  // m̃
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j);
        scaled += influence(block.influence, xi, block.horizon) * bond_scale(ctx, block, b) * xi * xi *
                  neighbor_volume(ctx, i, j, xi);
      }
      ctx.point_constants[0][i] = 2 - scaled * ctx.inverse_weighted_volume[i];
    }
  });
}

// The page of `peridot info --model lps` (docs/models/lps.md). The equations restate the header comment;
// keep them in step with the code.
ModelInfo Lps::info() {
  ModelDoc doc{
    .summary = R"(An ordinary state-based model: the force of a bond depends on the stretch of that bond and on the
dilatation θ of each of its end points, a weighted sum over all their bonds. The volumetric and deviatoric
responses are separate, so any two elastic constants (any Poisson ratio in (−1, 0.5)) can be matched. A
bond carries the force states of both its ends, each with that point's own θ and weighted volume m.)",
    .equations = R"(Notation: ξ = |x′ − x| the reference bond length, e = |y′ − y| − ξ its extension, ω(ξ) the influence
function (1, δ/ξ or exp(−ξ²/δ²)), V the neighbour volume; sums run over a point's intact bonds.

3D (Silling et al. 2007):

- (1) weighted volume: m = Σ ω ξ² V, computed once in the reference configuration
- (2) dilatation: θ = (3/m) Σ ω ξ e V
- (3) scalar force state: t = (3Kθ/m) ω ξ + (15G/m) ω e^d, with e^d = e − θξ/3
- (4) energy density: W = Kθ²/2 + (15G/2m) Σ ω (e^d)² V

2D, thickness h, V = h × area (docs/algorithms.md §3):

- (5) dilatation: θ₂ = (2/m) Σ ω ξ e V, which equals ε₁₁ + ε₂₂ for a homogeneous strain
- (6) scalar force state: t = (ω/m)[2K′ θ₂ ξ + 8G (e − θ₂ξ/2)]
- (7) energy density: W = K′θ₂²/2 + (4G/m) Σ ω (e − θ₂ξ/2)² V,
  with K′ = K + G/3 in plane strain and 9KG/(3K + 4G) in plane stress

One form covers both: t = (ω/m)[α_v θ ξ + α_d (e − θξ/n)] with (n, α_v, α_d) = (3, 3K, 15G) in 3D and
(2, 2K′, 8G) in 2D, and W = α_v θ²/(2n) + (α_d/2m) Σ ω (e − θξ/n)² V; t = ∂W/∂e exactly.

With surface_correction (docs/algorithms.md §15), each bond's ω is multiplied by its factor G (ω̃ = G ω) in θ, the
force and W, while m stays the reference Σ ω ξ² V:

- (8) t = (ω̃/m)[α_v θ ξ + α_d (e − κ θξ/n)], κ = 2 − m̃/m, m̃ = Σ ω̃ ξ² V, which is ∂W/∂e of the same W with ω̃.)",
    .restrictions = R"(- Needs the dilatation pass: every step computes θ of every point over its intact bonds before the
  forces, one more loop over the bonds than pmb.
- m is computed once from the bonds at set-up (bonds across a pre-crack are not among them) and is not
  updated when bonds break; broken bonds drop out of θ, the forces and the energy.
- On a damaged family (m over all bonds, θ over the intact ones, as in Peridigm) the force is not the exact
  gradient of W: it lacks the term −(15G/m) q ω ξ, q = Σ ω ξ e^d V / m, that lps_plastic includes.
- Linear elastic up to bond failure; for plasticity or viscosity see lps_plastic and lps_viscoelastic.
- Points within δ of a free surface have one-sided families and respond stiffer to stretching along the surface
  (2D plane stress, δ = 3.015Δx: the outer row stores 1.35 times the classical energy of a uniaxial stress, and
  a bar 16 points wide carries waves 5.3 % faster than √(E/ρ)). `surface_correction: true` scales each bond by
  the energy method (docs/algorithms.md §15): the bar's wave speed is then within 1.3 %. The correction keeps
  t = ∂W/∂e (force (8) below) and is computed once at set-up.
- On a lattice the deviatoric sum is a quadrature: at δ = 3.015Δx the interior energy of a general strain
  is off by 1–2.5 %; δ = 4.015Δx with partial_volume: extended brings it within 1 %.
- The critical stretch derived from fracture_energy uses the bond-based (pmb) micromodulus of the same K,
  as is usual; it is not an energy release rate computed for the state-based model.
- The stable time step is the Silling–Askari bound of the pmb model with the same bulk modulus and ω = 1;
  for lps it is only an estimate, scaled by solver.safety_factor (default 0.8).
- 2D decks use the forms (5)–(7) for the thickness h and the plane (stress or strain) of the discretization.)",
    .further_references = {"Silling & Askari, Comput. Struct. 83 (2005) 1526-1535 (critical-stretch bond failure)"},
    .example = R"(materials:
  aluminium:
    model: lps
    density: 2.7 g/cm^3
    youngs_modulus: 69 GPa
    poisson_ratio: 0.33
    influence: inverse_distance
    damage: {critical_stretch: 0.005})",
  };
  return {.name = name,
          .description = "linear peridynamic solid: ordinary state-based, any Poisson ratio",
          .reference = "Silling, Epton, Weckner, Xu & Askari, J. Elasticity 88 (2007) 151-184",
          .keys = {thermal_expansion_key(), surface_correction_key()},
          .doc = doc};
}

}  // namespace peridot
