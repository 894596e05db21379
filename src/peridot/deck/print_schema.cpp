// `peridot info` and docs/deck.md, generated from the schema tables the parser validates against.
#include <algorithm>
#include <ostream>

#include <fmt/format.h>

#include "peridot/deck/deck.hpp"
#include "peridot/deck/schema.hpp"
#include "peridot/materials/registry.hpp"

namespace peridot {

namespace {

std::string type_name(const KeySpec& k) {
  switch (k.type) {
    case ValueType::number: return "number";
    case ValueType::integer: return "integer";
    case ValueType::boolean: return "true/false";
    case ValueType::text: return "text";
    case ValueType::choice: return fmt::format("{}", fmt::join(k.choices, " | "));
    case ValueType::point: return "[x, y, z]";
    case ValueType::names: return "list of names";
    case ValueType::expression: return "f(x, y, z, t)";
    case ValueType::static_expression: return "f(x, y, z)";
    case ValueType::mapping: return "mapping";
    case ValueType::sequence: return "list";
  }
  return "";
}

/// "required", "one of horizon_factor, horizon (required)", the default, or empty.
std::string presence(const KeySpec& k, const std::vector<KeySpec>& section) {
  std::string text;
  if (!k.one_of.empty()) {
    std::vector<std::string_view> group;
    for (const KeySpec& other : section)
      if (other.one_of == k.one_of) group.push_back(other.key);
    text = fmt::format("one of {}{}", fmt::join(group, ", "), k.required ? " (required)" : "");
  } else if (k.required) {
    text = "required";
  } else if (!k.default_yaml.empty()) {
    text = fmt::format("default {}", k.default_yaml);
  }
  if (k.dimension != 0) text += fmt::format("{}{}D only", text.empty() ? "" : "; ", k.dimension);
  return text;
}

using Row = std::vector<std::string>;
const Row header = {"key", "type", "unit", "range", "presence", "description"};

Row row_of(const KeySpec& k, const std::vector<KeySpec>& section) {
  bool has_unit = k.type == ValueType::number || k.type == ValueType::expression || k.type == ValueType::static_expression;
  return {std::string(k.key), type_name(k), has_unit && k.unit != Unit::none ? std::string(si_unit(k.unit)) : "",
          k.range.str(), presence(k, section), std::string(k.description)};
}

/// Display width: count code points, not bytes (δ, ν, ≥ are two or three bytes).
std::size_t width(const std::string& s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

void print_table(std::ostream& out, const std::vector<Row>& rows, bool markdown) {
  if (markdown) {
    auto line = [&](const Row& r) {
      out << "|";
      for (std::string cell : r) {
        for (std::size_t at = cell.find('|'); at != std::string::npos; at = cell.find('|', at + 2)) cell.insert(at, "\\");
        out << " " << cell << " |";
      }
      out << "\n";
    };
    line(header);
    line(Row(header.size(), "---"));
    for (const Row& r : rows) line(r);
    out << "\n";
    return;
  }
  std::vector<std::size_t> widths(header.size(), 0);
  for (const Row& r : rows)
    for (std::size_t c = 0; c < r.size(); ++c) widths[c] = std::max(widths[c], width(r[c]));
  for (const Row& r : rows) {
    out << "  ";
    for (std::size_t c = 0; c < r.size(); ++c)
      out << r[c] << (c + 1 < r.size() ? std::string(widths[c] - width(r[c]) + 2, ' ') : "\n");
  }
  out << "\n";
}

void print_section(std::ostream& out, std::string_view title, std::string_view description, const std::vector<KeySpec>& keys,
                   bool markdown) {
  out << (markdown ? fmt::format("## `{}`\n\n{}\n\n", title, description) : fmt::format("{}: {}\n", title, description));
  std::vector<Row> rows;
  for (const KeySpec& k : keys) rows.push_back(row_of(k, keys));
  print_table(out, rows, markdown);
}

void print_models(std::ostream& out, bool markdown) {
  out << (markdown ? "## Material models\n\n" : "material models (materials.<name>.model):\n");
  for (const ModelInfo& m : material_models()) {
    std::string elastic = m.bond_based ? "one modulus; ν is implied (1/4 in 3D and plane strain, 1/3 in plane stress)"
                                       : "any two of bulk_modulus, shear_modulus, youngs_modulus, poisson_ratio";
    if (markdown) {
      out << fmt::format("### `{}`\n\n{}.\n\n- Elastic constants: {}.\n- Reference: {}.\n\n", m.name, m.description, elastic,
                         m.reference);
    } else {
      out << fmt::format("  {}: {}\n      elastic constants: {}\n      reference: {}\n", m.name, m.description, elastic,
                         m.reference);
    }
    if (!m.extra_keys.empty()) print_section(out, fmt::format("materials.<name> with model {}", m.name), "model parameters",
                                             m.extra_keys, markdown);
  }
  out << "\n";
}

void print_units(std::ostream& out, bool markdown) {
  constexpr Unit units[] = {Unit::length,   Unit::time,     Unit::pressure,     Unit::density,
                            Unit::energy_per_area, Unit::velocity, Unit::force_density, Unit::rate};
  out << (markdown ? "## Units\n\nNumbers are SI. A number may carry a unit of its key's quantity, e.g. "
                     "`youngs_modulus: 72 GPa`, `spacing: 0.5 mm`, `density: 7.8 g/cm^3`:\n\n| quantity | SI | accepted |\n|---|---|---|\n"
                   : "units: numbers are SI; a number may carry a unit of its key's quantity (72 GPa, 0.5 mm):\n");
  for (Unit u : units)
    out << (markdown ? fmt::format("| {} | {} | {} |\n", quantity_name(u), si_unit(u), accepted_units(u))
                     : fmt::format("  {:<16} {}\n", quantity_name(u), accepted_units(u)));
  out << "\n";
}

}  // namespace

void print_schema(std::ostream& out, bool markdown) {
  out << (markdown ? "# Peridot deck reference\n\nGenerated by `peridot info --markdown` from the schema the parser "
                     "validates against. Keys are snake_case; expressions are muParser expressions of x, y, z (m) "
                     "and t (s) with the constant pi.\n\n"
                   : "Peridot deck reference (from the schema the parser validates against)\n\n");
  print_units(out, markdown);
  for (const SectionSpec& section : deck_sections())
    print_section(out, section.path.empty() ? "(top level)" : section.path, section.description, section.keys, markdown);
  print_models(out, markdown);
}

}  // namespace peridot
