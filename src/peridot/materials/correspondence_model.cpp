#include "peridot/materials/correspondence_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "peridot/correspondence/force.hpp"
#include "peridot/deck/map_reader.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

CorrespondenceModel::Params CorrespondenceModel::resolve(const MaterialSpec& spec, const Problem&, MaterialParams& block) {
  const Parameters& q = spec.parameters;
  Params p{correspondence::make_law(q.text("constitutive_law"), q, spec.elastic, spec.density),
           q.number("hourglass_coefficient"), q.number("hourglass_viscosity"), q.number("bulk_viscosity_linear"),
           q.number("bulk_viscosity_quadratic")};
  // Stable time step (docs/models/correspondence.md): the Silling–Askari bound of the PMB solid with the
  // same P-wave modulus M = K + 4G/3 (a PMB solid, ν = 1/4, has M = 1.8K), but never less stiff than the
  // PMB solid of the same K, plus the hourglass bond stiffness c_hg = 18 C_HG K/(πδ⁴) (force.hpp):
  //   c = 18 [max(K, M/1.8) + C_HG K] / (π δ⁴).
  const double K = spec.elastic.bulk_modulus, M = K + 4 * spec.elastic.shear_modulus / 3;
  block.stable_micromodulus =
      18 * (std::max(K, M / 1.8) + p.hourglass_coefficient * K) / (std::numbers::pi * std::pow(block.horizon, 4));
  block.stable_damping = correspondence::hourglass_damping(p.hourglass_viscosity, spec.density, K, block.horizon);
  block.stable_bulk_viscosity = p.bulk_viscosity_linear;
  block.damage_breaks_bonds = std::visit([](const auto& law) {
    if constexpr (requires { law.damage.degrades_bonds(); }) return law.damage.degrades_bonds();
    else return false;
  }, p.law);
  return p;
}

namespace {

bool has_key(const std::vector<KeySpec>& keys, std::string_view key) {
  return std::any_of(keys.begin(), keys.end(), [&](const KeySpec& k) { return k.key == key; });
}

}  // namespace

void CorrespondenceModel::check(const MapReader& r, const Parameters& q, DeckContext& ctx) {
  if (r.given("damage"))
    ctx.error(r["damage"].key_pos, r.path_of("damage"),
              "the correspondence model breaks bonds through its law's johnson_cook_damage (the influence function "
              "degrades with the damage of both ends), not by a critical stretch or energy; remove damage");
  if (!r.given("constitutive_law")) return;  // missing or not a listed law: reported
  const std::string chosen = r["constitutive_law"].text;
  std::vector<KeySpec> own;
  correspondence::ConstitutiveLaws::for_each([&](auto law) {
    if (decltype(law)::name == chosen) own = decltype(law)::keys();
  });
  // A key of another law only (reported once, with the first law that has it).
  std::vector<std::string_view> reported;
  correspondence::ConstitutiveLaws::for_each([&](auto law) {
    using Law = decltype(law);
    if (Law::name == chosen) return;
    for (const KeySpec& k : Law::keys())
      if (r.given(k.key) && !has_key(own, k.key) &&
          std::find(reported.begin(), reported.end(), k.key) == reported.end()) {
        reported.push_back(k.key);
        ctx.error(r[k.key].key_pos, r.path_of(k.key),
                  fmt::format("{} is a parameter of constitutive_law: {}, not of {}", k.key, Law::name, chosen));
      }
  });
  for (const KeySpec& k : own)
    if (k.required && !r.present(k.key))
      ctx.error(r["constitutive_law"].pos, r.path(), fmt::format("constitutive_law: {} needs {}", chosen, k.key));
  correspondence::ConstitutiveLaws::for_each([&](auto law) {
    using Law = decltype(law);
    if constexpr (requires { &Law::check; })
      if (Law::name == chosen) Law::check(r, q, ctx);
  });
}

