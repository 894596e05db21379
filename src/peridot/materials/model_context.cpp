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

bool ModelContext::any_start_step() const {
  return std::any_of(params.begin(), params.end(), [](const MaterialParams& p) {
    return with_model(p.model, [](auto m) { return decltype(m)::has_start_step; });
  });
}

bool ModelContext::any_damage() const {
  return std::any_of(params.begin(), params.end(), [](const MaterialParams& p) {
    return std::isfinite(p.critical_stretch) || p.fracture_energy > 0 || p.damage_breaks_bonds;
  });
}

namespace {

/// The largest value of trait(Model) over the blocks' models (0 without blocks).
template <class Trait>
int most_over_blocks(const std::vector<MaterialParams>& params, Trait trait) {
  int most = 0;
  for (const MaterialParams& p : params) most = std::max(most, with_model(p.model, trait));
  return most;
}

/// Every array index indices(Model) gives over the blocks' models, each once, in the order first given.
template <class Indices>
std::vector<int> each_once_over_blocks(const std::vector<MaterialParams>& params, Indices indices) {
  std::vector<int> all;
  for (const MaterialParams& p : params)
    for (int k : with_model(p.model, indices))
      if (k >= 0 && std::find(all.begin(), all.end(), k) == all.end()) all.push_back(k);
  return all;
}

}  // namespace

int ModelContext::bond_history_arrays() const {
  int most = 0;
  for (std::size_t b = 0; b < params.size(); ++b)
    most = std::max(most, with_model(params[b].model, [&](auto m) {
      using Model = decltype(m);
      if constexpr (requires { Model::bond_history_count(model_params_of<Model>(b)); })
        return Model::bond_history_count(model_params_of<Model>(b));
      else
        return Model::bond_history_arrays;
    }));
  return most;
}

int ModelContext::point_arrays() const {
  return most_over_blocks(params, [](auto m) { return static_cast<int>(decltype(m)::point_arrays.size()); });
}

int ModelContext::point_constant_arrays() const {
  return most_over_blocks(params, [](auto m) { return decltype(m)::point_constant_arrays; });
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
  return each_once_over_blocks(params, [](auto m) {
    const auto& arrays = decltype(m)::partner_point_arrays;
    return std::vector<int>(arrays.begin(), arrays.end());
  });
}

std::vector<int> ModelContext::released_extension_arrays() const {
  return each_once_over_blocks(params, [](auto m) { return std::vector<int>{decltype(m)::released_extension_array}; });
}

void ModelContext::set_time_step(double dt) {
  for (std::size_t b = 0; b < params.size(); ++b)
    with_model(params[b].model, [&](auto model) {
      using Model = decltype(model);
      Model::set_time_step(std::get<MaterialModels::index_of<Model>()>(model_params[b]), dt);
    });
}

}  // namespace peridot
