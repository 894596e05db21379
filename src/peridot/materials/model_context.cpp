#include "peridot/materials/model_context.hpp"

#include <algorithm>
#include <cmath>

namespace peridot {

void ModelContext::add_block(ResolvedMaterial material) {
  params.push_back(material.block);
  model_params.push_back(std::move(material.model));
}

bool ModelContext::any_dilatation() const {
  return std::any_of(params.begin(), params.end(), [](const MaterialParams& p) {
    return with_model(p.model, [](auto m) { return decltype(m)::uses_dilatation; });
  });
}

bool ModelContext::any_damage() const {
  return std::any_of(params.begin(), params.end(), [](const MaterialParams& p) { return std::isfinite(p.critical_stretch); });
}

int ModelContext::bond_history_arrays() const {
  int arrays = 0;
  for (const MaterialParams& p : params)
    arrays = std::max(arrays, with_model(p.model, [](auto m) { return decltype(m)::bond_history_arrays; }));
  return arrays;
}

int ModelContext::point_arrays() const {
  int arrays = 0;
  for (const MaterialParams& p : params)
    arrays = std::max(arrays, with_model(p.model, [](auto m) { return static_cast<int>(decltype(m)::point_arrays.size()); }));
  return arrays;
}

void ModelContext::initialize_point_arrays(MaterialHistory& history) const {
  const std::size_t n = disc->num_points();
  history.point.assign(static_cast<std::size_t>(point_arrays()), std::vector<double>(n, 0.0));
  // Owned points by their block's range, ghosts by their block: every point starts as its model says.
  for (std::size_t i = 0; i < n; ++i)
    with_model(params[static_cast<std::size_t>(disc->block[i])].model, [&](auto model) {
      const auto& arrays = decltype(model)::point_arrays;
      for (std::size_t k = 0; k < arrays.size(); ++k) history.point[k][i] = arrays[k].initial;
    });
}

std::vector<int> ModelContext::partner_point_arrays() const {
  std::vector<int> arrays;
  for (const MaterialParams& p : params)
    with_model(p.model, [&](auto model) {
      for (int k : decltype(model)::partner_point_arrays)
        if (std::find(arrays.begin(), arrays.end(), k) == arrays.end()) arrays.push_back(k);
    });
  return arrays;
}

std::vector<int> ModelContext::released_extension_arrays() const {
  std::vector<int> arrays;
  for (const MaterialParams& p : params)
    with_model(p.model, [&](auto model) {
      const int k = decltype(model)::released_extension_array;
      if (k >= 0 && std::find(arrays.begin(), arrays.end(), k) == arrays.end()) arrays.push_back(k);
    });
  return arrays;
}

void ModelContext::set_time_step(double dt) {
  for (std::size_t b = 0; b < params.size(); ++b)
    with_model(params[b].model, [&](auto model) {
      using Model = decltype(model);
      Model::set_time_step(std::get<MaterialModels::index_of<Model>()>(model_params[b]), dt);
    });
}

}  // namespace peridot
