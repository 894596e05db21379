#pragma once
// The one generic validation routine of the deck: a MapReader checks a YAML mapping against a section's
// KeySpec table (unknown keys with did-you-mean, duplicates, types, units, ranges, required keys,
// exclusive groups, 2D/3D-only keys), records every problem in the DeckContext and then hands out the
// converted values (defaults filled in). Section parsers (deck.cpp) only add cross-key checks.
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "peridot/core/error.hpp"
#include "peridot/core/vec3.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/deck/schema.hpp"

namespace peridot {

/// What the whole parse shares: the file name for positions, the deck's dimension once known, and
/// every diagnostic found so far.
class DeckContext {
 public:
  explicit DeckContext(std::string file) : file_(std::move(file)) {}

  int dimension = 0;  ///< 2 or 3; 0 while unknown (then 2D/3D-only checks are skipped)

  SourcePos pos(const YAML::Mark& mark) const;  ///< 1-based; line 0 when the mark is null
  /// `path` prefixes the message ("materials.steel"); empty for top-level problems.
  void error(const SourcePos& pos, const std::string& path, const std::string& message);
  void warning(const SourcePos& pos, const std::string& path, const std::string& message);

  const std::string& file() const { return file_; }
  std::vector<Diagnostic>& errors() { return errors_; }
  std::vector<Diagnostic>& warnings() { return warnings_; }

 private:
  std::string file_;
  std::vector<Diagnostic> errors_, warnings_;
};

/// A key's converted value; which member is meaningful follows its KeySpec::type.
struct Value {
  SourcePos key_pos;  ///< where the key is (unknown for defaults)
  SourcePos pos;      ///< where the value is (the key's position when the value is empty)
  YAML::Node node;    ///< mapping and sequence values, for the section parsers to descend into
  double number = 0;  ///< SI
  std::int64_t integer = 0;
  bool boolean = false;
  std::string text;  ///< text and choice
  Vec3 point;
  std::vector<std::string> names;
  Expression expression;
};

class MapReader {
 public:
  /// `owner` is where the section starts (the position missing-key errors point at); `path` names it
  /// in messages ("materials.glass"). Null nodes read as empty mappings.
  MapReader(DeckContext& context, const YAML::Node& node, SourcePos owner, std::string path, std::vector<KeySpec> keys);

  /// The key is in the deck and its value is valid.
  bool given(std::string_view key) const;
  /// The key is in the deck, valid or not (so that follow-up checks do not pile on).
  bool present(std::string_view key) const;
  /// The value given, else the default; an empty Value when neither.
  const Value& operator[](std::string_view key) const;
  std::optional<double> optional_number(std::string_view key) const;

  const std::string& path() const { return path_; }
  std::string path_of(std::string_view key) const;  ///< "materials.glass.density"
  const SourcePos& owner() const { return owner_; }

 private:
  void read_entries(const YAML::Node& node);
  void check_groups_and_required();
  void fill_defaults();
  const KeySpec* find_key(std::string_view key) const;
  bool applies(const KeySpec& spec) const;  ///< allowed in this deck's dimension

  DeckContext& context_;
  SourcePos owner_;
  std::string path_;
  std::vector<KeySpec> keys_;
  std::map<std::string, Value, std::less<>> values_;         ///< valid given values and defaults
  std::map<std::string, SourcePos, std::less<>> present_;    ///< every key in the deck, valid or not
  std::set<std::string, std::less<>> misspelled_;  ///< keys that an unknown key was probably meant to be
  std::set<std::string, std::less<>> given_;               ///< valid values from the deck
};

/// Where a node sits in the deck (its first character), 1-based.
SourcePos node_pos(const DeckContext& context, const YAML::Node& node);

}  // namespace peridot
