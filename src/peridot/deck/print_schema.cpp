// `peridot info` and docs/deck.md, generated from the schema tables the parser validates against, and the
// model pages (`peridot info --model NAME`, docs/models/NAME.md): the registry's ModelDoc text around a
// syntax block and parameter tables generated from the same tables.
#include <algorithm>
#include <ostream>
#include <sstream>

#include <fmt/format.h>

#include "peridot/deck/deck.hpp"
#include "peridot/deck/schema.hpp"
#include "peridot/deck/model_schema.hpp"

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
  if (k.min_dimension == 2) text += fmt::format("{}2D and 3D only", text.empty() ? "" : "; ");
  return text;
}

using Row = std::vector<std::string>;
const Row header = {"key", "type", "unit", "range", "presence", "description"};

/// The SI unit of a key's value, or empty.
std::string unit_of(const KeySpec& k) {
  bool numeric = k.type == ValueType::number || k.type == ValueType::expression || k.type == ValueType::static_expression;
  return numeric && k.unit != Unit::none ? std::string(si_unit(k.unit)) : "";
}

Row row_of(const KeySpec& k, const std::vector<KeySpec>& section) {
  return {std::string(k.key), type_name(k), unit_of(k),
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
      for (const std::string& cell : r) {
        out << " ";
        for (char c : cell) out << (c == '|' ? "\\|" : std::string_view(&c, 1));
        out << " |";
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
                   bool markdown, std::string_view heading = "##") {
  out << (markdown ? fmt::format("{} `{}`\n\n{}\n\n", heading, title, description) : fmt::format("{}: {}\n", title, description));
  std::vector<Row> rows;
  for (const KeySpec& k : keys) rows.push_back(row_of(k, keys));
  print_table(out, rows, markdown);
}

std::string elastic_constants_rule(const ModelInfo& m) {
  std::string rule = m.bond_based ? "one modulus; ν is implied (1/4 in 3D and plane strain, 1/3 in plane stress)"
                                  : "any two of bulk_modulus, shear_modulus, youngs_modulus, poisson_ratio";
  if (m.one_dimensional) rule += "; in 1D (a bar) youngs_modulus alone";
  return rule;
}

void print_models(std::ostream& out, bool markdown) {
  out << (markdown ? "## Material models\n\n" : "material models (materials.<name>.model):\n");
  for (const ModelInfo& m : material_models()) {
    if (markdown) {
      out << fmt::format("### `{}`\n\n{}.\n\n- Elastic constants: {}.\n- Reference: {}.\n- Page: [models/{}.md](models/{}.md) "
                         "(`peridot info --model {}`).\n\n",
                         m.name, m.description, elastic_constants_rule(m), m.reference, m.name, m.name, m.name);
    } else {
      out << fmt::format("  {}: {}\n      elastic constants: {}\n      reference: {}\n      page: peridot info --model {}\n",
                         m.name, m.description, elastic_constants_rule(m), m.reference, m.name);
    }
    if (!m.keys.empty()) print_section(out, fmt::format("materials.<name> with model {}", m.name), "model parameters",
                                             m.keys, markdown);
  }
  out << "\n";
}

void print_units(std::ostream& out, bool markdown) {
  constexpr Unit units[] = {Unit::length,   Unit::area, Unit::time,     Unit::pressure,     Unit::density,
                            Unit::energy_per_area, Unit::velocity, Unit::force_density, Unit::rate,
                            Unit::temperature, Unit::specific_heat, Unit::thermal_expansion, Unit::mass};
  out << (markdown ? "## Units\n\nNumbers are SI. A number may carry a unit of its key's quantity, e.g. "
                     "`youngs_modulus: 72 GPa`, `spacing: 0.5 mm`, `density: 7.8 g/cm^3`:\n\n| quantity | SI | accepted |\n|---|---|---|\n"
                   : "units: numbers are SI; a number may carry a unit of its key's quantity (72 GPa, 0.5 mm):\n");
  for (Unit u : units)
    out << (markdown ? fmt::format("| {} | {} | {} |\n", quantity_name(u), si_unit(u), accepted_units(u))
                     : fmt::format("  {:<16} {}\n", quantity_name(u), accepted_units(u)));
  out << "\n";
}

/// The YAML skeleton of a section: `key: value` placeholders from the KeySpecs, nested mappings from their
/// own sections, and the presence of each key as a comment.
void print_syntax(std::ostream& out, std::string_view path, const std::vector<KeySpec>& keys, const ModelInfo& model,
                  int indent) {
  for (const KeySpec& k : keys) {
    const bool nested = k.type == ValueType::mapping;
    std::string value = k.key == "model" ? std::string(model.name) : nested ? "" : type_name(k);
    if (const std::string unit = unit_of(k); !unit.empty()) value += fmt::format(" ({})", unit);
    std::string line = fmt::format("{}{}:{}{}", std::string(indent, ' '), k.key, value.empty() ? "" : " ", value);
    const std::string comment = k.key == "model" ? "" : presence(k, keys);
    out << line << (comment.empty() ? "" : std::string(width(line) < 56 ? 56 - width(line) : 2, ' ') + "# " + comment)
        << "\n";
    if (nested) {
      const std::string sub = fmt::format("{}.{}", path, k.key);
      print_syntax(out, sub, deck_section(sub).keys, model, indent + 2);
    }
  }
}

}  // namespace

void print_model_page(std::ostream& out, const ModelInfo& model, bool markdown) {
  auto heading = [&](std::string_view title) { out << (markdown ? fmt::format("## {}\n\n", title) : fmt::format("{}\n\n", title)); };
  auto text = [&](std::string_view body) { out << body << "\n\n"; };
  auto code = [&](auto&& print) {
    std::ostringstream block;
    print(block);
    if (markdown) {
      out << "```yaml\n" << block.str() << "```\n\n";
      return;
    }
    std::istringstream lines(block.str());
    for (std::string line; std::getline(lines, line);) out << "    " << line << "\n";
    out << "\n";
  };

  out << (markdown ? fmt::format("# Material model `{}`\n\nGenerated by `peridot info --model {} --markdown` from the model "
                                 "registry and the schema the parser validates against.\n\n{}.\n\n",
                                 model.name, model.name, model.description)
                   : fmt::format("material model {}: {}\n\n", model.name, model.description));
  heading("Syntax");
  code([&](std::ostream& block) {
    block << "materials:\n  <name>:\n";
    print_syntax(block, "materials.<name>", material_keys(model), model, 4);
  });
  heading("Example");
  code([&](std::ostream& block) { block << model.doc.example << "\n"; });
  heading("Description");
  text(model.doc.summary);
  text(fmt::format("Elastic constants: {}.", elastic_constants_rule(model)));
  heading("Equations");
  text(model.doc.equations);
  heading("Bond failure");
  text(damage_doc());
  heading("Parameters");
  print_section(out, "materials.<name>", fmt::format("a material of model {}", model.name), material_keys(model), markdown, "###");
  const SectionSpec& damage = deck_section("materials.<name>.damage");
  print_section(out, damage.path, damage.description, damage.keys, markdown, "###");
  heading("Restrictions");
  text(model.doc.restrictions);
  heading("References");
  out << "- " << model.reference << "\n";
  for (std::string_view reference : model.doc.further_references) out << "- " << reference << "\n";
}

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
