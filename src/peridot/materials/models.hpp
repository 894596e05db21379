#pragma once
// The registration list: every material model, one line each. A model is its own file pair
// (materials/NAME.{hpp,cpp}, see materials/model_base.hpp); this list makes the deck know it (its keys, page
// and checks, deck/model_schema.hpp), the set-up resolve its constants and the bond loops dispatch to its
// kernels at compile time (one instantiation per dimension and model: no call in a loop is virtual).
#include <algorithm>
#include <cstddef>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include "peridot/materials/correspondence_model.hpp"
#include "peridot/materials/lps.hpp"
#include "peridot/materials/lps_plastic.hpp"
#include "peridot/materials/lps_viscoelastic.hpp"
#include "peridot/materials/pmb.hpp"
#include "peridot/materials/thermoviscoelastic.hpp"

namespace peridot {

template <class... Models>
struct ModelList {
  /// Every model's block constants, one alternative per model in list order (the index is MaterialParams::model).
  using Params = std::variant<typename Models::Params...>;
  /// Position of Model in the list.
  template <class Model>
  static constexpr int index_of() {
    int index = 0, found = -1;
    ((std::is_same_v<Model, Models> ? found = index : 0, ++index), ...);
    return found;
  }
  static constexpr int most_bond_arrays = std::max({0, Models::bond_history_arrays...});
  static constexpr int most_point_arrays = std::max({0, static_cast<int>(Models::point_arrays.size())...});
};

// clang-format off
using MaterialModels = ModelList<
    Pmb,
    Lps,
    LpsPlastic,
    LpsViscoelastic,
    Thermoviscoelastic,
    CorrespondenceModel>;
// clang-format on

static_assert(MaterialModels::most_bond_arrays <= max_bond_arrays, "raise max_bond_arrays (materials/material.hpp)");
static_assert(MaterialModels::most_point_arrays <= max_point_arrays, "raise max_point_arrays (materials/material.hpp)");

/// A block's model constants: the Params of its model.
using ModelParams = MaterialModels::Params;

namespace detail {
template <class F, class First, class... Rest>
decltype(auto) with_model_at(int index, F&& f) {
  if constexpr (sizeof...(Rest) == 0) {
    return std::forward<F>(f)(First{});
  } else {
    if (index == 0) return std::forward<F>(f)(First{});
    return with_model_at<F, Rest...>(index - 1, std::forward<F>(f));
  }
}
template <class F, class... Models>
decltype(auto) with_model_in(ModelList<Models...>, int index, F&& f) {
  return with_model_at<F, Models...>(index, std::forward<F>(f));
}
}  // namespace detail

/// Runs f(Model{}) for the model at `index` of MaterialModels (MaterialParams::model).
template <class F>
decltype(auto) with_model(int index, F&& f) {
  return detail::with_model_in(MaterialModels{}, index, std::forward<F>(f));
}

/// Whether a block's model is Model.
template <class Model>
bool is_model(const MaterialParams& p) {
  return p.model == MaterialModels::index_of<Model>();
}

/// The Params of Model in a block's constants.
template <class Model>
const typename Model::Params& params_of(const ModelParams& params) {
  return std::get<MaterialModels::index_of<Model>()>(params);
}

/// Runs f(std::integral_constant<int, Dim>) for the deck's dimension. A 1D deck's points lie on the x axis
/// (y = z = 0), where the 2D loops are exact: it runs them, and what depends on the dimension beyond the
/// bond geometry (a calibration) reads the deck's dimension itself.
template <class F>
decltype(auto) with_dimension(int dimension, F&& f) {
  if (dimension <= 2) return std::forward<F>(f)(std::integral_constant<int, 2>{});
  return std::forward<F>(f)(std::integral_constant<int, 3>{});
}

/// The index in MaterialModels of the model with this name; −1 when there is none.
int model_index(std::string_view name);
/// The name of the model at this index.
std::string_view model_name(int index);

/// A block's material: what every model has and its model's own constants.
struct ResolvedMaterial {
  MaterialParams block;
  ModelParams model;
};

/// Builds a block's material from the deck. Throws InputError when the fracture energy cannot give a
/// critical stretch (non-positive result).
ResolvedMaterial resolve_material(const MaterialSpec& spec, double horizon, const Problem& problem);

}  // namespace peridot
