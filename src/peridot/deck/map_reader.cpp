#include "peridot/deck/map_reader.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

#include <algorithm>
#include <charconv>

#include <fmt/format.h>

#include "peridot/deck/expression.hpp"

namespace peridot {

// ---------------------------------------------------------------------------------------------
// DeckContext

SourcePos DeckContext::pos(const YAML::Mark& mark) const {
  if (mark.is_null()) return {file_, 0, 0};
  return {file_, mark.line + 1, mark.column + 1};
}

void DeckContext::error(const SourcePos& pos, const std::string& path, const std::string& message) {
  errors_.push_back({pos, path.empty() ? message : path + ": " + message, false});
}

void DeckContext::warning(const SourcePos& pos, const std::string& path, const std::string& message) {
  warnings_.push_back({pos, path.empty() ? message : path + ": " + message, true});
}

SourcePos node_pos(const DeckContext& context, const YAML::Node& node) { return context.pos(node.Mark()); }

// ---------------------------------------------------------------------------------------------
// Conversion of one value according to its KeySpec

namespace {

struct ValueError {
  std::string message;
  int column_offset = 0;  ///< from the value's first character (expressions point inside their text)
};

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Sequence: return fmt::format("a list of {}", node.size());
    case YAML::NodeType::Map: return "a mapping";
    case YAML::NodeType::Scalar: return "'" + node.Scalar() + "'";
    default: return "nothing";
  }
}

std::string with_unit(double value, Unit unit) {
  return unit == Unit::none ? fmt::format("{}", value) : fmt::format("{} {}", value, si_unit(unit));
}

std::optional<ValueError> check_range(const KeySpec& spec, double value) {
  if (spec.range.contains(value)) return std::nullopt;
  return ValueError{fmt::format("must be {}, got {}", spec.range.str(), with_unit(value, spec.unit))};
}

std::optional<ValueError> read_number(const KeySpec& spec, const YAML::Node& node, Value& out) {
  if (!node.IsScalar()) return ValueError{fmt::format("expected a number ({}), got {}", si_unit(spec.unit), describe(node))};
  Quantity q = parse_quantity(node.Scalar(), spec.unit);
  if (!q.value) return ValueError{q.error};
  out.number = *q.value;
  return check_range(spec, out.number);
}

std::optional<ValueError> read_integer(const KeySpec& spec, const YAML::Node& node, Value& out) {
  const std::string& s = node.IsScalar() ? node.Scalar() : std::string();
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out.integer);
  if (!node.IsScalar() || ec != std::errc() || end != s.data() + s.size())
    return ValueError{"expected a whole number, got " + describe(node)};
  return check_range(spec, static_cast<double>(out.integer));
}

std::optional<ValueError> read_choice(const KeySpec& spec, const YAML::Node& node, Value& out) {
  std::string choices = fmt::format("{}", fmt::join(spec.choices, ", "));
  if (!node.IsScalar()) return ValueError{fmt::format("expected one of {}, got {}", choices, describe(node))};
  out.text = node.Scalar();
  for (std::string_view choice : spec.choices)
    if (choice == out.text) return std::nullopt;
  std::string_view guess = closest_match(out.text, spec.choices);
  return ValueError{fmt::format("unknown {} '{}'{}; known: {}", spec.key, out.text,
                                guess.empty() ? "" : fmt::format(" (did you mean '{}'?)", guess), choices)};
}

std::optional<ValueError> read_point(const KeySpec& spec, const YAML::Node& node, int dimension, Value& out) {
  // dimension 0: the deck's own is invalid (reported there), so any length passes here.
  std::string expected = dimension == 3 ? "[x, y, z]" : dimension == 2 ? "[x, y] or [x, y, z]" : dimension == 1 ? "[x]"
                                                                                                             : "[x], [x, y] or [x, y, z]";
  std::size_t n = node.IsSequence() ? node.size() : 0;
  // Three components are also what the defaults give ([0, 0, 0]) in any dimension; a 1D deck's points lie on y = z = 0.
  bool size_ok = n == 3 || (n == 2 && (dimension == 2 || dimension == 0)) || (n == 1 && (dimension == 1 || dimension == 0));
  if (!size_ok) return ValueError{fmt::format("expected {} (m), got {}", expected, describe(node))};
  for (std::size_t d = 0; d < n; ++d) {
    KeySpec component{.key = spec.key, .unit = Unit::length};
    Value v;
    if (auto e = read_number(component, node[d], v)) return ValueError{"component " + std::to_string(d + 1) + ": " + e->message};
    out.point[static_cast<int>(d)] = v.number;
  }
  return std::nullopt;
}

