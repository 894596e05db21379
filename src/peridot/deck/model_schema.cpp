#include "peridot/deck/model_schema.hpp"

#include <string>

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

const ModelInfo* find_model(std::string_view name) {
  for (const ModelInfo& model : material_models())
    if (model.name == name) return &model;
  return nullptr;
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
  keys.insert(keys.end(), model.keys.begin(), model.keys.end());
  return keys;
}

KeySpec thermal_expansion_key() {
  return {.key = "thermal_expansion", .unit = Unit::thermal_expansion, .default_yaml = "0",
          .description = "α (1/K): with a temperature field, every bond carries the free thermal stretch α (T − T_ref) "
                         "of its end point (see temperature)"};
}

KeySpec surface_correction_key() {
  return {.key = "surface_correction", .type = ValueType::boolean, .default_yaml = "false",
          .description = "scale each bond so that every point stores the classical energy of a uniaxial strain along "
                         "each axis (energy method; points near a free surface have truncated families)"};
}

std::vector<KeySpec> damage_keys() {
  return {
      {.key = "critical_stretch", .range = positive, .description = "bond breaks beyond this stretch s0",
       .required = true, .one_of = "threshold"},
      {.key = "fracture_energy", .unit = Unit::energy_per_area, .range = positive,
       .description = "G0 (J/m^2); s0 then follows from K and δ (criterion stretch), or the bonds' work (energy)",
       .required = true, .one_of = "threshold"},
      {.key = "criterion", .type = ValueType::choice, .default_yaml = "stretch",
       .description = "stretch: s > s0 breaks; energy: the work done on the bond reaches 2Gc A_c/(N_c V_i V_j) "
                      "(needs fracture_energy)",
       .choices = {"stretch", "energy"}},
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
- (D2) 2D, thickness h: G0 = h c0 s0² ∫₀^δ ω ξ³ dξ, so s0 = √(πG0/(3K′δ)) for ω = 1
- 1D, a bar of area A: G0 = (A c0 s0²/2) ∫₀^δ ω ξ² dξ, so s0 = √(3G0/(Eδ)) for ω = 1

With `criterion: energy` (Madenci & Oterkus 2017, §6; docs/algorithms.md §14) a bond breaks by the work done on
it instead, whatever the model's force law, so that viscous or plastic work counts. Each bond keeps
W = ∫ (t_ij + t_ji) de (J/m^6): the force states of its two ends times its mechanical extension (thermal
stretch removed), added once per accepted step by the trapezoid rule. A bond in tension breaks, irreversibly,
once

- (D3) W V_i V_j ≥ 2 Gc A_c / N_c, A_c = Δx h (2D) or Δx² (3D), i.e. ½(G_ij + G_ji) ≥ Gc/N_c with G_ij = V_i V_j ∫ t_ij de / A_c

where N_c is twice the number of lattice bonds (|ξ| ≤ δ) crossing one cell of a crack plane between two
lattice rows, bonds through the cell's edge counting ½: the bonds crossing a straight crack then take exactly
Gc per unit area with them. N_c = 36 for δ = 3Δx in 2D (the paper counts 34) and 140 in 3D; the run log prints
it per block. The work of a step counts from the next step on in explicit runs (the check comes before the
step's forces); dynamic relaxation checks at each equilibrium with the work of the load step included. Between
two blocks the smaller threshold applies; a block with the stretch criterion keeps its s0 on its side. The
partial-volume factor enters neither the count nor the work. With lps_plastic, a bond that the energy
criterion breaks does not enter the released extension (P8).)";
}

namespace {

void copy_entry(Parameters& to, const Parameters::Entry& e) {
  switch (e.kind) {
    case Parameters::Kind::text: to.set_text(e.key, e.text, e.pos); break;
    case Parameters::Kind::integer: to.set_integer(e.key, static_cast<std::int64_t>(e.number), e.pos); break;
    case Parameters::Kind::boolean: to.set_boolean(e.key, e.number != 0, e.pos); break;
    case Parameters::Kind::number: to.set_number(e.key, e.number, e.pos); break;
  }
}

}  // namespace

Parameters complete_parameters(const std::vector<KeySpec>& keys, const Parameters& given) {
  Parameters all;
  for (const KeySpec& k : keys) {
    if (k.type == ValueType::mapping || k.type == ValueType::sequence) {  // "KEY.SUB" and "KEY[i].SUB", as given
      const std::string section(k.key);
      for (const Parameters::Entry& e : given.entries())
        if (e.key.size() > section.size() && e.key.compare(0, section.size(), section) == 0 &&
            (e.key[section.size()] == '.' || e.key[section.size()] == '['))
          copy_entry(all, e);
      continue;
    }
    if (const Parameters::Entry* e = given.find(k.key)) {
      copy_entry(all, *e);
      continue;
    }
    if (k.default_yaml.empty()) continue;
    const std::string key(k.key), value(k.default_yaml);
    switch (k.type) {
      case ValueType::choice:
      case ValueType::text: all.set_text(key, value); break;
      case ValueType::integer: all.set_integer(key, std::stoll(value)); break;
      case ValueType::boolean: all.set_boolean(key, value == "true"); break;
      default: {
        const Quantity q = parse_quantity(value, k.unit);
        PERIDOT_REQUIRE(q.value.has_value(), "default of " + key + " does not parse: " + q.error);
        all.set_number(key, *q.value);
      }
    }
  }
  return all;
}

double bond_based_poisson_ratio(int dimension, PlaneKind plane) {
  return dimension == 2 && plane == PlaneKind::stress ? 1.0 / 3.0 : 0.25;
}

}  // namespace peridot
