#pragma once
// The solvers as the deck sees them: each solver's type name, its keys and the checks it makes of the
// whole problem. The catalogue itself, solver_types(), is defined by the solver list
// (solvers/time_integrator.cpp), where each solver describes itself in its own file pair; the deck reads it
// through this header only.
#include <string>
#include <string_view>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/deck/schema.hpp"

namespace peridot {

class DeckContext;

struct SolverInfo {
  std::string_view name;         ///< the value of solver.type
  std::string_view summary;      ///< a few words, for the description of solver.type
  std::string_view description;  ///< the description of its section of the deck reference
  /// Its keys besides type, in the order the resolved deck writes them; the parser keeps every valid value
  /// and every default in SolverSpec::parameters.
  std::vector<KeySpec> keys;
  /// What it cannot solve, checked once the whole deck is read (positions and paths of the offending
  /// items). Null: nothing.
  void (*check)(const Problem& problem, DeckContext& context) = nullptr;
};

/// Every solver, in registration order; the first is the default type.
const std::vector<SolverInfo>& solver_types();
const SolverInfo* find_solver(std::string_view name);
/// solver.type: a choice of the registered names, the first by default.
KeySpec solver_type_key();
/// The deck-reference section of a solver: "solver" for the default one, "solver (type: NAME)" otherwise.
std::string solver_section_path(const SolverInfo& solver);
/// The keys of the solver section with this type: type and the solver's own.
std::vector<KeySpec> solver_keys(const SolverInfo& solver);

}  // namespace peridot