std::optional<ValueError> read_names(const YAML::Node& node, Value& out) {
  if (!node.IsSequence()) return ValueError{"expected a list of names, e.g. [left, right], got " + describe(node)};
  for (const YAML::Node& item : node) {
    if (!item.IsScalar()) return ValueError{"expected a list of names, got an item that is " + describe(item)};
    out.names.push_back(item.Scalar());
  }
  return std::nullopt;
}

std::optional<ValueError> read_expression(const KeySpec& spec, const YAML::Node& node, Value& out) {
  if (!node.IsScalar()) return ValueError{"expected an expression of x, y, z, t, got " + describe(node)};
  out.expression.text = node.Scalar();
  // A quoted scalar's mark is its opening quote; the expression starts one column later.
  if (node.Tag() == "!") out.pos.column += 1;
  out.expression.pos = out.pos;
  ExpressionCheck check = check_expression(out.expression.text);
  if (!check.ok) return ValueError{fmt::format("malformed expression '{}': {}", out.expression.text, check.message), check.position};
  out.expression.depends_on_time = check.uses_time;
  if (check.uses_time && spec.type == ValueType::static_expression)
    return ValueError{fmt::format("the expression '{}' uses t, but this value is a function of x, y, z only", out.expression.text)};
  return std::nullopt;
}

/// Converts `node` into `out` as `spec` says; the error when it cannot.
std::optional<ValueError> read_value(const KeySpec& spec, const YAML::Node& node, int dimension, Value& out) {
  out.node = node;
  bool empty_allowed = spec.type == ValueType::mapping || spec.type == ValueType::sequence;
  if (node.IsNull() && !empty_allowed) return ValueError{"missing value"};
  switch (spec.type) {
    case ValueType::number: return read_number(spec, node, out);
    case ValueType::integer: return read_integer(spec, node, out);
    case ValueType::boolean:
      if (!node.IsScalar() || !YAML::convert<bool>::decode(node, out.boolean))
        return ValueError{"expected true or false, got " + describe(node)};
      return std::nullopt;
    case ValueType::text:
      if (!node.IsScalar() || node.Scalar().empty()) return ValueError{"expected a name or text, got " + describe(node)};
      out.text = node.Scalar();
      return std::nullopt;
    case ValueType::choice: return read_choice(spec, node, out);
    case ValueType::point: return read_point(spec, node, dimension, out);
    case ValueType::names: return read_names(node, out);
    case ValueType::expression:
    case ValueType::static_expression: return read_expression(spec, node, out);
    case ValueType::mapping:
      if (!node.IsNull() && !node.IsMap()) return ValueError{"expected a mapping (key: value), got " + describe(node)};
      return std::nullopt;
    case ValueType::sequence:
      if (!node.IsNull() && !node.IsSequence()) return ValueError{"expected a list (- item), got " + describe(node)};
      return std::nullopt;
  }
  return std::nullopt;
}

