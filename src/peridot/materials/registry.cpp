#include "peridot/materials/registry.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

namespace {

// The pages of `peridot info --model NAME` (docs/models/NAME.md). Equations restate the header comments of
// materials/pmb.hpp, lps.hpp and material.hpp/.cpp; keep them in step with the code.

ModelDoc pmb_doc() {
  return {
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

The integrals ∫₀^δ ω ξ^p dξ are evaluated in closed form for each influence function.)",
      .restrictions = R"(- Bond-based: ν is fixed to 1/4 in 3D and plane strain and to 1/3 in plane stress. poisson_ratio may be
  given only when it equals that value (within 10⁻³); for another ν use lps.
- Linear elastic up to bond failure; no plasticity or viscosity.
- The calibration assumes a full neighbourhood: points near a free surface have fewer bonds and respond
  more softly (no surface correction is applied).
- 2D decks use the forms (5) for the thickness h and the plane (stress or strain) of the discretization.)",
      .further_references = {},
      .example = R"(materials:
  glass:
    model: pmb
    density: 2.44 g/cm^3
    youngs_modulus: 72 GPa
    damage: {fracture_energy: 3.8 J/m^2})",
  };
}

ModelDoc lps_doc() {
  return {
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
(2, 2K′, 8G) in 2D, and W = α_v θ²/(2n) + (α_d/2m) Σ ω (e − θξ/n)² V; t = ∂W/∂e exactly.)",
      .restrictions = R"(- Needs the dilatation pass: every step computes θ of every point over its intact bonds before the
  forces, one more loop over the bonds than pmb.
- m is computed once from the bonds at set-up (bonds across a pre-crack are not among them) and is not
  updated when bonds break; broken bonds drop out of θ, the forces and the energy.
- On a damaged family (m over all bonds, θ over the intact ones, as in Peridigm) the force is not the exact
  gradient of W: it lacks the term −(15G/m) q ω ξ, q = Σ ω ξ e^d V / m, that lps_plastic includes.
- Linear elastic up to bond failure; for plasticity or viscosity see lps_plastic and lps_viscoelastic. No
  surface correction is applied: points
  within δ of a free surface have one-sided families and respond stiffer to stretching along the surface
  (measured in 2D plane stress, δ = 3.015Δx: the outer row stores 1.35 times the classical energy of a
  uniaxial stress, and a bar 16 points wide is 10 % stiffer than E).
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
}

