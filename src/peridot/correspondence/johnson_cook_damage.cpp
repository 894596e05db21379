// Johnson–Cook damage: its deck section (johnson_cook_damage.hpp).
#include "peridot/correspondence/johnson_cook_damage.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot::correspondence {

KeySpec JohnsonCookDamage::key() {
  return {.key = "johnson_cook_damage", .type = ValueType::mapping,
          .description = "Johnson–Cook ductile damage D and how it weakens the material (see "
                         "materials.<name>.johnson_cook_damage); j2_viscoplastic and johnson_cook; omit for none"};
}

SectionSpec JohnsonCookDamage::section() {
  std::vector<KeySpec> keys = {
      {.key = "d1", .description = "D1 (-): εf = [D1 + D2 exp(D3 η)][1 + D4 ln ε̇*][1 + D5 T*]", .required = true},
      {.key = "d2", .default_yaml = "0", .description = "D2 (-)"},
      {.key = "d3", .default_yaml = "0", .description = "D3 (-), usually negative: εf falls with triaxiality η"},
      {.key = "d4", .default_yaml = "0",
       .description = "D4 (-), with ε̇* = max(ε̇p/ε̇0, 1), ε̇0 the law's reference_strain_rate"},
      {.key = "d5", .default_yaml = "0",
       .description = "D5 (-), with T* of thermal_softening (0 without it)"},
      {.key = "minimum_failure_strain", .default_yaml = "1e-3", .range = positive,
       .description = "floor of εf (-): where the fit gives less (with D1 < 0, D3 < 0: high triaxiality in tension), "
                      "the point fails after this much plastic strain"},
      {.key = "coupling", .type = ValueType::choice, .default_yaml = "influence_function",
       .description = "influence_function: bond weights ω (1 − max(D_i, D_j)), a bond breaks at D = 1 (Tupek et al.); "
                      "local_stress: the force uses (1 − D) σ, no bond breaks (unstable under refinement, for "
                      "comparison)",
       .choices = {"influence_function", "local_stress"}}};
  return {"materials.<name>.johnson_cook_damage",
          "Johnson–Cook damage of constitutive_law: j2_viscoplastic or johnson_cook, D += Δεp/εf; omit for none",
          std::move(keys)};
}

JohnsonCookDamage JohnsonCookDamage::from_parameters(const Parameters& q) {
  JohnsonCookDamage damage;
  if (!q.has("johnson_cook_damage.d1")) return damage;
  damage.enabled = true;
  damage.d1 = q.number("johnson_cook_damage.d1");
  damage.d2 = q.number_or("johnson_cook_damage.d2", 0);
  damage.d3 = q.number_or("johnson_cook_damage.d3", 0);
  damage.d4 = q.number_or("johnson_cook_damage.d4", 0);
  damage.d5 = q.number_or("johnson_cook_damage.d5", 0);
  damage.minimum_failure_strain = q.number_or("johnson_cook_damage.minimum_failure_strain", 1e-3);
  damage.coupling = q.has("johnson_cook_damage.coupling") && q.text("johnson_cook_damage.coupling") == "local_stress"
                        ? DamageCoupling::local_stress
                        : DamageCoupling::influence_function;
  return damage;
}

}  // namespace peridot::correspondence