// The page of `peridot info --model correspondence` (docs/models/correspondence.md). The equations restate
// the header comments of correspondence/; keep them in step with the code.
ModelInfo CorrespondenceModel::info() {
  std::vector<std::string_view> laws = correspondence::law_names();
  std::vector<KeySpec> keys = {
      {.key = "constitutive_law", .type = ValueType::choice, .description = "the law in the unrotated frame",
       .required = true, .choices = laws},
      {.key = "hourglass_coefficient", .default_yaml = "0.05", .range = non_negative,
       .description = "C_HG (-): hourglass bond stiffness 18 C_HG K/(πδ⁴); 0 = no control"},
      {.key = "hourglass_viscosity", .default_yaml = "0", .range = non_negative,
       .description = "C_HV (-): viscous hourglass damping, a bond dashpot 18 C_HV √(ρK)/(πδ³) on the non-affine "
                      "stretch rate; 0 = none (elastic control only)"},
      {.key = "bulk_viscosity_linear", .default_yaml = "0", .range = non_negative,
       .description = "C_l (-): linear bulk viscosity of shocks, q = C_l ρ c ℓ |tr D| in compression (c the P-wave "
                      "speed, ℓ = V^(1/3)); hydrocodes use 0.06; 0 = none"},
      {.key = "bulk_viscosity_quadratic", .default_yaml = "0", .range = non_negative,
       .description = "C_q (-): quadratic bulk viscosity of shocks, q = C_q ρ ℓ² (tr D)² in compression; hydrocodes "
                      "use 1.5; 0 = none"}};
  std::vector<SectionSpec> sections;
  correspondence::ConstitutiveLaws::for_each([&](auto law) {
    using Law = decltype(law);
    for (KeySpec k : Law::keys())  // required only with its law: CorrespondenceModel::check
      if (!has_key(keys, k.key)) {
        k.required = false;
        keys.push_back(k);
      }
    if constexpr (requires { Law::sections(); })
      for (const SectionSpec& section : Law::sections()) sections.push_back(section);
  });
  ModelDoc doc{
    .summary = R"(A non-ordinary state-based (correspondence) solid: each point's family gives it a nonlocal deformation
gradient F, a classical constitutive law turns the motion into a Cauchy stress, and the first Piola–Kirchhoff
stress is mapped back to bond forces. The law works in the unrotated frame of the Flanagan–Taylor polar
decomposition, so large rotations are objective. Three laws are available: hypoelastic (rate form of Hooke's
law), Foster's J2 viscoplasticity (power-law strain hardening and rate sensitivity, radial return with an
implicit rate term), fitted in the reference to 6061-T6 aluminium, and Johnson–Cook plasticity. A weak bond spring on the non-affine part
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
- Johnson–Cook law: σ_y(εp, ε̇p, T) = (A + B εp^n)(1 + C ln ε̇*)(1 − T*^m), ε̇* = max(ε̇p/ε̇0, 1), A = yield_stress,
  B, n, C = strain_hardening_coefficient, strain_hardening_exponent, strain_rate_coefficient, m the exponent of
  `thermal_softening` (T of the previous step); elastic when |S^tr| ≤ √(2/3) σ_y(εp_n, 0); otherwise Δλ solves
  |S^tr| − 2GΔλ − √(2/3) σ_y(εp_n + √(2/3)Δλ, √(2/3)Δλ/Δt) = 0 (implicit in εp and its rate), S = (|S^tr| − 2GΔλ)
  S^tr/|S^tr|, Δεp = √(2/3)Δλ; pressure and heating as the J2 law
- `johnson_cook_damage` (j2_viscoplastic and johnson_cook): D_{n+1} = min(1, D_n + Δεp/εf),
  εf = [D1 + D2 exp(D3 η)][1 + D4 ln ε̇*][1 + D5 T*], η = p/σ_vm of the returned stress (Johnson & Cook 1985).
  coupling influence_function (default; Tupek, Rimoli & Radovitzky 2013): every bond's ω in K, F and the force
  state is ω0 (1 − max(D_i, D_j)); the bond breaks for good when that reaches 0, so a point at D = 1 loses every
  bond and flies free with no stress; a point whose remaining bonds can no longer form K fails too (D = 1), and a
  failing point's stored elastic energy is added to dissipated_energy. Bonds touching a no_fail point keep their
  weight. coupling local_stress: the force state uses (1 − D) σ and no bond breaks (the classical coupling the
  paper shows to localise in one row of points). Output `material_damage` (D); `damage` stays the fraction of
  broken bonds
- (23) σ = R τ Rᵀ; (24) P = det(F) σ F⁻ᵀ; (25) force state T⟨ξ⟩ = ω P K⁻¹ ξ; (4) f = Σ (T⟨ξ⟩ − T′⟨−ξ⟩) V
- hourglass state T^hg⟨ξ⟩ = ω (c_hg/|ξ|) ((Y − Fξ)·n) n, n = Y/|Y|, c_hg = 18 C_HG K/(πδ⁴)
  (docs/algorithms.md §7); C_HG is hourglass_coefficient
- hourglass damping (optional) T^hv⟨ξ⟩ = ω (c_hv/|ξ|) (ż·n) n, ż = (v′ − v) − Ḟξ the rate of Y − Fξ,
  c_hv = 18 C_HV √(ρK)/(πδ³): the same bond with K replaced by a viscosity C_HV ρ c δ, c = √(K/ρ). The springs
  hold a zero-energy mode but store its energy, so an impact leaves it ringing; the dashpots dissipate it.
  Damping ratio of the checkerboard mode ≈ 2.1 C_HV/√C_HG (about 0.3 measured at C_HV = C_HG = 0.02); C_HV is
  hourglass_viscosity
- bulk (shock) viscosity (optional; von Neumann–Richtmyer with a linear term, as hydrocodes apply it): while a point
  is compressed (tr D < 0) its stress gains −q I, q = ρ ℓ (C_q ℓ (tr D)² − C_l c tr D), ℓ = V^(1/3) the point's
  size, c the P-wave speed √((K + 4G/3)/ρ); C_l and C_q are bulk_viscosity_linear and bulk_viscosity_quadratic
  (hydrocodes use 0.06 and 1.5; default 0: none). q is not part of the law's state; its work J q |tr D| Δt per
  reference volume is dissipated
- (62) Green–Lagrange strain E = ½(FᵀF − I), an output only

Energy bookkeeping (history CSV): strain_energy is the elastic energy Σ J (p²/(2K) + S:S/(4G)) V;
dissipated_energy the inelastic work Σ ∫ J S : (dev(d) − Ṡ/(2G)) dt V (the plastic work of the J2 and Johnson–Cook laws, 0 for the
hypoelastic law) plus the work of the bulk viscosity; hourglass_work the work of the hourglass forces (springs and dashpots),
−Σ ½(f_hg^n + f_hg^{n+1})·Δu V per step.
With the kinetic energy they balance the external work. Exodus output adds deformation_gradient_*,
cauchy_stress_* (the stress that acts: with −q I where a bulk viscosity is on), von_mises_stress,
green_lagrange_strain_*, equivalent_plastic_strain and dissipation.

Stable time step: the Silling–Askari bound with c = 18 [max(K, M/1.8) + C_HG K]/(πδ⁴), M = K + 4G/3 the
P-wave modulus: the PMB solid with the same wave speed (a PMB solid has M = 1.8K), never softer than the
PMB solid of the same K, stiffened by the hourglass springs. With hourglass dashpots it is multiplied by
√(1 + ζ²) − ζ, ζ = (c_hv/c)/Δt_SA (central differences with damping ratio ζ on the highest mode: 0.81 for
the Taylor example, aluminium at δ = 3.015Δx with C_HV = 0.05), and with a linear bulk viscosity by √(1 + C_l²) − C_l
(the quadratic term, which grows with the compression rate, is left to the safety factor). It is an estimate,
scaled by solver.safety_factor.)",
    .restrictions = R"(- 3D only.