std::string quoted_list(const std::vector<std::string_view>& keys, std::string_view conjunction) {
  std::string list;
  for (std::size_t k = 0; k < keys.size(); ++k)
    list += fmt::format("{}'{}'", k == 0 ? "" : (k + 1 == keys.size() ? conjunction : ", "), keys[k]);
  return list;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// MapReader

MapReader::MapReader(DeckContext& context, const YAML::Node& node, SourcePos owner, std::string path,
                     std::vector<KeySpec> keys)
    : context_(context), owner_(std::move(owner)), path_(std::move(path)), keys_(std::move(keys)) {
  if (!node.IsMap() && !node.IsNull()) {
    // Nothing inside can be checked; missing keys would only repeat this error.
    context_.error(node_pos(context_, node), path_, "expected a mapping (key: value), got " + describe(node));
    fill_defaults();
    return;
  }
  if (node.IsMap()) read_entries(node);
  check_groups_and_required();
  fill_defaults();
}

bool MapReader::applies(const KeySpec& spec) const {
  if (context_.dimension == 0) return true;
  return (spec.dimension == 0 || spec.dimension == context_.dimension) &&
         (spec.min_dimension == 0 || context_.dimension >= spec.min_dimension);
}

const KeySpec* MapReader::find_key(std::string_view key) const {
  for (const KeySpec& spec : keys_)
    if (spec.key == key) return &spec;
  return nullptr;
}

void MapReader::read_entries(const YAML::Node& node) {
  for (auto it = node.begin(); it != node.end(); ++it) {
    std::string key = it->first.IsScalar() ? it->first.Scalar() : std::string();
    SourcePos key_pos = node_pos(context_, it->first);
    const KeySpec* spec = find_key(key);
    if (spec == nullptr) {
      std::vector<std::string_view> known;
      for (const KeySpec& s : keys_)
        if (applies(s)) known.push_back(s.key);
      std::string_view guess = closest_match(key, known);
      if (!guess.empty()) misspelled_.insert(std::string(guess));
      context_.error(key_pos, path_,
                     fmt::format("unknown key '{}'{}", key, guess.empty() ? "" : fmt::format(" (did you mean '{}'?)", guess)));
      continue;
    }
    if (present_.count(key)) {
      context_.error(key_pos, path_, fmt::format("duplicate key '{}' (first given at line {})", key, present_[key].line));
      continue;
    }
    present_[key] = key_pos;
    if (!applies(*spec)) {
      context_.error(key_pos, path_, fmt::format("'{}' applies to {} decks only, and this deck has dimension {}", key,
                                                 spec->dimension != 0 ? fmt::format("{}D", spec->dimension) : "2D and 3D",
                                                 context_.dimension));
      continue;
    }
    Value value;
    value.key_pos = key_pos;
    value.pos = it->second.IsNull() ? key_pos : node_pos(context_, it->second);
    if (auto e = read_value(*spec, it->second, context_.dimension, value)) {
      SourcePos at = value.pos;
      at.column += e->column_offset;
      context_.error(at, path_of(key), e->message);
      continue;
    }
    given_.insert(key);
    values_[key] = std::move(value);
  }
}

void MapReader::check_groups_and_required() {
  // Keys outside a group are their own group of one; a group of keys applicable in this dimension
  // needs exactly one (required) or at most one (optional) key present.
  std::vector<std::string_view> groups_done;
  for (const KeySpec& spec : keys_) {
    if (!applies(spec)) continue;
    // Without a valid dimension (already reported) a key of one dimension is not demanded.
    if (context_.dimension == 0 && (spec.dimension != 0 || spec.min_dimension != 0)) continue;
    std::string_view group = spec.one_of.empty() ? spec.key : spec.one_of;
    if (std::find(groups_done.begin(), groups_done.end(), group) != groups_done.end()) continue;
    groups_done.push_back(group);

    std::vector<std::string_view> members, given;
    // A missing key is not reported again when the user tried to give it: misspelled, or in the
    // wrong dimension (a 2D segment pre-crack in a 3D deck), both already reported.
    bool attempted = false;
    for (const KeySpec& other : keys_) {
      bool same_group = spec.one_of.empty() ? &other == &spec : other.one_of == spec.one_of;
      if (!same_group) continue;
      attempted = attempted || misspelled_.count(other.key) || (present_.count(other.key) && !applies(other));
      if (!applies(other)) continue;
      members.push_back(other.key);
      if (present_.count(other.key)) given.push_back(other.key);
    }
    // Name the conflicting keys in document order, at the later one.
    auto position = [&](std::string_view key) {
      const SourcePos& at = present_.find(key)->second;
      return std::pair(at.line, at.column);
    };
    std::sort(given.begin(), given.end(), [&](auto a, auto b) { return position(a) < position(b); });
    if (given.size() > 1) {
      context_.error(present_.find(given[1])->second, path_, "give only one of " + quoted_list(given, " and "));
    } else if (given.empty() && spec.required && !attempted) {
      context_.error(owner_, path_,
                     members.size() == 1 ? fmt::format("missing required key '{}'", members[0])
                                         : "missing one of " + quoted_list(members, " or "));
    }
  }
}

void MapReader::fill_defaults() {
  for (const KeySpec& spec : keys_) {
    if (spec.default_yaml.empty() || present_.count(spec.key) || !applies(spec)) continue;
    Value value;
    auto e = read_value(spec, YAML::Load(std::string(spec.default_yaml)), context_.dimension, value);
    PERIDOT_REQUIRE(!e, "invalid default of key " + std::string(spec.key));
    values_[std::string(spec.key)] = std::move(value);
  }
}

bool MapReader::given(std::string_view key) const { return given_.find(key) != given_.end(); }

bool MapReader::present(std::string_view key) const { return present_.find(key) != present_.end(); }

const Value& MapReader::operator[](std::string_view key) const {
  PERIDOT_REQUIRE(find_key(key) != nullptr, "key " + std::string(key) + " is not in the schema of " + path_);
  static const Value empty;
  auto it = values_.find(key);
  return it == values_.end() ? empty : it->second;
}

std::optional<double> MapReader::optional_number(std::string_view key) const {
  if (!given(key)) return std::nullopt;
  return (*this)[key].number;
}

std::string MapReader::path_of(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

}  // namespace peridot
