#include "peridot/materials/pmb.hpp"

// KeySpecs and ModelInfo are written with designated initializers that leave the other fields at their
// defaults on purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

Pmb::Params Pmb::resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block) {
  return {bond_based_micromodulus(spec.elastic, block.horizon, spec.influence, problem)};
}

// The page of `peridot info --model pmb` (docs/models/pmb.md). The equations restate the header comment;
// keep them in step with the code.
ModelInfo Pmb::info() {
  ModelDoc doc{
    .summary = R"(Every bond is a linear spring between two points: its force depends on its own stretch only, not on
the other bonds of either point. Peridot calibrates the micromodulus from the bulk modulus, so that an
isotropic strain of a point with a full neighbourhood stores the classical strain energy; the shear
response then follows and fixes the Poisson ratio, so the deck gives one modulus.)",
    .equations = R"(Notation: ξ = |x′ − x| the reference bond length, Y = y′ − y the deformed bond, δ the horizon,
V the neighbour volume, ω(ξ) the influence function (1, δ/ξ or exp(−ξ²/δ²)).

- (1) bond stretch: s = (|Y| − ξ)/ξ
- (2) pair force density: f = c(ξ) s Y/|Y| with c(ξ) = c0 ω(ξ); each end carries half, T⟨ξ⟩ = f/2
- (3) pair energy w = ½ c(ξ) s² ξ; a point's energy density W = Σ ½ w V (half the energy of each of its bonds)
- (4) 3D calibration, W = 9Ks²/2 for an isotropic stretch s: c0 = 9K / (2π ∫₀^δ ω ξ³ dξ), which is 18K/(πδ⁴) for ω = 1
- (5) 2D calibration, thickness h, W = 2K′s²: c0 = 4K′ / (πh ∫₀^δ ω ξ² dξ), which is 12K′/(πhδ³) for ω = 1,
  with K′ = K + G/3 in plane strain and 9KG/(3K + 4G) = E/(2(1 − ν)) in plane stress
- (6) 1D calibration, a bar of area A, W = Eε²/2 for a uniform strain ε: c0 = E / (A ∫₀^δ ω ξ dξ), which is
  2E/(Aδ²) for ω = 1

The integrals ∫₀^δ ω ξ^p dξ are evaluated in closed form for each influence function.)",
    .restrictions = R"(- Bond-based: ν is fixed to 1/4 in 3D and plane strain and to 1/3 in plane stress. poisson_ratio may be
  given only when it equals that value (within 10⁻³); for another ν use lps.
- Linear elastic up to bond failure; no plasticity or viscosity.
- The calibration assumes a full neighbourhood: points near a free surface have fewer bonds and respond
  more softly (a 3D block of 9³ points stores 32 % less than the classical energy of a uniaxial strain).
  `surface_correction: true` scales each pair's micromodulus by the energy method's factor G (docs/algorithms.md
  §15; c0 ω G): the block's energy is then within 0.7 %.
- 2D decks use the forms (5) for the thickness h and the plane (stress or strain) of the discretization; 1D
  decks the form (6) for the bar's area A, with Young's modulus alone (no ν).)",
    .further_references = {},
    .example = R"(materials:
  glass:
    model: pmb
    density: 2.44 g/cm^3
    youngs_modulus: 72 GPa
    damage: {fracture_energy: 3.8 J/m^2})",
  };
  return {.name = name,
          .description = "prototype microelastic brittle: bond-based, pairwise linear springs",
          .reference = "Silling & Askari, Comput. Struct. 83 (2005) 1526-1535",
          .bond_based = true,
          .keys = {thermal_expansion_key(), surface_correction_key()},
          .doc = doc,
          .one_dimensional = true};
}

}  // namespace peridot