- Bonds break only through a law's johnson_cook_damage; a critical-stretch or energy `damage` section is refused.
- Influence-function damage: a bond between two points that are both damaged but not failed keeps a weight of
  1 − max(D); across an opened crack such bridging bonds can remain (the fragment count then sees one piece),
  carrying the small force of their weight.
- A correspondence body may share bonds with another correspondence body, but not with a body of another
  model: the run stops at set-up naming both bodies. Keep such bodies more than a horizon apart.
- Rate form: an initial displacement produces no stress (the stress integrates the motion from t = 0).
- Zero-energy modes are held only by the hourglass springs (hourglass_coefficient 0 lets them grow) and
  damped only by the hourglass dashpots (hourglass_viscosity 0, the default: an excited mode rings on).
- K⁻¹ is recomputed every step (the eigenvalue check refuses a point whose family is nearly flat, λ_min/λ_max
  below 10⁻⁸, with the point named).)",
    .further_references = {"Flanagan & Taylor, CMAME 62 (1987) 305-320 (incremental rotation)",
                             "Johnson & Cook, Eng. Fract. Mech. 21 (1985) 31-48 (failure strain)",
                             "Tupek, Rimoli & Radovitzky, CMAME 263 (2013) 20-26 (damage through the influence function)",
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
  return {
      .name = name,
      .description = "non-ordinary state-based (correspondence) solid: hypoelastic, J2 viscoplastic or Johnson–Cook law, "
                     "Johnson–Cook damage, hourglass control",
      .reference = "Foster, Silling & Chen, IJNME 81 (2010) 1242-1258",
      // In the order the resolved deck writes them: the law, its hourglass control, then the laws' keys.
      .keys = keys,
      .sections = sections,
      .doc = doc,
      .dimension = 3,
      .check = &CorrespondenceModel::check,
  };
}

}  // namespace peridot
