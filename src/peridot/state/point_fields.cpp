#include "peridot/state/point_fields.hpp"

#include <stdexcept>

namespace peridot {

namespace {

std::vector<PointField> make_fields() {
  using S = FieldScope;
  std::vector<PointField> fields = {
      {"displacement", true, "m", "u", S::always, true, false, [](State& s) { return FieldStorage{&s.u, nullptr}; }},
      {"velocity", true, "m/s", "v (relaxation: the load step's mean)", S::always, true, false,
       [](State& s) { return FieldStorage{&s.v, nullptr}; }},
      {"force_density", true, "N/m³", "internal force density f", S::always, true, false,
       [](State& s) { return FieldStorage{&s.force, nullptr}; }},
      {"damage", false, "-", "φ, volume-weighted fraction of broken bonds", S::always, true, false,
       [](State& s) { return FieldStorage{nullptr, &s.damage}; }},
      {"dilatation", false, "-", "θ (2D: in-plane)", S::always, true, false,
       [](State& s) { return FieldStorage{nullptr, &s.dilatation}; }},
      {"weighted_volume", false, "m⁵", "m (2D: m⁴·h)", S::always, true, true,
       [](State& s) { return FieldStorage{nullptr, &s.weighted_volume}; }},
      {"volume", false, "m³", "V (2D: area × h)", S::always, false, true, nullptr},
      {"equivalent_plastic_strain", false, "-", "ε̄p", S::inelastic, true, false,
       [](State& s) { return FieldStorage{nullptr, &s.history.plastic_strain}; }},
      {"dissipation", false, "J/m³", "dissipated energy density since t = 0", S::inelastic, true, false,
       [](State& s) { return FieldStorage{nullptr, &s.history.dissipation}; }},
  };
  // The correspondence fields, filled when an Exodus frame is written (State::point_outputs).
  for (const std::string& name : correspondence_output_names()) {  // a static list: the views stay valid
    const std::string_view unit = name.rfind("cauchy", 0) == 0 || name == "von_mises_stress" ? "Pa" : "-";
    fields.push_back({name, false, unit, "correspondence: F, σ, von Mises stress, Green–Lagrange strain",
                      S::correspondence, false, false, nullptr});
  }
  fields.push_back({"temperature", false, "K", "T: the deck's temperature field, or a J2 law's with thermal softening (0 elsewhere)", S::thermal, false,
                    false, nullptr});
  fields.push_back({"material_damage", false, "-", "D of a correspondence law's johnson_cook_damage (0 elsewhere)",
                    S::material_damage, false, false, nullptr});
  fields.push_back({"fragment", false, "-", "fragment label: the smallest input id of its points", S::damage, true,
                    false, [](State& s) { return FieldStorage{nullptr, &s.fragment}; }});
  return fields;
}

}  // namespace

double PointField::value(const State& state, std::size_t i, int d) const {
  const ConstFieldStorage where = in(state);
  if (where.vector) return (*where.vector)(i, d);
  if (where.scalar) return where.scalar->empty() ? 0.0 : (*where.scalar)[i];
  throw std::logic_error("point field '" + std::string(name) + "' is not stored in State");
}

const std::vector<PointField>& point_fields() {
  static const std::vector<PointField> fields = make_fields();
  return fields;
}

const PointField* find_point_field(std::string_view name, int* component) {
  for (const PointField& field : point_fields()) {
    if (!field.vector && field.name == name) {
      if (component) *component = 0;
      return &field;
    }
    if (field.vector && name.size() == field.name.size() + 2 && name.substr(0, field.name.size()) == field.name &&
        name[field.name.size()] == '_' && name.back() >= 'x' && name.back() <= 'z') {
      if (component) *component = name.back() - 'x';
      return &field;
    }
  }
  return nullptr;
}

const std::vector<std::string>& probe_field_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const PointField& field : point_fields())
      if (field.probe)
        for (const std::string& name : variable_names(field, 3)) all.push_back(name);
    return all;
  }();
  return names;
}

std::vector<std::string> variable_names(const PointField& field, int dimension) {
  if (!field.vector) return {std::string(field.name)};
  std::vector<std::string> names;
  for (int d = 0; d < dimension; ++d) names.push_back(std::string(field.name) + "_" + static_cast<char>('x' + d));
  return names;
}

}  // namespace peridot