ModelDoc lps_plastic_doc() {
  return {
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
}

ModelDoc lps_viscoelastic_doc() {
  return {
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
}

ModelDoc correspondence_doc() {
  return {
      .summary = R"(A non-ordinary state-based (correspondence) solid: each point's family gives it a nonlocal deformation
gradient F, a classical constitutive law turns the motion into a Cauchy stress, and the first Piola–Kirchhoff
stress is mapped back to bond forces. The law works in the unrotated frame of the Flanagan–Taylor polar
decomposition, so large rotations are objective. Two laws are available: hypoelastic (rate form of Hooke's
law) and Foster's J2 viscoplasticity (power-law strain hardening and rate sensitivity, radial return with an
implicit rate term), fitted in the reference to 6061-T6 aluminium. A weak bond spring on the non-affine part
of each bond's deformation controls the zero-energy (hourglass) modes.)",
      .equations = R"(Notation: ξ the reference bond, Y = ξ + u′ − u the deformed bond, ω the influence function times the
partial-volume factor, V the neighbour volume; sums run over a point's bonds. Numbers (N) are those of
Foster, Silling & Chen (2010).

- (10) shape tensor K = Σ ω ξ⊗ξ V; (13) F = [Σ ω Y⊗ξ V] K⁻¹ and Ḟ = [Σ ω (v′ − v)⊗ξ V] K⁻¹ from u^{n+1}
  and the mid-step velocity v^{n+½}
- (14) L = Ḟ F⁻¹ at mid-step, F^{n+½} = F^{n+1} − ½Δt Ḟ; (15) D, W its symmetric and skew parts
- (16–18) Flanagan–Taylor: F = V R, R_{n+1} = Q R_n with the Cayley increment Q, and d = Rᵀ D R
- hypoelastic law: τ_{n+1} = τ_n + Δt (λ tr(d) I + 2G d), λ = K − ⅔G
- J2 law: flow stress G(εp, ε̇p) = Y (1 + εp/ε0)^(1/n) (1 + ε̇p/ε̇0)^(1/m) (58–59); trial S^tr = S_n + 2G dev(d)Δt
  (49); elastic when |S^tr| ≤ √(2/3) G(εp_n, 0); otherwise Δλ solves |S^tr| − 2GΔλ − √(2/3) G(εp_n, √(2/3)Δλ/Δt) = 0
  (60) and S = √(2/3) G S^tr/|S^tr| (50, 61); pressure p_{n+1} = p_n + K tr(d)Δt (52); εp from (56–57)
- J2 with `thermal_softening` (not in Foster et al., who drop temperature): G is multiplied by the Johnson–Cook
  factor Θ = 1 − T*^q, T* = (T_n − T_r)/(T_m − T_r) clamped to [0, 1], the temperature of the previous step;
  adiabatic heating T_{n+1} = T_n + β G Δεp/(ρc) (no conduction: heat moves √(κt) ≈ 0.06 mm in 50 µs in
  aluminium), T_0 = T_r; output `temperature` (K)
- (23) σ = R τ Rᵀ; (24) P = det(F) σ F⁻ᵀ; (25) force state T⟨ξ⟩ = ω P K⁻¹ ξ; (4) f = Σ (T⟨ξ⟩ − T′⟨−ξ⟩) V
- hourglass state T^hg⟨ξ⟩ = ω (c_hg/|ξ|) ((Y − Fξ)·n) n, n = Y/|Y|, c_hg = 18 C_HG K/(πδ⁴)
  (docs/algorithms.md §7); C_HG is hourglass_coefficient
- hourglass damping (optional) T^hv⟨ξ⟩ = ω (c_hv/|ξ|) (ż·n) n, ż = (v′ − v) − Ḟξ the rate of Y − Fξ,
  c_hv = 18 C_HV √(ρK)/(πδ³): the same bond with K replaced by a viscosity C_HV ρ c δ, c = √(K/ρ). The springs
  hold a zero-energy mode but store its energy, so an impact leaves it ringing; the dashpots dissipate it.
  Damping ratio of the checkerboard mode ≈ 2.1 C_HV/√C_HG (about 0.3 measured at C_HV = C_HG = 0.02); C_HV is
  hourglass_viscosity
- (62) Green–Lagrange strain E = ½(FᵀF − I), an output only

Energy bookkeeping (history CSV): strain_energy is the elastic energy Σ J (p²/(2K) + S:S/(4G)) V;
dissipated_energy the inelastic work Σ ∫ J S : (dev(d) − Ṡ/(2G)) dt V (the plastic work of J2, 0 for the
hypoelastic law); hourglass_work the work of the hourglass forces (springs and dashpots),
−Σ ½(f_hg^n + f_hg^{n+1})·Δu V per step.
With the kinetic energy they balance the external work. Exodus output adds deformation_gradient_*,
cauchy_stress_*, von_mises_stress, green_lagrange_strain_*, equivalent_plastic_strain and dissipation.

Stable time step: the Silling–Askari bound with c = 18 [max(K, M/1.8) + C_HG K]/(πδ⁴), M = K + 4G/3 the
P-wave modulus: the PMB solid with the same wave speed (a PMB solid has M = 1.8K), never softer than the
PMB solid of the same K, stiffened by the hourglass springs. With hourglass dashpots it is multiplied by
√(1 + ζ²) − ζ, ζ = (c_hv/c)/Δt_SA (central differences with damping ratio ζ on the highest mode: 0.81 for
the Taylor example, aluminium at δ = 3.015Δx with C_HV = 0.05). It is an estimate, scaled by solver.safety_factor.)",
      .restrictions = R"(- 3D only.
- No damage: bond failure inside K, F and the force state is not implemented (a deck with damage is refused).
- A correspondence body may share bonds with another correspondence body, but not with a body of another
  model: the run stops at set-up naming both bodies. Keep such bodies more than a horizon apart.
- Rate form: an initial displacement produces no stress (the stress integrates the motion from t = 0).
- Zero-energy modes are held only by the hourglass springs (hourglass_coefficient 0 lets them grow) and
  damped only by the hourglass dashpots (hourglass_viscosity 0, the default: an excited mode rings on).
- K⁻¹ is recomputed every step (the eigenvalue check refuses a point whose family is nearly flat, λ_min/λ_max
  below 10⁻⁸, with the point named).)",
      .further_references = {"Flanagan & Taylor, CMAME 62 (1987) 305-320 (incremental rotation)",
                             "Littlewood, Peridigm hourglass control (docs/algorithms.md §7)"},
      .example = R"(materials:
  aluminium:
    model: correspondence
    density: 2.7 g/cm^3
    youngs_modulus: 68.9 GPa
    poisson_ratio: 0.333
    constitutive_law: j2_viscoplastic
    yield_stress: 276 MPa
    hardening_exponent: 13.5
    reference_plastic_strain: 0.001
    rate_exponent: 44
    reference_strain_rate: 1000 1/s)",
  };
}

}  // namespace

