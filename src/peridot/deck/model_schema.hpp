#pragma once
// The material models as the deck sees them: each model's name, keys, nested sections, cross-key checks and
// documentation page. The catalogue itself, material_models(), is defined by the model list
// (materials/models.cpp), where each model describes itself in its own file pair; the deck reads the
// catalogue through this header only, so that the deck does not depend on the models' kernels.
#include <string_view>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/deck/schema.hpp"

namespace peridot {

class DeckContext;
class MapReader;

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
  std::string_view description;
  std::string_view reference;
  /// Bond-based models have a fixed Poisson ratio (1/4 in 3D and plane strain, 1/3 in plane stress),
  /// so the deck gives one modulus; state-based ones take any two elastic constants.
  bool bond_based = false;
  /// The model's parameters beyond common_material_keys(), in the order the resolved deck writes them.
  /// The parser keeps every valid value and every default in MaterialSpec::parameters.
  std::vector<KeySpec> keys;
  /// The tables of its keys of type mapping, path "materials.<name>.KEY"; their values are kept in
  /// MaterialSpec::parameters as "KEY.SUBKEY".
  std::vector<SectionSpec> sections;
  ModelDoc doc;
  int dimension = 0;  ///< 0: 2D and 3D (and 1D when one_dimensional); 3: 3D only (the deck refuses the model in 2D)
  /// The model has a 1D form, a bar of area A calibrated to Young's modulus alone (discretization.dimension: 1).
  bool one_dimensional = false;
  /// The one influence function the model is calibrated for ("inverse_distance": the deck refuses another
  /// and takes this one when none is given); empty: any.
  std::string_view influence;
  /// Checks across keys that the tables cannot state (a key that only one variant accepts, keys that go
  /// together); reports through the context. Null: none.
  void (*check)(const MapReader& material, const Parameters& parameters, DeckContext& context) = nullptr;
};

/// Every model, in registration order (materials/models.hpp).
const std::vector<ModelInfo>& material_models();
const ModelInfo* find_model(std::string_view name);
std::vector<std::string_view> model_names();

/// Keys of every material: model, density, elastic constants, influence function, damage.
std::vector<KeySpec> common_material_keys();
/// The keys of a material of this model: the common keys and the model's own.
std::vector<KeySpec> material_keys(const ModelInfo& model);
/// The key `thermal_expansion` (α, 1/K, default 0), for the key table of a model whose bonds carry the thermal
/// stretch α (T − T_ref) of a prescribed temperature field (the ordinary models; the bond loops apply it).
KeySpec thermal_expansion_key();
/// The key `surface_correction` (boolean, default false), for the key table of a model whose bond loops apply the
/// per-bond factor of the energy method (ModelBase::corrects_surfaces; solvers/surface_correction.hpp).
KeySpec surface_correction_key();
/// Keys of a material's damage section.
std::vector<KeySpec> damage_keys();
/// How critical-stretch damage works, for the model pages (Markdown; the same for every model).
std::string_view damage_doc();

/// `given` (in its order) and the default of every key of the table it lacks, as the parser fills them in:
/// for problems built in code (tests, benchmarks). Keys not in the table are dropped.
Parameters complete_parameters(const std::vector<KeySpec>& keys, const Parameters& given);

/// The Poisson ratio a bond-based model implies: 1/4 in 3D and plane strain, 1/3 in plane stress.
double bond_based_poisson_ratio(int dimension, PlaneKind plane);

}  // namespace peridot
