#pragma once
// The material models Peridot knows, one line each in registry.cpp: name, kind, description, reference,
// the keys the model adds to the common material keys, and its documentation page. The deck parser
// validates a material against these tables and `peridot info` prints them (`peridot info --model NAME`
// the page, docs/models/NAME.md); adding a model means adding its line and its ModelDoc there.
#include <optional>
#include <string_view>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/deck/schema.hpp"

namespace peridot {

/// The hand-written part of a model's page, Markdown; the syntax and parameter table are generated from
/// the KeySpecs. Say only what the code does.
struct ModelDoc {
  std::string_view summary;       ///< paragraph(s): what the model is and how Peridot calibrates it
  std::string_view equations;     ///< the equations the code implements (as in the header comments), numbered
  std::string_view restrictions;  ///< bullet list: what the model cannot do, what it needs
  std::vector<std::string_view> further_references;  ///< beyond ModelInfo::reference
  std::string_view example;       ///< a `materials:` block with one material; tests parse it in a deck
};

struct ModelInfo {
  std::string_view name;
  ModelKind kind;
  std::string_view description;
  std::string_view reference;
  /// Bond-based models have a fixed Poisson ratio (1/4 in 3D and plane strain, 1/3 in plane stress),
  /// so the deck gives one modulus; state-based ones take any two elastic constants.
  bool bond_based = false;
  std::vector<KeySpec> extra_keys;  ///< model parameters beyond common_material_keys()
  ModelDoc doc;
  int dimension = 0;  ///< 0: 2D and 3D; 3: 3D only (the deck refuses the model in 2D)
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
/// Keys of a j2_viscoplastic material's thermal_softening section.
std::vector<KeySpec> thermal_softening_keys();
/// How critical-stretch damage works, for the model pages (Markdown; the same for every model).
std::string_view damage_doc();

/// The Poisson ratio a bond-based model implies: 1/4 in 3D and plane strain, 1/3 in plane stress.
double bond_based_poisson_ratio(int dimension, PlaneKind plane);

}  // namespace peridot
