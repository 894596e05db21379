#include "peridot/materials/correspondence_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "peridot/deck/map_reader.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

namespace correspondence {

double hourglass_stiffness(double coefficient, double bulk_modulus, double horizon) {
  return 18.0 * coefficient * bulk_modulus / (std::numbers::pi * std::pow(horizon, 4));
}

double hourglass_damping(double coefficient, double density, double bulk_modulus, double horizon) {
  return 18.0 * coefficient * std::sqrt(density * bulk_modulus) / (std::numbers::pi * std::pow(horizon, 3));
}

}  // namespace correspondence

CorrespondenceModel::Params CorrespondenceModel::resolve(const MaterialSpec& spec, const Problem&, MaterialParams& block) {
  const ModelParameters& q = spec.parameters;
  Params p;
  p.law = q.text("constitutive_law") == "j2_viscoplastic" ? ConstitutiveLawKind::j2_viscoplastic
                                                           : ConstitutiveLawKind::hypoelastic;
  p.hourglass_coefficient = q.number("hourglass_coefficient");
  p.hourglass_viscosity = q.number("hourglass_viscosity");
  if (p.law == ConstitutiveLawKind::j2_viscoplastic) {
    p.yield_stress = q.number("yield_stress");
    p.hardening_exponent = q.number_or("hardening_exponent", std::numeric_limits<double>::infinity());
    p.reference_plastic_strain = q.number_or("reference_plastic_strain", 1);
    p.rate_exponent = q.number_or("rate_exponent", std::numeric_limits<double>::infinity());
    p.reference_strain_rate = q.number_or("reference_strain_rate", 1);
    if (q.has("thermal_softening.taylor_quinney_coefficient")) {  // defaulted: there when the section is
      ThermalSoftening& t = p.thermal;
      t.enabled = true;
      t.specific_heat = q.number("thermal_softening.specific_heat");
      t.reference_temperature = q.number("thermal_softening.reference_temperature");
      t.melting_temperature = q.number("thermal_softening.melting_temperature");
      t.exponent = q.number("thermal_softening.exponent");
      t.taylor_quinney = q.number("thermal_softening.taylor_quinney_coefficient");
    }
  }
  // Stable time step (docs/models/correspondence.md): the Silling–Askari bound of the PMB solid with the
  // same P-wave modulus M = K + 4G/3 (a PMB solid, ν = 1/4, has M = 1.8K), but never less stiff than the
  // PMB solid of the same K, plus the hourglass bond stiffness c_hg = 18 C_HG K/(πδ⁴) (force.hpp):
  //   c = 18 [max(K, M/1.8) + C_HG K] / (π δ⁴).
  const double K = spec.elastic.bulk_modulus, M = K + 4 * spec.elastic.shear_modulus / 3;
  block.stable_micromodulus =
      18 * (std::max(K, M / 1.8) + p.hourglass_coefficient * K) / (std::numbers::pi * std::pow(block.horizon, 4));
  block.stable_damping = correspondence::hourglass_damping(p.hourglass_viscosity, spec.density, K, block.horizon);
  return p;
}

void CorrespondenceModel::check(const MapReader& r, const ModelParameters& q, DeckContext& ctx) {
  if (r.given("damage"))
    ctx.error(r["damage"].key_pos, r.path_of("damage"),
              "the correspondence model has no bond failure yet; remove damage (broken bonds would leave K, F "
              "and the force state without a failure criterion)");
  const bool j2 = r["constitutive_law"].text == "j2_viscoplastic";
  static constexpr std::string_view j2_keys[] = {"yield_stress", "hardening_exponent", "reference_plastic_strain",
                                                 "rate_exponent", "reference_strain_rate", "thermal_softening"};
  if (!j2) {
    for (std::string_view key : j2_keys)
      if (r.given(key))
        ctx.error(r[key].key_pos, r.path_of(key),
                  fmt::format("{} is a parameter of constitutive_law: j2_viscoplastic, not of hypoelastic", key));
    return;
  }
  if (!r.present("yield_stress"))
    ctx.error(r["constitutive_law"].pos, r.path(), "constitutive_law: j2_viscoplastic needs yield_stress");
  // An exponent and its reference value come together: (1 + εp/ε0)^(1/n), (1 + ε̇p/ε̇0)^(1/m).
  for (auto [exponent, reference] : {std::pair<std::string_view, std::string_view>{"hardening_exponent", "reference_plastic_strain"},
                                     {"rate_exponent", "reference_strain_rate"}})
    if (r.present(exponent) != r.present(reference)) {
      std::string_view given = r.present(exponent) ? exponent : reference;
      if (r.given(given))
        ctx.error(r[given].key_pos, r.path_of(given),
                  fmt::format("{} and {} go together; give both or neither", exponent, reference));
    }
  const ModelParameters::Entry* reference = q.find("thermal_softening.reference_temperature");
  const ModelParameters::Entry* melting = q.find("thermal_softening.melting_temperature");
  if (reference && melting && !(melting->number > reference->number))
    ctx.error(melting->pos, r.path_of("thermal_softening") + ".melting_temperature",
              fmt::format("melting_temperature ({:g} K) must be above reference_temperature ({:g} K)",
                          melting->number, reference->number));
}

// The page of `peridot info --model correspondence` (docs/models/correspondence.md). The equations restate
// the header comments of correspondence/; keep them in step with the code.
ModelInfo CorrespondenceModel::info() {
  ModelDoc doc{
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
  return {
      .name = name,
      .description = "non-ordinary state-based (correspondence) solid: hypoelastic or J2 viscoplastic law, hourglass control",
      .reference = "Foster, Silling & Chen, IJNME 81 (2010) 1242-1258",
      // In the order the resolved deck writes them (the law, its hourglass control, then the J2 keys).
      .keys = {{.key = "constitutive_law", .type = ValueType::choice, .description = "the law in the unrotated frame",
                .required = true, .choices = {"hypoelastic", "j2_viscoplastic"}},
               {.key = "hourglass_coefficient", .default_yaml = "0.05", .range = non_negative,
                .description = "C_HG (-): hourglass bond stiffness 18 C_HG K/(πδ⁴); 0 = no control"},
               {.key = "hourglass_viscosity", .default_yaml = "0", .range = non_negative,
                .description = "C_HV (-): viscous hourglass damping, a bond dashpot 18 C_HV √(ρK)/(πδ³) on the non-affine "
                               "stretch rate; 0 = none (elastic control only)"},
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
                               "j2_viscoplastic; omit for none"}},
      .sections = {{"materials.<name>.thermal_softening",
                    "adiabatic heating and Johnson–Cook thermal softening of constitutive_law: j2_viscoplastic; omit for none",
                    {{.key = "specific_heat", .unit = Unit::specific_heat, .range = positive,
       .description = "c (J/(kg K)), specific heat at constant pressure", .required = true},
      {.key = "reference_temperature", .unit = Unit::temperature, .range = positive,
       .description = "T_r (K): the initial temperature, where the thermal factor is 1", .required = true},
      {.key = "melting_temperature", .unit = Unit::temperature, .range = positive,
       .description = "T_m (K): the thermal factor is 0 there; above reference_temperature", .required = true},
      {.key = "exponent", .range = positive, .description = "q (-): thermal factor 1 − T*^q, Johnson–Cook's m",
       .required = true},
      {.key = "taylor_quinney_coefficient", .default_yaml = "0.9", .range = {0, 1, false, false},
       .description = "β (-): share of the plastic work that heats the point"}}}},
      .doc = doc,
      .dimension = 3,
      .check = &CorrespondenceModel::check,
  };
}

}  // namespace peridot
