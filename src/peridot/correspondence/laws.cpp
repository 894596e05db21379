#include "peridot/correspondence/laws.hpp"

#include <optional>
#include <string>

#include "peridot/core/error.hpp"

namespace peridot::correspondence {

std::vector<std::string_view> law_names() {
  std::vector<std::string_view> names;
  ConstitutiveLaws::for_each([&](auto law) { names.push_back(decltype(law)::name); });
  return names;
}

AnyLaw make_law(std::string_view name, const Parameters& parameters, const ElasticConstants& elastic,
                double density) {
  std::optional<AnyLaw> made;
  ConstitutiveLaws::for_each([&](auto law) {
    using Law = decltype(law);
    if (!made && Law::name == name) made = Law::from_parameters(parameters, elastic, density);
  });
  PERIDOT_REQUIRE(made.has_value(), "no constitutive law is named '" + std::string(name) + "'");
  return *made;
}

}  // namespace peridot::correspondence
