#include "peridot/materials/models.hpp"

namespace peridot {

namespace {

template <class... Models>
std::vector<ModelInfo> infos(ModelList<Models...>) {
  return {Models::info()...};
}

template <class... Models>
std::vector<std::string_view> names(ModelList<Models...>) {
  return {Models::name...};
}

}  // namespace

// The catalogue the deck reads (declared in deck/model_schema.hpp).
const std::vector<ModelInfo>& material_models() {
  static const std::vector<ModelInfo> models = infos(MaterialModels{});
  return models;
}

int model_index(std::string_view name) {
  static const std::vector<std::string_view> all = names(MaterialModels{});
  const auto it = std::find(all.begin(), all.end(), name);
  return it == all.end() ? -1 : static_cast<int>(it - all.begin());
}

std::string_view model_name(int index) {
  return with_model(index, [](auto model) { return decltype(model)::name; });
}

ResolvedMaterial resolve_material(const MaterialSpec& spec, double horizon, const Problem& problem) {
  const int index = model_index(spec.model);
  PERIDOT_REQUIRE(index >= 0, "material model '" + spec.model + "' is not registered");
  MaterialParams p;
  p.model = index;
  p.influence = spec.influence;
  p.dimension = problem.dimension;
  p.density = spec.density;
  p.horizon = horizon;
  p.elastic = spec.elastic;
  p.thermal_expansion = spec.parameters.number_or("thermal_expansion", 0.0);
  p.stable_micromodulus = bond_based_micromodulus(spec.elastic, horizon, InfluenceKind::constant, problem);
  if (spec.damage.enabled && spec.damage.criterion == DamageCriterion::energy) {
    p.fracture_energy = spec.damage.fracture_energy.value_or(0.0);  // the deck requires it
    if (!(problem.spacing > 0))  // N_c and the crack area A_c of one cell are the lattice's
      throw InputError(spec.pos, "materials." + spec.name +
                                     ": damage criterion energy needs the lattice spacing (discretization.spacing)");
  } else if (spec.damage.enabled) {
    if (spec.damage.critical_stretch) p.critical_stretch = *spec.damage.critical_stretch;
    else if (spec.damage.fracture_energy)
      p.critical_stretch = critical_stretch_from_energy(*spec.damage.fracture_energy, spec, horizon, problem);
    if (!(p.critical_stretch > 0))
      throw InputError(spec.pos, "materials." + spec.name + ": the critical stretch must be positive");
  }
  p.surface_correction = with_model(index, [&](auto m) {
    return decltype(m)::corrects_surfaces && spec.parameters.has("surface_correction") &&
           spec.parameters.boolean("surface_correction");
  });
  ModelParams model = with_model(index, [&](auto m) -> ModelParams {
    using Model = decltype(m);
    return ModelParams(std::in_place_index<MaterialModels::index_of<Model>()>, Model::resolve(spec, problem, p));
  });
  return {p, std::move(model)};
}

}  // namespace peridot
