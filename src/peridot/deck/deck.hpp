#pragma once
// The deck stage: YAML text → a validated, fully resolved Problem (docs/design.md "The deck").
// Every problem in a deck is collected, each with file:line:col, and thrown together as one InputError.
#include <iosfwd>
#include <string>
#include <vector>

#include "peridot/deck/problem.hpp"

namespace peridot {

/// A deck value set from outside the deck before it is parsed (the Python module's parameters): `path` is the
/// dotted key path ("materials.steel.yield_stress"; a list entry by its index, "boundary_conditions.0.value"),
/// `yaml` the new value as YAML text ("3.5e8", "{value: 1}"). Missing keys on the way are created; the schema
/// then checks the result as it checks the file. Errors in a set value name its key path (it has no line).
struct DeckOverride {
  std::string path;
  std::string yaml;
};

/// Reads and parses the deck at `path`; relative file names in it are relative to its folder.
/// Throws InputError carrying every error (warnings end up in Problem::warnings).
Problem load_deck(const std::string& path, const std::vector<DeckOverride>& overrides = {});

/// Parses deck text; `file_name_for_messages` prefixes positions, `base_dir` resolves relative paths.
Problem parse_deck(const std::string& yaml_text, const std::string& file_name_for_messages, const std::string& base_dir,
                   const std::vector<DeckOverride>& overrides = {});

/// The deck as the run understood it: every default filled in, every number in SI, all four elastic
/// constants, paths absolute. parse_deck reads it back to an equal Problem (positions aside).
std::string resolved_deck_yaml(const Problem& problem);

/// The deck reference generated from the schema tables: plain text (`peridot info`) or Markdown (docs/deck.md).
void print_schema(std::ostream& out, bool markdown);

struct ModelInfo;
/// A material model's page: syntax, example, description, equations, parameter tables (from the schema),
/// restrictions, references. Plain text (`peridot info --model NAME`) or Markdown (docs/models/NAME.md).
void print_model_page(std::ostream& out, const ModelInfo& model, bool markdown);

}  // namespace peridot
