#include "peridot/materials/registry.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

const std::vector<ModelInfo>& material_models() {
  static const std::vector<ModelInfo> models = {
      {"pmb", ModelKind::pmb, "prototype microelastic brittle: bond-based, pairwise linear springs",
       "Silling & Askari, Comput. Struct. 83 (2005) 1526-1535", true, {}},
      {"lps", ModelKind::lps, "linear peridynamic solid: ordinary state-based, any Poisson ratio",
       "Silling, Epton, Weckner, Xu & Askari, J. Elasticity 88 (2007) 151-184", false, {}},
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

double bond_based_poisson_ratio(int dimension, PlaneKind plane) {
  return dimension == 2 && plane == PlaneKind::stress ? 1.0 / 3.0 : 0.25;
}

}  // namespace peridot
