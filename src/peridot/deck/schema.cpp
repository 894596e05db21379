#include "peridot/deck/schema.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/deck/model_schema.hpp"
#include "peridot/deck/solver_schema.hpp"
#include "peridot/state/point_fields.hpp"

namespace peridot {

// ---------------------------------------------------------------------------------------------
// Ranges

bool Range::contains(double v) const {
  bool above = lo_open ? v > lo : v >= lo;
  bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

bool Range::is_everything() const { return std::isinf(lo) && std::isinf(hi); }

std::string Range::str() const {
  if (is_everything()) return "";
  if (std::isinf(hi)) return fmt::format("{} {}", lo_open ? ">" : "≥", lo);
  if (std::isinf(lo)) return fmt::format("{} {}", hi_open ? "<" : "≤", hi);
  return fmt::format("{}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
}

// ---------------------------------------------------------------------------------------------
// Units: a small table of spellings per quantity, not a unit algebra.

namespace {

struct UnitInfo {
  Unit unit;
  std::string_view quantity;
  std::vector<std::pair<std::string_view, double>> spellings;  ///< first = SI
};

const std::vector<UnitInfo>& unit_table() {
  static const std::vector<UnitInfo> table = {
      {Unit::none, "dimensionless", {{"-", 1.0}}},
      {Unit::length, "length", {{"m", 1.0}, {"cm", 1e-2}, {"mm", 1e-3}, {"um", 1e-6}, {"µm", 1e-6}, {"nm", 1e-9}}},
      {Unit::area, "area", {{"m^2", 1.0}, {"cm^2", 1e-4}, {"mm^2", 1e-6}}},
      {Unit::time, "time", {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}, {"µs", 1e-6}, {"ns", 1e-9}, {"min", 60.0}, {"h", 3600.0}}},
      {Unit::pressure, "pressure", {{"Pa", 1.0}, {"kPa", 1e3}, {"MPa", 1e6}, {"GPa", 1e9}}},
      {Unit::density, "density", {{"kg/m^3", 1.0}, {"g/cm^3", 1e3}}},
      {Unit::energy_per_area, "energy per area", {{"J/m^2", 1.0}, {"N/m", 1.0}, {"kJ/m^2", 1e3}}},
      {Unit::velocity, "velocity", {{"m/s", 1.0}, {"mm/s", 1e-3}, {"km/s", 1e3}}},
      {Unit::force_density, "force density", {{"N/m^3", 1.0}, {"kN/m^3", 1e3}, {"MN/m^3", 1e6}}},
      {Unit::rate, "rate", {{"1/s", 1.0}, {"1/ms", 1e3}, {"1/us", 1e6}}},
      {Unit::temperature, "temperature", {{"K", 1.0}}},
      {Unit::specific_heat, "specific heat", {{"J/(kg K)", 1.0}, {"J/kg/K", 1.0}, {"kJ/(kg K)", 1e3}}},
      {Unit::thermal_expansion, "thermal expansion coefficient", {{"1/K", 1.0}}},
      {Unit::mass, "mass", {{"kg", 1.0}, {"g", 1e-3}}},
  };
  return table;
}

const UnitInfo& unit_info(Unit unit) {
  for (const UnitInfo& info : unit_table())
    if (info.unit == unit) return info;
  PERIDOT_REQUIRE(false, "unit missing from the unit table");
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string_view si_unit(Unit unit) { return unit_info(unit).spellings.front().first; }
std::string_view quantity_name(Unit unit) { return unit_info(unit).quantity; }

std::string accepted_units(Unit unit) {
  std::string list;
  for (const auto& [spelling, factor] : unit_info(unit).spellings)
    list += (list.empty() ? "" : ", ") + std::string(spelling);
  return list;
}

Quantity parse_quantity(std::string_view text, Unit unit) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);  // from_chars rejects a leading '+'
  double number = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (ec != std::errc() || !std::isfinite(number))
    return {std::nullopt, unit == Unit::none ? fmt::format("expected a number, got '{}'", text)
                                             : fmt::format("expected a number in {}, got '{}'", si_unit(unit), text)};
  std::string_view suffix = trim(text.substr(static_cast<std::size_t>(end - text.data())));
  if (suffix.empty()) return {number, ""};

  const UnitInfo& expected = unit_info(unit);
  if (unit == Unit::none) return {std::nullopt, fmt::format("takes no unit, but '{}' is given", suffix)};
  for (const auto& [spelling, factor] : expected.spellings)
    if (spelling == suffix) return {number * factor, ""};
  for (const UnitInfo& other : unit_table())
    for (const auto& [spelling, factor] : other.spellings)
      if (spelling == suffix)
        return {std::nullopt, fmt::format("'{}' is a unit of {}, but a {} is expected (in {}; accepted: {})", suffix,
                                          other.quantity, expected.quantity, si_unit(unit), accepted_units(unit))};
  return {std::nullopt, fmt::format("unknown unit '{}' (a {} is expected; accepted: {})", suffix, expected.quantity,
                                    accepted_units(unit))};
}

// ---------------------------------------------------------------------------------------------
// Did you mean

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      diagonal = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, substitution});
    }
  }
  return row[b.size()];
}

