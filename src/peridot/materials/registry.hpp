#pragma once
// The material models Peridot knows, one line each in registry.cpp: name, kind, description, reference
// and the keys the model adds to the common material keys. The deck parser validates a material
// against these tables and `peridot info` prints them; adding a model means adding its line there.
#include <optional>
#include <string_view>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/deck/schema.hpp"

namespace peridot {

struct ModelInfo {
  std::string_view name;
  ModelKind kind;
  std::string_view description;
  std::string_view reference;
  /// Bond-based models have a fixed Poisson ratio (1/4 in 3D and plane strain, 1/3 in plane stress),
  /// so the deck gives one modulus; state-based ones take any two elastic constants.
  bool bond_based = false;
  std::vector<KeySpec> extra_keys;  ///< model parameters beyond common_material_keys()
};

const std::vector<ModelInfo>& material_models();
const ModelInfo* find_model(std::string_view name);
const ModelInfo& model_info(ModelKind kind);
std::vector<std::string_view> model_names();

/// Keys of every material: model, density, elastic constants, influence function, damage.
std::vector<KeySpec> common_material_keys();
/// The keys of a material of this model: the common keys and the model's own.
std::vector<KeySpec> material_keys(const ModelInfo& model);
/// Keys of a material's damage section.
std::vector<KeySpec> damage_keys();

/// The Poisson ratio a bond-based model implies: 1/4 in 3D and plane strain, 1/3 in plane stress.
double bond_based_poisson_ratio(int dimension, PlaneKind plane);

}  // namespace peridot