const std::vector<ModelInfo>& material_models() {
  static const std::vector<ModelInfo> models = {
      {"pmb", ModelKind::pmb, "prototype microelastic brittle: bond-based, pairwise linear springs",
       "Silling & Askari, Comput. Struct. 83 (2005) 1526-1535", true, {}, pmb_doc()},
      {"lps", ModelKind::lps, "linear peridynamic solid: ordinary state-based, any Poisson ratio",
       "Silling, Epton, Weckner, Xu & Askari, J. Elasticity 88 (2007) 151-184", false, {}, lps_doc()},
      {"lps_plastic", ModelKind::lps_plastic, "elastic-plastic ordinary state-based solid (Mitchell), linear hardening",
       "Mitchell, SAND2011-3166 (2011)", false,
       {{.key = "yield_stress", .unit = Unit::pressure, .range = positive,
         .description = "uniaxial yield stress σ_y (Pa)", .required = true},
        {.key = "hardening_modulus", .unit = Unit::pressure, .default_yaml = "0", .range = non_negative,
         .description = "linear hardening H (Pa): σ_Y = σ_y + H ε̄p; 0 = perfectly plastic"}},
       lps_plastic_doc()},
      {"lps_viscoelastic", ModelKind::lps_viscoelastic,
       "viscoelastic ordinary state-based solid (Mitchell standard linear solid)", "Mitchell, SAND2011-8064 (2011)",
       false,
       {{.key = "relaxing_fraction", .range = {0, 1, false, false},
         .description = "λ_i: share of the deviatoric stiffness that relaxes (Peridigm 'lambda_i')", .required = true},
        {.key = "relaxation_time", .unit = Unit::time, .range = positive,
         .description = "τ_b (s): relaxation time of the back extension (Peridigm 'tau b')", .required = true}},
       lps_viscoelastic_doc()},
      {"correspondence", ModelKind::correspondence,
       "non-ordinary state-based (correspondence) solid: hypoelastic or J2 viscoplastic law, hourglass control",
       "Foster, Silling & Chen, IJNME 81 (2010) 1242-1258", false,
       {{.key = "constitutive_law", .type = ValueType::choice, .description = "the law in the unrotated frame",
         .required = true, .choices = {"hypoelastic", "j2_viscoplastic"}},
        {.key = "yield_stress", .unit = Unit::pressure, .range = positive,
         .description = "Y (Pa), quasi-static yield stress; j2_viscoplastic (required there)"},
        {.key = "hardening_exponent", .range = positive,
         .description = "n (-): G ∝ (1 + εp/ε0)^(1/n); j2_viscoplastic; omit for no strain hardening"},
        {.key = "reference_plastic_strain", .range = positive,
         .description = "ε0 (-), with hardening_exponent; j2_viscoplastic"},
        {.key = "rate_exponent", .range = positive,
         .description = "m (-): G ∝ (1 + ε̇p/ε̇0)^(1/m); j2_viscoplastic; omit for rate independence"},
        {.key = "reference_strain_rate", .unit = Unit::rate, .range = positive,
         .description = "ε̇0 (1/s), with rate_exponent; j2_viscoplastic"},
        {.key = "thermal_softening", .type = ValueType::mapping,
         .description = "adiabatic heating and Johnson–Cook thermal softening (see materials.<name>.thermal_softening); "
                        "j2_viscoplastic; omit for none"},
        {.key = "hourglass_coefficient", .default_yaml = "0.05", .range = non_negative,
         .description = "C_HG (-): hourglass bond stiffness 18 C_HG K/(πδ⁴); 0 = no control"},
        {.key = "hourglass_viscosity", .default_yaml = "0", .range = non_negative,
         .description = "C_HV (-): viscous hourglass damping, a bond dashpot 18 C_HV √(ρK)/(πδ³) on the non-affine "
                        "stretch rate; 0 = none (elastic control only)"}},
       correspondence_doc(), 3},
  };
  return models;
}

const ModelInfo* find_model(std::string_view name) {
  for (const ModelInfo& model : material_models())
    if (model.name == name) return &model;
  return nullptr;
}