std::string_view closest_match(std::string_view word, const std::vector<std::string_view>& candidates) {
  // A typo changes a few letters (about one edit per three characters) or cuts a word short.
  std::size_t best = std::max<std::size_t>(2, word.size() / 3) + 1;
  std::string_view match;
  for (std::string_view candidate : candidates) {
    std::size_t d = edit_distance(word, candidate);
    if (d < best) best = d, match = candidate;
  }
  if (!match.empty() || word.size() < 3) return match;
  for (std::string_view candidate : candidates)
    if (candidate.starts_with(word)) return candidate;
  return match;
}

// ---------------------------------------------------------------------------------------------
// The sections. Keys that must appear together or exclusively share a `one_of` group name.

namespace {

using VT = ValueType;

KeySpec horizon_key(bool required) {
  return {.key = "horizon", .unit = Unit::length, .range = positive,
          .description = "horizon δ (m); or horizon_factor", .required = required, .one_of = "horizon"};
}
KeySpec horizon_factor_key(bool required) {
  return {.key = "horizon_factor", .range = positive,
          .description = "δ / spacing (3.015 is common); or horizon", .required = required, .one_of = "horizon"};
}

std::vector<KeySpec> component_keys(Unit unit, ValueType type) {
  return {{.key = "x", .type = type, .unit = unit, .description = "x component"},
          {.key = "y", .type = type, .unit = unit, .description = "y component", .min_dimension = 2},
          {.key = "z", .type = type, .unit = unit, .description = "z component", .dimension = 3}};
}

std::vector<KeySpec> with_node_set(std::vector<KeySpec> keys, bool required) {
  keys.insert(keys.begin(), {.key = "node_set", .type = VT::text,
                             .description = required ? "node set it applies to" : "node set it applies to; default every point",
                             .required = required});
  return keys;
}

/// The fields a history probe may sample (state/point_fields.hpp).
std::vector<std::string_view> probe_choices() {
  std::vector<std::string_view> choices;
  for (const std::string& name : probe_field_names()) choices.push_back(name);
  return choices;
}

std::vector<SectionSpec> make_sections() {
  std::vector<SectionSpec> s;
  s.push_back({"", "top level of the deck",
               {{.key = "discretization", .type = VT::mapping, .description = "dimension, lattice spacing, horizon", .required = true},
                {.key = "materials", .type = VT::mapping, .description = "named materials", .required = true},
                {.key = "bodies", .type = VT::mapping, .description = "named bodies: a shape or a point file, and a material", .required = true},
                {.key = "precracks", .type = VT::sequence, .description = "bonds crossing these are removed at start"},
                {.key = "node_sets", .type = VT::mapping, .description = "named sets of points"},
                {.key = "no_fail", .type = VT::names, .description = "node sets whose bonds never break"},
                {.key = "initial_conditions", .type = VT::sequence, .description = "initial displacement or velocity"},
                {.key = "boundary_conditions", .type = VT::sequence, .description = "prescribed displacement or velocity"},
                {.key = "body_forces", .type = VT::sequence, .description = "force per volume"},
                {.key = "tractions", .type = VT::sequence, .description = "force per area, carried by a layer of points"},
                {.key = "rigid_walls", .type = VT::sequence, .description = "rigid frictionless planes the points cannot cross"},
                {.key = "rigid_bodies", .type = VT::sequence,
                 .description = "rigid spheres, cylinders, boxes and planes: fixed, moved as prescribed, or free"},
                {.key = "contact", .type = VT::mapping,
                 .description = "short-range forces between points that are not bonded (fragments, crack faces, bodies)"},
                {.key = "temperature", .type = VT::mapping, .description = "a prescribed temperature field: thermal strain, WLF shift"},
                {.key = "solver", .type = VT::mapping, .description = "explicit dynamics or quasi-static relaxation", .required = true},
                {.key = "decomposition", .type = VT::mapping, .description = "how a distributed run (mpirun) splits the points"},
                {.key = "output", .type = VT::mapping, .description = "Exodus fields, CSV history, progress"}}});
  s.push_back({"discretization", "the point lattice",
               {{.key = "dimension", .type = VT::integer, .range = {1, 3}, .description = "1 (a bar), 2 or 3", .required = true},
                {.key = "spacing", .unit = Unit::length, .range = positive,
                 .description = "lattice spacing Δx (m); required unless every body uses points_file or mesh"},
                horizon_factor_key(true),
                horizon_key(true),
                {.key = "plane", .type = VT::choice, .description = "2D idealisation", .required = true, .dimension = 2,
                 .choices = {"stress", "strain"}},
                {.key = "thickness", .unit = Unit::length, .default_yaml = "1", .range = positive,
                 .description = "out-of-plane thickness h (m)", .dimension = 2},
                {.key = "area", .unit = Unit::area, .default_yaml = "1", .range = positive,
                 .description = "cross-sectional area A of the bar (m²)", .dimension = 1},
                {.key = "lattice_origin", .type = VT::point, .default_yaml = "[0, 0, 0]",
                 .description = "lattice points sit at origin + (i + ½)Δx"},
                {.key = "jitter", .default_yaml = "0", .range = {0, 0.5, false, true},
                 .description = "random shift of each point, fraction of Δx"},
                {.key = "seed", .type = VT::integer, .default_yaml = "1", .range = non_negative,
                 .description = "random seed of the jitter (a point's shift depends on the seed and its lattice site only)"},
                {.key = "partial_volume", .type = VT::choice, .default_yaml = "none",
                 .description = "weigh bonds by the part of the neighbour's cell inside the horizon: none; extended "
                                "(also bonds cells centred up to δ + Δx/2, converges); horizon (bonds within δ only, "
                                "as LAMMPS PERI)",
                 .choices = {"none", "extended", "horizon"}},
                {.key = "quadrature", .type = VT::choice, .default_yaml = "one_point",
                 .description = "how a bond sum weighs a neighbour: one_point (its volume); isotropic (times a "
                                "direction weight fitted so that the lattice family's stiffness is isotropic and equals "
                                "the continuum's: a solution converges to classical elasticity at second order in δ at "
                                "fixed δ/Δx; pmb and the lps models on lattice bodies; docs/algorithms.md)",
                 .choices = {"one_point", "isotropic"}}}});
  s.push_back({"materials.<name>", "a material: a model from the registry and its parameters", common_material_keys()});
  s.push_back({"materials.<name>.damage", "bond breaking; omit for no damage", damage_keys()});
  for (const ModelInfo& model : material_models())  // the models' nested sections, each path once
    for (const SectionSpec& section : model.sections)
      if (std::none_of(s.begin(), s.end(), [&](const SectionSpec& known) { return known.path == section.path; }))
        s.push_back(section);
  s.push_back({"bodies.<name>", "a body: points filling a shape on the lattice, or read from a point file or a mesh",
               {{.key = "material", .type = VT::text, .description = "name of a material", .required = true},
                {.key = "shape", .type = VT::mapping, .description = "a shape (see shape)", .required = true, .one_of = "source"},
                {.key = "points_file", .type = VT::text, .description = "text file, columns x y [z] volume [block]; relative to the deck",
                 .required = true, .one_of = "source"},
                {.key = "mesh", .type = VT::mapping, .description = "a mesh file (see bodies.<name>.mesh)", .required = true,
                 .one_of = "source"},
                {.key = "block", .type = VT::integer, .description = "with points_file: keep only rows of this block"},
                horizon_factor_key(false),
                horizon_key(false),
                {.key = "volume_constraint", .unit = Unit::length, .range = positive,
                 .description = "thickness of a layer of points added outside the shape (the lattice sites within this "
                                "distance of the body's own), with the body's material, as the node set "
                                "<body>_constraint: prescribe its displacement in boundary_conditions for the nonlocal "
                                "volume constraint (δ for bond-based models, 2δ for state-based ones, whose forces read "
                                "the neighbours' dilatations); shape bodies only"}}});
  s.push_back({"bodies.<name>.mesh",
               "a mesh file: one point per element at its centroid with the element's volume (hexahedra, tetrahedra and "
               "prisms of 8, 4 and 6 nodes; quadrilaterals and triangles of 4 and 3 nodes in 2D, times the thickness), "
               "or one per Exodus SPHERE element (its node, and its volume attribute as Peridigm and Sierra write it)",
               {{.key = "file", .type = VT::text, .description = "the mesh file, relative to the deck", .required = true},
                {.key = "format", .type = VT::choice,
                 .description = "exodus (.e, .exo, .g, .gen), abaqus (.inp) or gmsh (.msh, format 4.1, ASCII or binary); by "
                                "default from the extension",
                 .choices = {"exodus", "abaqus", "gmsh"}},
                {.key = "block", .type = VT::text,
                 .description = "what this body takes, by name: an Exodus element block (or block_<id>), an Abaqus element "
                                "set, a Gmsh physical group (or entity_<tag>); every element when omitted"},
                {.key = "scale", .default_yaml = "1", .range = positive,
                 .description = "coordinates are multiplied by this: 1e-3 for a mesh drawn in millimetres"}}});
  s.push_back({"shape", "exactly one of these keys; in 2D box → rectangle, cylinder and sphere → disc, tube → annulus",
               {{.key = "box", .type = VT::mapping, .description = "see shape.box", .required = true, .one_of = "shape"},
                {.key = "cylinder", .type = VT::mapping, .description = "see shape.cylinder", .required = true, .one_of = "shape"},
                {.key = "tube", .type = VT::mapping, .description = "see shape.tube", .required = true, .one_of = "shape"},
                {.key = "sphere", .type = VT::mapping, .description = "see shape.sphere", .required = true, .one_of = "shape"},
                {.key = "union", .type = VT::sequence, .description = "list of shapes: points in any", .required = true, .one_of = "shape"},
                {.key = "difference", .type = VT::sequence, .description = "list of shapes: the first minus all others",
                 .required = true, .one_of = "shape"}}});
  s.push_back({"shape.box", "axis-aligned box (rectangle in 2D)",
               {{.key = "min", .type = VT::point, .description = "lowest corner (m)", .required = true},
                {.key = "max", .type = VT::point, .description = "highest corner (m)", .required = true}}});
  s.push_back({"shape.cylinder", "solid cylinder (disc in 2D)",
               {{.key = "center", .type = VT::point, .description = "centre of the base (m)", .required = true},
                {.key = "axis", .type = VT::point, .default_yaml = "[0, 0, 1]", .description = "direction of the axis", .dimension = 3},
                {.key = "radius", .unit = Unit::length, .range = positive, .description = "radius (m)", .required = true},
                {.key = "length", .unit = Unit::length, .range = positive, .description = "length along the axis (m)",
                 .required = true, .dimension = 3}}});
  s.push_back({"shape.tube", "hollow cylinder (annulus in 2D)",
               {{.key = "center", .type = VT::point, .description = "centre of the base (m)", .required = true},
                {.key = "axis", .type = VT::point, .default_yaml = "[0, 0, 1]", .description = "direction of the axis", .dimension = 3},
                {.key = "inner_radius", .unit = Unit::length, .range = non_negative, .description = "inner radius (m)", .required = true},
                {.key = "outer_radius", .unit = Unit::length, .range = positive, .description = "outer radius (m)", .required = true},
                {.key = "length", .unit = Unit::length, .range = positive, .description = "length along the axis (m)",
                 .required = true, .dimension = 3}}});
  s.push_back({"shape.sphere", "ball (disc in 2D)",
               {{.key = "center", .type = VT::point, .description = "centre (m)", .required = true},
                {.key = "radius", .unit = Unit::length, .range = positive, .description = "radius (m)", .required = true}}});
  s.push_back({"precracks[i]", "a pre-crack: bonds crossing it are removed",
               {{.key = "at", .unit = Unit::length, .description = "1D: the position x on the bar that it cuts (m)",
                 .required = true, .one_of = "crack", .dimension = 1},
                {.key = "segment", .type = VT::mapping, .description = "2D: a segment", .required = true, .one_of = "crack", .dimension = 2},
                {.key = "rectangle", .type = VT::mapping, .description = "3D: a parallelogram", .required = true, .one_of = "crack",
                 .dimension = 3}}});
  s.push_back({"precracks[i].segment", "segment from `from` to `to`",
               {{.key = "from", .type = VT::point, .description = "first end (m)", .required = true},
                {.key = "to", .type = VT::point, .description = "second end (m)", .required = true}}});
  s.push_back({"precracks[i].rectangle", "parallelogram origin + s·edge1 + t·edge2, s, t ∈ [0, 1]",
               {{.key = "origin", .type = VT::point, .description = "a corner (m)", .required = true},
                {.key = "edge1", .type = VT::point, .description = "first edge vector (m)", .required = true},
                {.key = "edge2", .type = VT::point, .description = "second edge vector (m)", .required = true}}});
  s.push_back({"node_sets.<name>", "a named set of points",
               {{.key = "shape", .type = VT::mapping, .description = "points inside this shape (see shape)", .required = true, .one_of = "source"},
                {.key = "ids_file", .type = VT::text, .description = "text file of 0-based point ids; relative to the deck",
                 .required = true, .one_of = "source"},
                {.key = "mesh_set", .type = VT::text,
                 .description = "a node set, side set or element set of the bodies' meshes: the points of its elements (of a node "
                                "set: of the elements with a node in it)",
                 .required = true, .one_of = "source"},
                {.key = "bodies", .type = VT::names, .description = "with shape or mesh_set: only points of these bodies (default all)"}}});
  s.push_back({"initial_conditions[i]", "initial displacement or velocity, functions of x, y, z",
               with_node_set({{.key = "displacement", .type = VT::mapping, .description = "components (m)", .required = true, .one_of = "kind"},
                              {.key = "velocity", .type = VT::mapping, .description = "components (m/s)", .required = true, .one_of = "kind"}},
                             false)});
  s.push_back({"initial_conditions[i].displacement", "initial displacement (m)", component_keys(Unit::length, VT::static_expression)});
  s.push_back({"initial_conditions[i].velocity", "initial velocity (m/s)", component_keys(Unit::velocity, VT::static_expression)});
  s.push_back({"boundary_conditions[i]", "prescribed displacement or velocity, functions of x, y, z, t",
               with_node_set({{.key = "displacement", .type = VT::mapping, .description = "components (m)", .required = true, .one_of = "kind"},
                              {.key = "velocity", .type = VT::mapping, .description = "components (m/s)", .required = true, .one_of = "kind"}},
                             true)});
  s.push_back({"boundary_conditions[i].displacement", "prescribed displacement (m)", component_keys(Unit::length, VT::expression)});
  s.push_back({"boundary_conditions[i].velocity", "prescribed velocity (m/s)", component_keys(Unit::velocity, VT::expression)});
  s.push_back({"body_forces[i]", "force per volume (N/m^3), functions of x, y, z, t",
               with_node_set(component_keys(Unit::force_density, VT::expression), false)});
  {
    std::vector<KeySpec> keys = with_node_set(component_keys(Unit::pressure, VT::expression), true);
    keys.insert(keys.begin() + 1, {.key = "depth", .unit = Unit::length, .range = positive,
                                   .description = "depth d of the layer normal to the surface; default the lattice spacing "
                                                  "(one row of points)"});
    s.push_back({"tractions[i]",
                 "a traction t (Pa, functions of x, y, z, t) carried by the node set, a layer of points of depth d next to "
                 "the loaded surface: each of its points gets the body force t/d (Madenci & Oterkus's boundary layer; the "
                 "layer may be a fictitious extension of the body beyond the surface)",
                 std::move(keys)});
  }
  s.push_back({"rigid_walls[i]",
               "a rigid, frictionless plane (an anvil): penalty force density κ·(penetration) along the normal on every "
               "point behind it, κ = stiffness_factor × the Silling–Askari stiffness Σ V c/ξ of a full family of the point's "
               "block; the force on the wall goes to the history as wall_<name>_x/_y/_z",
               {{.key = "name", .type = VT::text, .description = "name of the wall (history columns)", .required = true},
                {.key = "point", .type = VT::point, .description = "a point of the plane at t = 0 (m)", .required = true},
                {.key = "normal", .type = VT::point, .description = "normal of the plane, toward the bodies (any length)",
                 .required = true},
                {.key = "speed", .unit = Unit::velocity, .default_yaml = "0",
                 .description = "velocity of the plane along its normal (m/s)"},
                {.key = "stiffness_factor", .default_yaml = "0.5", .range = positive,
                 .description = "penalty stiffness as a fraction of a full family's; 0.5 keeps a surface point no stiffer "
                                "than an interior one, so the stable time step holds"},
                {.key = "contact", .type = VT::choice, .default_yaml = "penalty",
                 .description = "penalty: the penalty force alone; symmetry: besides it, the correspondence points within a "
                                "horizon of the plane are bonded to the mirror images of their neighbours, so the plane "
                                "loads the body as a symmetry plane does (its mirror image pressed against it), from t = 0 "
                                "until the body moves away from it while pulling on it (it leaves); the body's surface "
                                "must lie on the plane at t = 0 (its nearest points half a spacing from it) and the wall must be "
                                "at rest",
                 .choices = {"penalty", "symmetry"}}}});
  s.push_back({"contact",
               "short-range forces (Silling–Askari): two points that are not bonded (never bonded, or their bond broke), "
               "of one body or of two, repel each other when their distance falls below d_ij = min(reference_fraction "
               "× |ξ_ij|, distance_factor × (r_i + r_j)), r the node radius (half the spacing), with the pair force density "
               "(c_S/δ)(d_ij − |y_j − y_i|) along the line between them, c_S = stiffness_factor × c and c/δ the softer "
               "block's; optional Coulomb friction per pair of bodies",
               {{.key = "stiffness_factor", .default_yaml = "15", .range = positive,
                 .description = "c_S / c, c the block's micromodulus (15: Silling and Askari, LAMMPS)"},
                {.key = "distance_factor", .default_yaml = "1.35", .range = positive,
                 .description = "contact distance as a multiple of r_i + r_j, the spacing on a lattice (1.35: LAMMPS)"},
                {.key = "reference_fraction", .default_yaml = "0.9", .range = {0, 1, true, false},
                 .description = "the contact distance never exceeds this fraction of the pair's reference distance, so "
                                "that neighbours at rest do not repel"},
                {.key = "skin", .default_yaml = "0.5", .range = positive,
                 .description = "Verlet skin as a fraction of the largest node diameter: the pair list holds every pair "
                                "within d + skin and is rebuilt when a point has moved half the skin"},
                {.key = "barrier_fraction", .default_yaml = "0", .range = {0, 1, false, true},
                 .description = "below this fraction b of d_ij the pair force stops growing linearly and becomes a barrier, "
                                "(c_S/δ)(d_ij − r_c + r_c (r_c − r)/r) with r_c = b d_ij, whose energy no pair driven together "
                                "head-on can cross (the linear force is finite at r = 0); 0: linear at every distance (LAMMPS)"},
                {.key = "friction", .type = VT::sequence, .description = "Coulomb friction between pairs of bodies"}}});
  s.push_back({"contact.friction[i]", "Coulomb friction between the points of two bodies (or within one): a force "
               "μ |f_n| against their relative tangential velocity",
               {{.key = "bodies", .type = VT::names, .description = "two body names, or one (within that body)", .required = true},
                {.key = "coefficient", .range = non_negative, .description = "friction coefficient μ", .required = true}}});
  s.push_back({"rigid_bodies[i]",
               "a rigid body that the points cannot enter: penalty force density κ·(penetration) along the surface's "
               "outward normal on every point inside it, κ = stiffness_factor × the Silling–Askari stiffness Σ V c/ξ "
               "of a full family of the point's block. It is fixed; moves as prescribed (displacement); or is free "
               "(mass, velocity), moved by the reaction of the points' contact forces. The history records its "
               "position, velocity and contact force as body_<name>_x/_y/_z, _vx/_vy/_vz, _fx/_fy/_fz",
               {{.key = "name", .type = VT::text, .description = "name of the body (history columns)", .required = true},
                {.key = "sphere", .type = VT::mapping, .description = "see rigid_bodies[i].sphere", .required = true, .one_of = "shape"},
                {.key = "cylinder", .type = VT::mapping, .description = "see rigid_bodies[i].cylinder", .required = true, .one_of = "shape",
                 .dimension = 3},
                {.key = "box", .type = VT::mapping, .description = "see rigid_bodies[i].box", .required = true, .one_of = "shape"},
                {.key = "plane", .type = VT::mapping, .description = "see rigid_bodies[i].plane", .required = true, .one_of = "shape"},
                {.key = "displacement", .type = VT::mapping,
                 .description = "prescribed motion: the body's displacement, components as expressions of t (m)", .one_of = "motion"},
                {.key = "mass", .type = VT::number, .unit = Unit::mass, .range = positive,
                 .description = "a free body: its mass (kg)", .one_of = "motion"},
                {.key = "velocity", .type = VT::point, .description = "a free body: its initial velocity (m/s)"},
                {.key = "stiffness_factor", .default_yaml = "0.5", .range = positive,
                 .description = "penalty stiffness as a fraction of a full family's; 0.5 keeps a surface point no stiffer "
                                "than an interior one, so the stable time step holds", .one_of = "penalty"},
                {.key = "indenter_stiffness", .range = positive,
                 .description = "instead, the penalty of LAMMPS's fix indent: force density K h² at depth h, K in N/m⁵ "
                                "(for comparisons with LAMMPS decks; far softer than a rigid body)", .one_of = "penalty"}}});
  s.push_back({"rigid_bodies[i].sphere", "a ball (a disc in 2D)",
               {{.key = "center", .type = VT::point, .description = "centre at t = 0 (m)", .required = true},
                {.key = "radius", .unit = Unit::length, .range = positive, .description = "radius (m)", .required = true}}});
  s.push_back({"rigid_bodies[i].cylinder", "a solid cylinder with flat ends (3D)",
               {{.key = "center", .type = VT::point, .description = "centre of the base at t = 0 (m)", .required = true},
                {.key = "axis", .type = VT::point, .default_yaml = "[0, 0, 1]", .description = "direction of the axis"},
                {.key = "radius", .unit = Unit::length, .range = positive, .description = "radius (m)", .required = true},
                {.key = "length", .unit = Unit::length, .range = positive, .description = "length along the axis (m)",
                 .required = true}}});
  s.push_back({"rigid_bodies[i].box", "an axis-aligned box (a rectangle in 2D)",
               {{.key = "min", .type = VT::point, .description = "lowest corner at t = 0 (m)", .required = true},
                {.key = "max", .type = VT::point, .description = "highest corner at t = 0 (m)", .required = true}}});
  s.push_back({"rigid_bodies[i].plane", "a half-space: everything behind the plane is solid",
               {{.key = "point", .type = VT::point, .description = "a point of the plane at t = 0 (m)", .required = true},
                {.key = "normal", .type = VT::point, .description = "normal of the plane, toward the bodies (any length)",
                 .required = true}}});
  s.push_back({"rigid_bodies[i].displacement", "the prescribed displacement of the body (m), expressions of t",
               component_keys(Unit::length, VT::expression)});
  s.push_back({"temperature",
               "a prescribed temperature field T(x, y, z, t): every point of a material with thermal_expansion α carries "
               "the free thermal stretch α (T − reference) in each of its bonds, and the thermoviscoelastic model's "
               "relaxation times follow T through its WLF shift",
               {{.key = "value", .type = VT::expression, .unit = Unit::temperature,
                 .description = "T (K) as an expression of x, y, z, t; a number for a uniform temperature", .required = true},
                {.key = "reference", .unit = Unit::temperature, .range = positive,
                 .description = "T_ref (K): the temperature at which the bodies are free of thermal strain", .required = true}}});
  // Section paths are views: the strings live as long as the table, which is built once.
  static const std::vector<std::string> solver_paths = [] {
    std::vector<std::string> paths;
    for (const SolverInfo& solver : solver_types()) paths.push_back(solver_section_path(solver));
    return paths;
  }();
  for (std::size_t k = 0; k < solver_types().size(); ++k)
    s.push_back({solver_paths[k], solver_types()[k].description, solver_keys(solver_types()[k])});
  s.push_back({"decomposition", "the split of the points over the ranks of a distributed run (docs/parallel.md); "
               "results are the same bits whatever the split",
               {{.key = "method", .type = VT::choice, .default_yaml = "rcb",
                 .description = "Zoltan's geometric partitioner, weighted by bond count: rcb (recursive coordinate "
                                "bisection), rib (recursive inertial bisection), hsfc (Hilbert space-filling curve)",
                 .choices = {"rcb", "rib", "hsfc"}}}});
  s.push_back({"output", "what is written, relative to the deck's folder",
               {{.key = "directory", .type = VT::text, .default_yaml = "output", .description = "output folder, relative to the deck"},
                {.key = "exodus", .type = VT::mapping, .description = "Exodus II fields (see output.exodus); omit for none"},
                {.key = "history", .type = VT::mapping, .description = "CSV time history (see output.history); omit for none"},
                {.key = "checkpoint", .type = VT::mapping,
                 .description = "restart files (see output.checkpoint); omit for none"},
                {.key = "progress", .type = VT::boolean, .default_yaml = "true", .description = "print progress to the terminal"}}});
  s.push_back({"output.exodus", "Exodus II field output: one file; a distributed run writes one piece per rank, FILE.N.r, "
               "which ParaView reads as one data set and `peridot join` merges into the serial file (docs/parallel.md)",
               {{.key = "every", .type = VT::integer, .default_yaml = "100", .range = at_least_one, .description = "steps between frames"},
                {.key = "file", .type = VT::text, .default_yaml = "results.e", .description = "file name in the output folder"}}});
  s.push_back({"output.history", "CSV time history: energies, reactions, probes",
               {{.key = "every", .type = VT::integer, .default_yaml = "10", .range = at_least_one, .description = "steps between rows"},
                {.key = "file", .type = VT::text, .default_yaml = "history.csv", .description = "file name in the output folder"},
                {.key = "reaction", .type = VT::names, .description = "node sets whose reaction force is recorded"},
                {.key = "probes", .type = VT::sequence, .description = "point samples (see output.history.probes[i])"}}});
  s.push_back({"output.checkpoint",
               "checkpoint_<step>.nc files in the output folder, from which `peridot run DECK --restart FILE` continues "
               "bitwise as if never stopped (on any number of ranks and threads); also written when a stop signal "
               "(SIGINT, SIGTERM, SIGUSR1) ends the run; a distributed run writes one piece per rank, "
               "checkpoint_<step>.nc.N.r, and --restart takes checkpoint_<step>.nc for the set. Give every, wall_time or both",
               {{.key = "every", .type = VT::integer, .default_yaml = "0", .range = non_negative,
                 .description = "steps between checkpoints (0: not by steps)"},
                {.key = "wall_time", .type = VT::number, .unit = Unit::time, .default_yaml = "0", .range = non_negative,
                 .description = "wall-clock time between checkpoints, e.g. 2 h or 30 min (0: not by time)"},
                {.key = "keep", .type = VT::integer, .default_yaml = "2", .range = at_least_one,
                 .description = "the newest checkpoints kept; older ones are removed"}}});
  s.push_back({"output.history.probes[i]", "the value of a field at the point nearest to a position",
               {{.key = "name", .type = VT::text, .description = "column name", .required = true},
                {.key = "point", .type = VT::point, .description = "position (m)", .required = true},
                {.key = "field", .type = VT::choice, .description = "sampled field", .required = true,
                 .choices = probe_choices()}}});
  return s;
}

}  // namespace

const std::vector<SectionSpec>& deck_sections() {
  static const std::vector<SectionSpec> sections = make_sections();
  return sections;
}

const SectionSpec& deck_section(std::string_view path) {
  for (const SectionSpec& section : deck_sections())
    if (section.path == path) return section;
  PERIDOT_REQUIRE(false, "no deck section " + std::string(path));
}

}  // namespace peridot
