#pragma once
// The registration list of the correspondence constitutive laws, one line each. A law is its own file pair
// (correspondence/NAME.{hpp,cpp}): a struct satisfying ConstitutiveLaw (constitutive.hpp) that also says its
// `name`, its deck `keys()` (required ones are required only with this law), optionally `sections()` and a
// cross-key `check`, and builds itself `from_parameters` of a material. The correspondence model
// (materials/correspondence_model.cpp) offers every listed law as a choice of constitutive_law, and the
// solver (solvers/correspondence_blocks.cpp) keeps one block type per law.
#include <string_view>
#include <variant>
#include <vector>

#include "peridot/correspondence/hypoelastic.hpp"
#include "peridot/correspondence/j2_viscoplastic.hpp"
#include "peridot/correspondence/johnson_cook.hpp"

namespace peridot::correspondence {

template <class... Laws>
struct LawList {
  /// A law of any listed kind.
  using Any = std::variant<Laws...>;
  /// Runs f(Law{}) for every law, in list order.
  template <class F>
  static void for_each(F&& f) {
    (f(Laws{}), ...);
  }
};

// clang-format off
using ConstitutiveLaws = LawList<
    Hypoelastic,
    J2Viscoplastic,
    JohnsonCook>;
// clang-format on

using AnyLaw = ConstitutiveLaws::Any;

/// The names of the listed laws, in list order (the choices of constitutive_law).
std::vector<std::string_view> law_names();
/// The law `name` built from a material's parameters; a programming error when no law has the name (the
/// deck's choice list holds only listed names).
AnyLaw make_law(std::string_view name, const Parameters& parameters, const ElasticConstants& elastic,
                double density);

}  // namespace peridot::correspondence
