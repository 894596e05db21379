#pragma once
// The deck schema: one KeySpec per key (type, unit, default, range, one-line description), grouped in
// sections. The parser validates every section against its table (deck/map_reader.hpp) and
// `peridot info` / docs/deck.md print the same tables (print_schema), so the reference cannot drift
// from what the parser accepts. Material models add their keys in their own files (materials/NAME.cpp, deck/model_schema.hpp).
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace peridot {

/// Physical quantity of a number; each has an SI unit and a few accepted alternatives ("72 GPa").
enum class Unit {
  none, length, area, time, pressure, density, energy_per_area, velocity, force_density, rate, temperature, specific_heat,
  thermal_expansion, mass
};

enum class ValueType {
  number,         ///< a real, optionally followed by a unit of the key's quantity
  integer,        ///< a whole number, no unit
  boolean,        ///< true | false
  text,           ///< a string (file name, reference to a named item)
  choice,         ///< one of KeySpec::choices
  point,          ///< [x, y] (2D only) or [x, y, z], lengths
  names,          ///< a list of names of other deck items
  expression,     ///< muParser expression of x, y, z, t
  static_expression,  ///< muParser expression of x, y, z only (t not allowed)
  mapping,        ///< a nested section
  sequence,       ///< a list of nested sections
};

/// An interval for numbers and integers; open or closed at each end.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;
  bool contains(double v) const;
  bool is_everything() const;
  std::string str() const;  ///< "> 0", "≥ 1", "(0, 1]", ...
};

inline constexpr double infinity = std::numeric_limits<double>::infinity();
inline const Range positive{0, infinity, true, false};
inline const Range non_negative{0, infinity, false, false};
inline const Range at_least_one{1, infinity, false, false};

struct KeySpec {
  std::string_view key;
  ValueType type = ValueType::number;
  Unit unit = Unit::none;
  std::string_view default_yaml;  ///< default value as YAML text; empty = no default
  Range range;
  std::string_view description;
  bool required = false;    ///< in a one_of group: one key of the group is required
  std::string_view one_of;  ///< exclusive group: at most one of the keys sharing this name may be given
  int dimension = 0;        ///< 0 = any; 1, 2 or 3 = allowed only in decks of that dimension
  int min_dimension = 0;    ///< 0 = any; 2 = allowed in 2D and 3D decks only (a y component)
  std::vector<std::string_view> choices;  ///< the accepted values of a ValueType::choice
};

struct SectionSpec {
  std::string_view path;         ///< as printed, e.g. "materials.<name>", "precracks[i].segment"
  std::string_view description;  ///< one line
  std::vector<KeySpec> keys;
};

/// Every section of the deck, in document order (material keys come from the model registry).
const std::vector<SectionSpec>& deck_sections();
/// The section with this path; a programming error when absent.
const SectionSpec& deck_section(std::string_view path);

/// "m", "Pa", "-", ... and the accepted unit spellings of a quantity.
std::string_view si_unit(Unit unit);
std::string_view quantity_name(Unit unit);
std::string accepted_units(Unit unit);  ///< "Pa, kPa, MPa, GPa"

/// A number with an optional unit ("0.5 mm", "72e9", "7.8 g/cm^3") converted to SI.
struct Quantity {
  std::optional<double> value;
  std::string error;  ///< why value is empty
};
Quantity parse_quantity(std::string_view text, Unit unit);

/// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);
/// The candidate closest to `word` when close enough to be a likely typo, else empty.
std::string_view closest_match(std::string_view word, const std::vector<std::string_view>& candidates);

}  // namespace peridot
