#include "peridot/deck/solver_schema.hpp"

#include <fmt/format.h>

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

const SolverInfo* find_solver(std::string_view name) {
  for (const SolverInfo& solver : solver_types())
    if (solver.name == name) return &solver;
  return nullptr;
}

KeySpec solver_type_key() {
  // The KeySpec holds views: the names and the joined description live as long as the catalogue.
  static const std::string description = [] {
    std::string text;
    for (const SolverInfo& s : solver_types()) text += fmt::format("{}{}: {}", text.empty() ? "" : "; ", s.name, s.summary);
    return text;
  }();
  std::vector<std::string_view> names;
  for (const SolverInfo& s : solver_types()) names.push_back(s.name);
  return {.key = "type", .type = ValueType::choice, .default_yaml = solver_types().front().name,
          .description = description, .choices = names};
}

std::string solver_section_path(const SolverInfo& solver) {
  if (&solver == &solver_types().front()) return "solver";
  return fmt::format("solver (type: {})", solver.name);
}

std::vector<KeySpec> solver_keys(const SolverInfo& solver) {
  std::vector<KeySpec> keys = {solver_type_key()};
  keys.insert(keys.end(), solver.keys.begin(), solver.keys.end());
  return keys;
}

}  // namespace peridot