const ModelInfo& model_info(ModelKind kind) {
  for (const ModelInfo& model : material_models())
    if (model.kind == kind) return model;
  PERIDOT_REQUIRE(false, "model kind missing from the registry");
}

std::vector<std::string_view> model_names() {
  std::vector<std::string_view> names;
  for (const ModelInfo& model : material_models()) names.push_back(model.name);
  return names;
}

std::vector<KeySpec> common_material_keys() {
  return {
      {.key = "model", .type = ValueType::choice, .description = "material model (see the model list)", .required = true,
       .choices = model_names()},
      {.key = "density", .unit = Unit::density, .range = positive, .description = "mass density ρ (kg/m^3)", .required = true},
      {.key = "bulk_modulus", .unit = Unit::pressure, .range = positive, .description = "K (Pa)"},
      {.key = "shear_modulus", .unit = Unit::pressure, .range = positive, .description = "G (Pa)"},
      {.key = "youngs_modulus", .unit = Unit::pressure, .range = positive, .description = "E (Pa)"},
      {.key = "poisson_ratio", .range = {-1, 0.5, true, true},
       .description = "ν; give any two of K, G, E, ν (bond-based models: one modulus, ν is implied)"},
      {.key = "influence", .type = ValueType::choice, .default_yaml = "constant",
       .description = "influence function ω: 1, δ/|ξ| or exp(-|ξ|²/δ²)", .choices = {"constant", "inverse_distance", "gaussian"}},
      {.key = "damage", .type = ValueType::mapping, .description = "bond breaking (see materials.<name>.damage); omit for none"},
  };
}

std::vector<KeySpec> material_keys(const ModelInfo& model) {
  std::vector<KeySpec> keys = common_material_keys();
  keys.insert(keys.end(), model.extra_keys.begin(), model.extra_keys.end());
  return keys;
}

std::vector<KeySpec> damage_keys() {
  return {
      {.key = "critical_stretch", .range = positive, .description = "bond breaks beyond this stretch s0",
       .required = true, .one_of = "criterion"},
      {.key = "fracture_energy", .unit = Unit::energy_per_area, .range = positive,
       .description = "G0 (J/m^2); s0 then follows from K and δ", .required = true, .one_of = "criterion"},
  };
}

std::vector<KeySpec> thermal_softening_keys() {
  return {
      {.key = "specific_heat", .unit = Unit::specific_heat, .range = positive,
       .description = "c (J/(kg K)), specific heat at constant pressure", .required = true},
      {.key = "reference_temperature", .unit = Unit::temperature, .range = positive,
       .description = "T_r (K): the initial temperature, where the thermal factor is 1", .required = true},
      {.key = "melting_temperature", .unit = Unit::temperature, .range = positive,
       .description = "T_m (K): the thermal factor is 0 there; above reference_temperature", .required = true},
      {.key = "exponent", .range = positive, .description = "q (-): thermal factor 1 − T*^q, Johnson–Cook's m",
       .required = true},
      {.key = "taylor_quinney_coefficient", .default_yaml = "0.9", .range = {0, 1, false, false},
       .description = "β (-): share of the plastic work that heats the point"},
  };
}

std::string_view damage_doc() {
  return R"(A bond breaks, irreversibly, once its stretch s = (|Y| − ξ)/ξ exceeds the critical stretch s0; compression
never breaks a bond. A bond between two blocks uses the smaller of their s0 (a block without damage counts as
+∞); bonds touching a point of a no_fail node set never break. A broken bond carries no force and no
energy. The damage of a point is the volume-weighted fraction of its broken bonds,
φ = 1 − (intact neighbour volume)/(all neighbour volume). Bonds crossing a pre-crack are never created.

s0 is given (critical_stretch) or follows from the fracture energy G0 (fracture_energy), the work to break
every bond crossing a unit crack area, with the bond-based micromodulus c0 of the material's K and influence
function (equations (4) and (5) of the pmb page):

- (D1) 3D: G0 = (π c0 s0²/2) ∫₀^δ ω ξ⁴ dξ, so s0 = √(5G0/(9Kδ)) for ω = 1
- (D2) 2D, thickness h: G0 = h c0 s0² ∫₀^δ ω ξ³ dξ, so s0 = √(πG0/(3K′δ)) for ω = 1)";
}

double bond_based_poisson_ratio(int dimension, PlaneKind plane) {
  return dimension == 2 && plane == PlaneKind::stress ? 1.0 / 3.0 : 0.25;
}

}  // namespace peridot
