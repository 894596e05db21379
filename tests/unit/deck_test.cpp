// The deck stage: good decks resolve to the right numbers; each kind of bad deck is reported at the
// exact file:line:col with a message that says what is wrong; the resolved deck reads back unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>

#include "peridot/deck/deck.hpp"
#include "peridot/deck/expression.hpp"
#include "peridot/materials/models.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {
namespace {

namespace fs = std::filesystem;

const std::string deck_2d = R"deck(discretization:
  dimension: 2
  spacing: 0.5 mm
  horizon_factor: 3.015
  plane: stress
  thickness: 1 mm
materials:
  glass:
    model: lps
    density: 2.44 g/cm^3
    youngs_modulus: 72 GPa
    poisson_ratio: 0.22
    influence: gaussian
    damage:
      critical_stretch: 1e-3
bodies:
  plate:
    material: glass
    shape: {box: {min: [0, 0], max: [0.05, 0.05]}}
precracks:
  - segment: {from: [0, 0.025], to: [0.02, 0.025]}
node_sets:
  left: {shape: {box: {min: [-1, -1], max: [0.002, 1]}}, bodies: [plate]}
  top: {shape: {box: {min: [-1, 0.048], max: [1, 1]}}}
no_fail: [left]
initial_conditions:
  - {velocity: {x: "0", y: "100*(y-0.025)"}}
boundary_conditions:
  - {node_set: left, displacement: {x: 0, y: "0"}}
  - {node_set: top, velocity: {y: "-20*min(t/1e-6,1)"}}
body_forces:
  - {y: "-9.81*2440"}
solver:
  end_time: 100 us
  safety_factor: 0.7
output:
  directory: out
  exodus: {every: 100}
  history: {every: 10, reaction: [left], probes: [{name: tip, point: [0.02, 0.025], field: displacement_y}]}
)deck";

const std::string deck_3d = R"deck(discretization:
  dimension: 3
  spacing: 1e-3
  horizon: 3 mm
  lattice_origin: [0.1, 0, 0]
  jitter: 0.1
  seed: 7
  partial_volume: extended
materials:
  steel:
    model: pmb
    density: 7800
    bulk_modulus: 160e9
    damage: {fracture_energy: 2 kJ/m^2}
bodies:
  rod:
    material: steel
    shape:
      difference:
        - union:
            - {cylinder: {center: [0, 0, 0], axis: [0, 0, 2], radius: 5 mm, length: 0.1}}
            - {sphere: {center: [0, 0, 0.1], radius: 8 mm}}
        - {tube: {center: [0, 0, 0], inner_radius: 1 mm, outer_radius: 2 mm, length: 0.05}}
    horizon_factor: 4
precracks:
  - rectangle: {origin: [0, -0.01, 0.05], edge1: [0.01, 0, 0], edge2: [0, 0.02, 0]}
node_sets:
  bottom: {shape: {box: {min: [-1, -1, -1], max: [1, 1, 0.002]}}}
boundary_conditions:
  - {node_set: bottom, displacement: {x: 0, y: 0, z: "1e-3*sin(pi*t/1e-5)"}}
solver:
  num_steps: 500
  time_step: 10 ns
)deck";

/// 1-based line and column of the first occurrence of `text` in `deck`.
std::pair<int, int> position_of(const std::string& deck, const std::string& text) {
  std::size_t at = deck.find(text);
  EXPECT_NE(at, std::string::npos) << text;
  int line = 1 + static_cast<int>(std::count(deck.begin(), deck.begin() + static_cast<long>(at), '\n'));
  std::size_t line_start = deck.rfind('\n', at);
  int column = static_cast<int>(at - (line_start == std::string::npos ? 0 : line_start + 1)) + 1;
  return {line, column};
}

std::string replaced(std::string deck, const std::string& from, const std::string& to) {
  std::size_t at = deck.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return deck.replace(at, from.size(), to);
}

std::string test_dir() {
  fs::path dir = fs::path(testing::TempDir()) / "peridot_deck_test";
  fs::create_directories(dir);
  return dir.string();
}

Problem parse(const std::string& deck) { return parse_deck(deck, "deck.yaml", test_dir()); }

std::vector<Diagnostic> errors_of(const std::string& deck) {
  try {
    parse(deck);
  } catch (const InputError& e) {
    return e.diagnostics();
  }
  ADD_FAILURE() << "the deck parsed without error:\n" << deck;
  return {};
}

/// The deck fails with an error at (line, column) whose message contains `message`.
void expect_error(const std::string& deck, std::pair<int, int> at, const std::string& message) {
  std::vector<Diagnostic> errors = errors_of(deck);
  std::string all;
  for (const Diagnostic& d : errors) {
    all += d.str() + "\n";
    if (d.pos.line == at.first && d.pos.column == at.second && d.message.find(message) != std::string::npos) return;
  }
  ADD_FAILURE() << "expected an error at " << at.first << ":" << at.second << " containing '" << message
                << "'; got:\n" << all;
}

const std::string deck_1d = R"deck(discretization:
  dimension: 1
  area: 2 mm^2
  spacing: 1 mm
  horizon_factor: 3
materials:
  epoxy:
    model: thermoviscoelastic
    density: 1810
    youngs_modulus: 700 MPa
    prony_series:
      - {youngs_modulus: 200 MPa, relaxation_time: 1e-4 s}
    damage: {fracture_energy: 5 J/m^2, criterion: energy}
bodies:
  bar: {material: epoxy, shape: {box: {min: [0], max: [0.05]}}}
precracks:
  - at: 0.0301
node_sets:
  left: {shape: {box: {min: [-1], max: [0.001]}}}
  right: {shape: {box: {min: [0.049], max: [1]}}}
boundary_conditions:
  - {node_set: left, displacement: {x: "0"}}
tractions:
  - {node_set: right, x: "1e6 * min(t / 0.001, 1)"}
solver: {type: relaxation, load_steps: 4, end_time: 2 ms}
output:
  history: {every: 1, probes: [{name: end, point: [0.0495], field: displacement_x}]}
)deck";

// ---------------------------------------------------------------------------------------------
// Good decks

TEST(Deck, Parses2DDeckWithUnitsAndDefaults) {
  Problem p = parse(deck_2d);
  EXPECT_EQ(p.dimension, 2);
  EXPECT_EQ(p.plane, PlaneKind::stress);
  EXPECT_DOUBLE_EQ(p.thickness, 1e-3);
  EXPECT_DOUBLE_EQ(p.spacing, 0.5e-3);
  EXPECT_DOUBLE_EQ(p.horizon, 3.015 * 0.5e-3);
  EXPECT_EQ(p.jitter, 0);
  EXPECT_EQ(p.seed, 1u);
  EXPECT_EQ(p.partial_volume, PartialVolumeKind::none);

  ASSERT_EQ(p.materials.size(), 1u);
  const MaterialSpec& glass = p.materials[0];
  EXPECT_EQ(glass.model, "lps");
  EXPECT_DOUBLE_EQ(glass.density, 2440);
  EXPECT_DOUBLE_EQ(glass.elastic.youngs_modulus, 72e9);
  EXPECT_DOUBLE_EQ(glass.elastic.poisson_ratio, 0.22);
  EXPECT_DOUBLE_EQ(glass.elastic.bulk_modulus, 72e9 / (3 * (1 - 2 * 0.22)));
  EXPECT_DOUBLE_EQ(glass.elastic.shear_modulus, 72e9 / (2 * (1 + 0.22)));
  EXPECT_EQ(glass.influence, InfluenceKind::gaussian);
  EXPECT_TRUE(glass.damage.enabled);
  EXPECT_DOUBLE_EQ(*glass.damage.critical_stretch, 1e-3);
  EXPECT_FALSE(glass.damage.fracture_energy);

  ASSERT_EQ(p.bodies.size(), 1u);
  const BodySpec& plate = p.bodies[0];
  EXPECT_EQ(&p.material_of(plate), &glass);
  ASSERT_TRUE(plate.shape);
  EXPECT_EQ(plate.shape->kind, Shape::Kind::box);
  EXPECT_DOUBLE_EQ(plate.shape->hi.y, 0.05);
  EXPECT_DOUBLE_EQ(plate.horizon, p.horizon);
  EXPECT_EQ(plate.pos.line, 17);
  EXPECT_EQ(plate.pos.column, 3);

  ASSERT_EQ(p.precracks.size(), 1u);
  EXPECT_TRUE(p.precracks[0].is_segment);
  EXPECT_DOUBLE_EQ(p.precracks[0].b.x, 0.02);
  ASSERT_EQ(p.node_sets.size(), 2u);
  EXPECT_EQ(p.node_sets[0].bodies, std::vector<std::string>{"plate"});
  EXPECT_EQ(p.no_fail_sets, std::vector<std::string>{"left"});

  ASSERT_EQ(p.initial_conditions.size(), 1u);
  EXPECT_EQ(p.initial_conditions[0].kind, InitialConditionSpec::Kind::velocity);
  EXPECT_EQ(p.initial_conditions[0].component[1]->text, "100*(y-0.025)");
  EXPECT_FALSE(p.initial_conditions[0].component[2]);

  // {x, y} on `left` and y on `top`: one condition per component.
  ASSERT_EQ(p.boundary_conditions.size(), 3u);
  EXPECT_EQ(p.boundary_conditions[0].component, 0);
  EXPECT_EQ(p.boundary_conditions[0].value.text, "0");
  EXPECT_EQ(p.boundary_conditions[1].component, 1);
  EXPECT_EQ(p.boundary_conditions[2].node_set, "top");
  EXPECT_EQ(p.boundary_conditions[2].kind, BoundaryConditionSpec::Kind::velocity);
  EXPECT_TRUE(p.boundary_conditions[2].value.depends_on_time);
  EXPECT_FALSE(p.boundary_conditions[1].value.depends_on_time);
  ASSERT_EQ(p.body_forces.size(), 1u);
  EXPECT_TRUE(p.body_forces[0].node_set.empty());

  EXPECT_DOUBLE_EQ(p.solver.parameters.number("end_time"), 1e-4);
  EXPECT_FALSE(p.solver.parameters.has("num_steps"));
  EXPECT_DOUBLE_EQ(p.solver.parameters.number("safety_factor"), 0.7);
  EXPECT_EQ(p.output.directory, (fs::absolute(test_dir()) / "out").lexically_normal().string());
  EXPECT_EQ(p.output.exodus_every, 100);
  EXPECT_EQ(p.output.exodus_file, "results.e");
  EXPECT_EQ(p.output.history_every, 10);
  EXPECT_EQ(p.output.reaction_sets, std::vector<std::string>{"left"});
  ASSERT_EQ(p.output.probes.size(), 1u);
  EXPECT_EQ(p.output.probes[0].field, "displacement_y");
  EXPECT_TRUE(p.output.progress);
  EXPECT_TRUE(p.warnings.empty());
}

TEST(Deck, Parses3DDeckWithShapesAndPmbImpliedPoisson) {
  Problem p = parse(deck_3d);
  EXPECT_EQ(p.dimension, 3);
  EXPECT_EQ(p.plane, PlaneKind::none);
  EXPECT_DOUBLE_EQ(p.horizon, 3e-3);
  EXPECT_DOUBLE_EQ(p.lattice_origin.x, 0.1);
  EXPECT_DOUBLE_EQ(p.jitter, 0.1);
  EXPECT_EQ(p.seed, 7u);
  EXPECT_EQ(p.partial_volume, PartialVolumeKind::extended);

  const ElasticConstants& c = p.materials[0].elastic;
  EXPECT_DOUBLE_EQ(c.bulk_modulus, 160e9);
  EXPECT_DOUBLE_EQ(c.poisson_ratio, 0.25);
  EXPECT_DOUBLE_EQ(c.youngs_modulus, 3 * 160e9 * (1 - 2 * 0.25));
  EXPECT_DOUBLE_EQ(c.shear_modulus, c.youngs_modulus / 2.5);
  EXPECT_DOUBLE_EQ(*p.materials[0].damage.fracture_energy, 2000);

  const BodySpec& rod = p.bodies[0];
  EXPECT_DOUBLE_EQ(rod.horizon, 4e-3);  // the body's own horizon_factor
  const Shape& s = *rod.shape;
  ASSERT_EQ(s.kind, Shape::Kind::difference);
  ASSERT_EQ(s.children.size(), 2u);
  EXPECT_EQ(s.children[0].kind, Shape::Kind::union_of);
  const Shape& cylinder = s.children[0].children[0];
  EXPECT_EQ(cylinder.kind, Shape::Kind::cylinder);
  EXPECT_DOUBLE_EQ(cylinder.axis.z, 1);  // normalised
  EXPECT_DOUBLE_EQ(cylinder.radius, 5e-3);
  EXPECT_EQ(s.children[0].children[1].kind, Shape::Kind::sphere);
  const Shape& tube = s.children[1];
  EXPECT_EQ(tube.kind, Shape::Kind::tube);
  EXPECT_DOUBLE_EQ(tube.inner_radius, 1e-3);
  EXPECT_DOUBLE_EQ(tube.radius, 2e-3);
  EXPECT_DOUBLE_EQ(tube.axis.z, 1);  // default axis
  EXPECT_TRUE(s.contains({0, 0, 0.08}, 3));
  EXPECT_FALSE(s.contains({0, 0.0015, 0.01}, 3));  // inside the tube that is cut away

  ASSERT_EQ(p.precracks.size(), 1u);
  EXPECT_FALSE(p.precracks[0].is_segment);
  EXPECT_DOUBLE_EQ(p.precracks[0].edge2.y, 0.02);
  ASSERT_EQ(p.boundary_conditions.size(), 3u);
  EXPECT_EQ(p.boundary_conditions[2].component, 2);
  EXPECT_EQ(p.solver.parameters.integer("num_steps"), 500);
  EXPECT_DOUBLE_EQ(p.solver.parameters.number("time_step"), 1e-8);
  EXPECT_DOUBLE_EQ(p.solver.parameters.number("safety_factor"), 0.8);
  EXPECT_EQ(p.output.exodus_every, 0);  // no output section: defaults, nothing written but progress
  EXPECT_EQ(p.output.directory, (fs::absolute(test_dir()) / "output").lexically_normal().string());
}

TEST(Deck, PmbImpliesOneThirdInPlaneStressAndQuarterInPlaneStrain) {
  std::string pmb = replaced(replaced(deck_2d, "model: lps", "model: pmb"), "    poisson_ratio: 0.22\n", "");
  EXPECT_DOUBLE_EQ(parse(pmb).materials[0].elastic.poisson_ratio, 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(parse(pmb).materials[0].elastic.bulk_modulus, 72e9);  // E / (3 (1 − 2/3))
  EXPECT_DOUBLE_EQ(parse(replaced(pmb, "plane: stress", "plane: strain")).materials[0].elastic.poisson_ratio, 0.25);
  // A consistent second modulus is accepted.
  std::string with_g = replaced(pmb, "youngs_modulus: 72 GPa", "youngs_modulus: 72 GPa\n    shear_modulus: 27 GPa");
  EXPECT_DOUBLE_EQ(parse(with_g).materials[0].elastic.shear_modulus, 27e9);
}

TEST(Deck, AnyTwoElasticConstantsGiveTheSameMaterial) {
  const double E = 72e9, nu = 0.22, K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  const std::pair<std::string, double> constants[] = {
      {"youngs_modulus", E}, {"poisson_ratio", nu}, {"bulk_modulus", K}, {"shear_modulus", G}};
  for (const auto& a : constants)
    for (const auto& b : constants) {
      if (a.first >= b.first) continue;
      std::string deck = replaced(deck_2d, "    youngs_modulus: 72 GPa\n    poisson_ratio: 0.22\n",
                                  fmt::format("    {}: {}\n    {}: {}\n", a.first, a.second, b.first, b.second));
      const ElasticConstants c = parse(deck).materials[0].elastic;
      SCOPED_TRACE(a.first + " and " + b.first);
      EXPECT_NEAR(c.youngs_modulus / E, 1, 1e-12);
      EXPECT_NEAR(c.poisson_ratio, nu, 1e-12);
      EXPECT_NEAR(c.bulk_modulus / K, 1, 1e-12);
      EXPECT_NEAR(c.shear_modulus / G, 1, 1e-12);
    }
}

TEST(Deck, ExpressionsEvaluate) {
  ScalarFunction f(Expression{"100*(y-0.025)", {}, false});
  EXPECT_NEAR(f(0, 0.03, 0, 0), 0.5, 1e-12);
  EXPECT_FALSE(f.depends_on_time());
  ScalarFunction ramp(Expression{"-20*min(t/1e-6,1) + 0*x*z + sin(pi)", {}, false});
  EXPECT_TRUE(ramp.depends_on_time());
  EXPECT_NEAR(ramp(1, 2, 3, 0.5e-6), -10, 1e-9);
  ScalarFunction copy = ramp;  // a copy evaluates independently (one per thread)
  EXPECT_NEAR(copy(0, 0, 0, 2e-6), -20, 1e-9);
  EXPECT_NEAR(ramp(0, 0, 0, 0.25e-6), -5, 1e-9);
  // A number in the deck is an expression too.
  Problem p = parse(deck_2d);
  EXPECT_EQ(ScalarFunction(p.boundary_conditions[0].value)(1, 2, 3, 4), 0);
}

TEST(Deck, MalformedExpressionThrowsAtItsPosition) {
  try {
    ScalarFunction f(Expression{"1+*x", {"deck.yaml", 5, 10}, false});
    FAIL() << "no error";
  } catch (const InputError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_EQ(e.diagnostics()[0].pos.line, 5);
    EXPECT_EQ(e.diagnostics()[0].pos.column, 12);  // the '*' at offset 2
    EXPECT_NE(e.diagnostics()[0].message.find("malformed expression '1+*x'"), std::string::npos);
  }
  EXPECT_THROW(ScalarFunction(Expression{"q*2", {}, false}), InputError);
}

TEST(Deck, ResolvedYamlRoundTrips) {
  for (const std::string& deck : {deck_2d, deck_3d}) {
    Problem first = parse(deck);
    std::string resolved = resolved_deck_yaml(first);
    Problem second = parse(resolved);
    // Every field is in the resolved deck at full precision, so equal text means equal problems.
    EXPECT_EQ(resolved_deck_yaml(second), resolved);
    EXPECT_EQ(second.horizon, first.horizon);
    EXPECT_EQ(second.materials[0].elastic.shear_modulus, first.materials[0].elastic.shear_modulus);
    EXPECT_EQ(second.bodies[0].horizon, first.bodies[0].horizon);
    EXPECT_EQ(second.boundary_conditions.size(), first.boundary_conditions.size());
    EXPECT_EQ(second.output.directory, first.output.directory);
  }
}

// damage.criterion: energy (damage/energy_failure.hpp) keeps fracture_energy as Gc and survives the resolved deck;
// stretch, the default, is not written.
TEST(Deck, EnergyCriterionParsesAndRoundTrips) {
  const std::string deck = replaced(deck_2d, "critical_stretch: 1e-3", "fracture_energy: 3.8\n      criterion: energy");
  const Problem first = parse(deck);
  ASSERT_TRUE(first.materials[0].damage.enabled);
  EXPECT_EQ(first.materials[0].damage.criterion, DamageCriterion::energy);
  EXPECT_EQ(*first.materials[0].damage.fracture_energy, 3.8);
  EXPECT_FALSE(first.materials[0].damage.critical_stretch);
  const std::string resolved = resolved_deck_yaml(first);
  EXPECT_NE(resolved.find("criterion: energy"), std::string::npos);
  EXPECT_EQ(parse(resolved).materials[0].damage.criterion, DamageCriterion::energy);
  EXPECT_EQ(parse(deck_2d).materials[0].damage.criterion, DamageCriterion::stretch);
  EXPECT_EQ(resolved_deck_yaml(parse(deck_2d)).find("criterion"), std::string::npos);
  const std::string both = replaced(deck_2d, "critical_stretch: 1e-3", "critical_stretch: 1e-3\n      criterion: energy");
  expect_error(both, position_of(both, "energy\n"), "criterion: energy needs fracture_energy (Gc), not critical_stretch");
}

TEST(Deck, PointsFileBodyNeedsNoSpacing) {
  std::ofstream(fs::path(test_dir()) / "points.txt") << "0 0 1e-6 1\n";
  std::string deck = replaced(deck_2d, "shape: {box: {min: [0, 0], max: [0.05, 0.05]}}", "points_file: points.txt\n    block: 1");
  deck = replaced(replaced(deck, "  spacing: 0.5 mm\n", ""), "horizon_factor: 3.015", "horizon: 1.5 mm");
  Problem p = parse(deck);
  EXPECT_EQ(p.spacing, 0);
  EXPECT_EQ(p.bodies[0].points_file, (fs::absolute(test_dir()) / "points.txt").string());
  EXPECT_EQ(*p.bodies[0].block_filter, 1);
  EXPECT_DOUBLE_EQ(p.bodies[0].horizon, 1.5e-3);

  std::string missing = replaced(deck, "points_file: points.txt", "points_file: nowhere.txt");
  expect_error(missing, position_of(missing, "nowhere.txt"), "file not found");
  std::string shape_without_spacing = replaced(deck_2d, "  spacing: 0.5 mm\n", "");
  expect_error(shape_without_spacing, {1, 1}, "missing required key 'spacing' (body 'plate' is filled from a shape");
  std::string partial_without_spacing = replaced(deck, "  dimension: 2\n", "  dimension: 2\n  partial_volume: extended\n");
  expect_error(partial_without_spacing, {1, 1}, "partial_volume needs 'spacing'");
}

TEST(Deck, PrintsSchemaFromTheTables) {
  std::ostringstream markdown, text;
  print_schema(markdown, true);
  print_schema(text, false);
  for (const std::string& s : {markdown.str(), text.str()}) {
    for (const char* word : {"critical_stretch", "horizon_factor", "safety_factor", "GPa", "pmb", "lps", "Silling"})
      EXPECT_NE(s.find(word), std::string::npos) << word;
  }
  EXPECT_NE(markdown.str().find("## `discretization`"), std::string::npos);
  EXPECT_NE(markdown.str().find("| key | type | unit |"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Bad decks: each at its exact position, with a message that says why

// Parameters set from outside (the Python module): by key path, list entries by index, checked by the schema
// as the file is; a path that cannot be followed is refused naming it.
TEST(Deck, OverridesSetValuesByKeyPath) {
  auto with = [](std::vector<DeckOverride> sets) { return parse_deck(deck_2d, "deck.yaml", test_dir(), sets); };
  const Problem p = with({{"materials.glass.damage.critical_stretch", "2.5e-3"},
                          {"boundary_conditions.1.velocity.y", "\"-5*t\""},
                          {"solver.end_time", "50 us"},
                          {"output.history", "{every: 7}"}});
  EXPECT_DOUBLE_EQ(*p.materials[0].damage.critical_stretch, 2.5e-3);
  EXPECT_EQ(p.boundary_conditions.back().value.text, "-5*t");
  std::smatch end_time;
  const std::string resolved = resolved_deck_yaml(p);
  ASSERT_TRUE(std::regex_search(resolved, end_time, std::regex("end_time: (\\S+)")));
  EXPECT_DOUBLE_EQ(std::stod(end_time[1]), 50e-6);
  EXPECT_EQ(p.output.history_every, 7);

  auto error_of = [&](std::vector<DeckOverride> sets) -> std::string {
    try {
      with(sets);
    } catch (const InputError& e) {
      std::string all;
      for (const Diagnostic& d : e.diagnostics()) all += d.str() + "\n";
      return all;
    }
    return "no error";
  };
  // A misspelt key is created, then refused by the schema as it would be in the file.
  EXPECT_NE(error_of({{"materials.glass.damage.critical_strech", "1e-3"}}).find("unknown key 'critical_strech'"),
            std::string::npos);
  EXPECT_NE(error_of({{"materials.glass.density", "-1"}}).find("materials.glass.density"), std::string::npos);
  EXPECT_NE(error_of({{"discretization.spacing.x", "1"}}).find("parameter 'discretization.spacing.x': 'discretization.spacing' is a value"),
            std::string::npos);
  EXPECT_NE(error_of({{"boundary_conditions.5.value", "1"}}).find("'boundary_conditions' is a list of 2, and '5' is not one of its indices"),
            std::string::npos);
  EXPECT_NE(error_of({{"solver.end_time", "[1, "}}).find("is not a YAML value"), std::string::npos);
  EXPECT_NE(error_of({{"solver..end_time", "1"}}).find("an empty key"), std::string::npos);
}

TEST(Deck, UnknownKeyDidYouMean) {
  std::string deck = replaced(deck_2d, "critical_stretch: 1e-3", "critical_strech: 1e-3");
  std::vector<Diagnostic> errors = errors_of(deck);
  ASSERT_FALSE(errors.empty());
  auto [line, column] = position_of(deck, "critical_strech");
  EXPECT_EQ(errors[0].str(), fmt::format("deck.yaml:{}:{}: error: materials.glass.damage: unknown key 'critical_strech' "
                                         "(did you mean 'critical_stretch'?)", line, column));
  std::string unknown = replaced(deck_2d, "  thickness: 1 mm\n", "  thickness: 1 mm\n  colour: blue\n");
  expect_error(unknown, position_of(unknown, "colour"), "discretization: unknown key 'colour'");
  EXPECT_EQ(errors_of(unknown)[0].message.find("did you mean"), std::string::npos);
}

TEST(Deck, MissingRequiredKey) {
  std::string deck = replaced(deck_2d, "    density: 2.44 g/cm^3\n", "");
  expect_error(deck, position_of(deck, "glass:"), "materials.glass: missing required key 'density'");
  std::string no_solver = replaced(deck_2d, "solver:\n  end_time: 100 us\n  safety_factor: 0.7\n", "");
  expect_error(no_solver, {1, 1}, "missing required key 'solver'");
}

TEST(Deck, WrongType) {
  std::string deck = replaced(deck_2d, "density: 2.44 g/cm^3", "density: heavy");
  expect_error(deck, position_of(deck, "heavy"), "materials.glass.density: expected a number in kg/m^3, got 'heavy'");
  std::string list = replaced(deck_2d, "end_time: 100 us", "end_time: [1, 2]");
  expect_error(list, position_of(list, "[1, 2]"), "solver.end_time: expected a number (s), got a list");
  std::string integer = replaced(deck_2d, "exodus: {every: 100}", "exodus: {every: 2.5}");
  expect_error(integer, position_of(integer, "2.5}"), "expected a whole number, got '2.5'");
  std::string point = replaced(deck_2d, "min: [0, 0]", "min: [0]");
  expect_error(point, position_of(point, "[0]"), "expected [x, y] or [x, y, z] (m)");
  std::string boolean = replaced(deck_2d, "directory: out", "directory: out\n  progress: maybe");
  expect_error(boolean, position_of(boolean, "maybe"), "expected true or false");
}

TEST(Deck, UnitsConvertAndWrongDimensionIsAnError) {
  std::string deck = replaced(deck_2d, "youngs_modulus: 72 GPa", "youngs_modulus: 72 mm");
  expect_error(deck, position_of(deck, "72 mm"), "'mm' is a unit of length, but a pressure is expected (in Pa; accepted: Pa, kPa");
  std::string unknown = replaced(deck_2d, "end_time: 100 us", "end_time: 100 fortnights");
  expect_error(unknown, position_of(unknown, "100 fortnights"), "unknown unit 'fortnights' (a time is expected; accepted: s, ms");
  std::string unitless = replaced(deck_2d, "safety_factor: 0.7", "safety_factor: 0.7 s");
  expect_error(unitless, position_of(unitless, "0.7 s"), "takes no unit");
  Problem p = parse(replaced(deck_2d, "end_time: 100 us", "end_time: 2.5ms"));
  EXPECT_DOUBLE_EQ(p.solver.parameters.number("end_time"), 2.5e-3);
}

TEST(Deck, OutOfRange) {
  std::string density = replaced(deck_2d, "density: 2.44 g/cm^3", "density: -2440");
  expect_error(density, position_of(density, "-2440"), "materials.glass.density: must be > 0, got -2440 kg/m^3");
  std::string nu = replaced(deck_2d, "poisson_ratio: 0.22", "poisson_ratio: 0.5");
  expect_error(nu, position_of(nu, "0.5\n"), "materials.glass.poisson_ratio: must be (-1, 0.5), got 0.5");
  std::string nu_low = replaced(deck_2d, "poisson_ratio: 0.22", "poisson_ratio: -1");
  expect_error(nu_low, position_of(nu_low, "-1\n"), "must be (-1, 0.5), got -1");
  std::string safety = replaced(deck_2d, "safety_factor: 0.7", "safety_factor: 1.5");
  expect_error(safety, position_of(safety, "1.5"), "solver.safety_factor: must be (0, 1], got 1.5");
  std::string jitter = replaced(deck_2d, "  thickness: 1 mm\n", "  thickness: 1 mm\n  jitter: 0.5\n");
  expect_error(jitter, position_of(jitter, "0.5\n"), "discretization.jitter: must be [0, 0.5), got 0.5");
  std::string dimension = replaced(deck_2d, "dimension: 2", "dimension: 4");
  expect_error(dimension, position_of(dimension, "4\n"), "discretization.dimension: must be [1, 3], got 4");
}

TEST(Deck, ContradictoryOrInsufficientElasticConstants) {
  std::string one = replaced(deck_2d, "    poisson_ratio: 0.22\n", "");
  expect_error(one, position_of(one, "glass:"),
               "give two of youngs_modulus, poisson_ratio, bulk_modulus, shear_modulus (only youngs_modulus is given)");
  std::string three = replaced(deck_2d, "poisson_ratio: 0.22", "poisson_ratio: 0.22\n    bulk_modulus: 50 GPa");
  expect_error(three, position_of(three, "50 GPa"),
               "materials.glass.bulk_modulus: 5e+10 contradicts the 4.28571e+10 that youngs_modulus 7.2e+10 and poisson_ratio 0.22 give");
  std::string unstable = replaced(deck_2d, "poisson_ratio: 0.22", "shear_modulus: 10 GPa");
  expect_error(unstable, position_of(unstable, "10 GPa"), "give E = 7.2e+10 Pa, ν = 2.6: no stable isotropic material");
  std::string pmb_nu = replaced(deck_2d, "model: lps", "model: pmb");
  expect_error(pmb_nu, position_of(pmb_nu, "0.22"),
               "materials.glass.poisson_ratio: 0.22 contradicts the ν = 0.3333 that bond-based model pmb implies in plane stress");
  std::string pmb_none = replaced(replaced(pmb_nu, "    youngs_modulus: 72 GPa\n", ""), "    poisson_ratio: 0.22\n", "");
  expect_error(pmb_none, position_of(pmb_none, "glass:"), "model pmb needs one of youngs_modulus, bulk_modulus, shear_modulus");
  std::string pmb_two = replaced(replaced(pmb_nu, "    poisson_ratio: 0.22\n", ""), "72 GPa", "72 GPa\n    bulk_modulus: 60 GPa");
  expect_error(pmb_two, position_of(pmb_two, "60 GPa"), "6e+10 contradicts the 7.2e+10 that youngs_modulus 7.2e+10 and the ν = 0.3333");
}

// δ < Δx is an error; δ = Δx (m = 1, nearest neighbours only, as convergence studies use) a warning.
TEST(Deck, HorizonSmallerThanSpacingIsAnErrorAndEqualAWarning) {
  std::string factor = replaced(deck_2d, "horizon_factor: 3.015", "horizon_factor: 0.9");
  expect_error(factor, position_of(factor, "0.9"), "discretization: horizon δ = 0.00045 m is not larger than the spacing Δx = 0.0005 m");
  std::string metres = replaced(deck_2d, "horizon_factor: 3.015", "horizon: 0.45 mm");
  expect_error(metres, position_of(metres, "0.45 mm\n  plane"), "(δ/Δx = 0.9)");
  std::string body = replaced(deck_2d, "    material: glass\n", "    material: glass\n    horizon_factor: 0.99\n");
  expect_error(body, position_of(body, "0.99\n    shape"), "bodies.plate: horizon δ");
  Problem nearest = parse(replaced(deck_2d, "horizon_factor: 3.015", "horizon: 0.5 mm"));
  ASSERT_EQ(nearest.warnings.size(), 1u);
  EXPECT_NE(nearest.warnings[0].message.find("nearest lattice neighbours only (m = 1)"), std::string::npos);
  Problem wide = parse(replaced(deck_2d, "horizon_factor: 3.015", "horizon_factor: 8"));
  ASSERT_EQ(wide.warnings.size(), 1u);
  EXPECT_TRUE(wide.warnings[0].is_warning);
  EXPECT_NE(wide.warnings[0].message.find("unusually large"), std::string::npos);
}

TEST(Deck, UnknownModelListsTheKnownOnes) {
  std::string deck = replaced(deck_2d, "model: lps", "model: pbm");
  expect_error(deck, position_of(deck, "pbm"), "materials.glass.model: unknown model 'pbm' (did you mean 'pmb'?); known: pmb, lps");
  std::string influence = replaced(deck_2d, "influence: gaussian", "influence: gauss");
  expect_error(influence, position_of(influence, "gauss\n"), "unknown influence 'gauss' (did you mean 'gaussian'?)");
}

TEST(Deck, MalformedExpressionPointsInsideIt) {
  std::string deck = replaced(deck_2d, "y: \"100*(y-0.025)\"", "y: \"100*(y-0.025\"");
  auto [line, column] = position_of(deck, "100*(y-0.025\"");
  std::vector<Diagnostic> errors = errors_of(deck);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].pos.line, line);
  EXPECT_GE(errors[0].pos.column, column);  // muParser reports where it gave up, inside the text
  EXPECT_NE(errors[0].message.find("initial_conditions[0].velocity.y: malformed expression '100*(y-0.025': "), std::string::npos);
  std::string plain = replaced(deck_2d, "x: 0, y: \"0\"", "x: 2*q, y: \"0\"");
  expect_error(plain, position_of(plain, "q, y"), "malformed expression '2*q'");
}

TEST(Deck, TimeIsNotAllowedInInitialConditions) {
  std::string deck = replaced(deck_2d, "x: \"0\", y: \"100*(y-0.025)\"", "x: \"t\"");
  expect_error(deck, position_of(deck, "t\"}") , "the expression 't' uses t, but this value is a function of x, y, z only");
}

TEST(Deck, UndefinedReferences) {
  std::string material = replaced(deck_2d, "material: glass", "material: glas");
  expect_error(material, position_of(material, "glas\n"), "bodies.plate.material: unknown material 'glas' (did you mean 'glass'?); defined: glass");
  std::string set = replaced(deck_2d, "{node_set: top,", "{node_set: tpo,");
  expect_error(set, position_of(set, "tpo"), "unknown node set 'tpo' (did you mean 'top'?); defined: left, top");
  std::string no_fail = replaced(deck_2d, "no_fail: [left]", "no_fail: [right]");
  expect_error(no_fail, position_of(no_fail, "[right]"), "no_fail: unknown node set 'right'");
  std::string body = replaced(deck_2d, "bodies: [plate]", "bodies: [plank]");
  expect_error(body, position_of(body, "[plank]"), "node_sets.left.bodies: unknown body 'plank'");
  std::string reaction = replaced(deck_2d, "reaction: [left]", "reaction: [lft]");
  expect_error(reaction, position_of(reaction, "[lft]"), "output.history.reaction: unknown node set 'lft' (did you mean 'left'?)");
}

TEST(Deck, DimensionOnlyKeys) {
  std::string segment_in_3d = replaced(deck_3d, "  - rectangle:", "  - segment: {from: [0, 0, 0], to: [1, 0, 0]}\n  - rectangle:");
  expect_error(segment_in_3d, position_of(segment_in_3d, "segment"), "precracks[0]: 'segment' applies to 2D decks only, and this deck has dimension 3");
  std::string plane_in_3d = replaced(deck_3d, "  spacing: 1e-3\n", "  spacing: 1e-3\n  plane: stress\n");
  expect_error(plane_in_3d, position_of(plane_in_3d, "plane"), "discretization: 'plane' applies to 2D decks only");
  std::string rectangle_in_2d = replaced(deck_2d, "  - segment: {from: [0, 0.025], to: [0.02, 0.025]}",
                                         "  - rectangle: {origin: [0, 0, 0], edge1: [1, 0, 0], edge2: [0, 1, 0]}");
  expect_error(rectangle_in_2d, position_of(rectangle_in_2d, "rectangle"), "'rectangle' applies to 3D decks only, and this deck has dimension 2");
  std::string z_in_2d = replaced(deck_2d, "{y: \"-9.81*2440\"}", "{z: \"1\"}");
  expect_error(z_in_2d, position_of(z_in_2d, "z: \"1\""), "body_forces[0]: 'z' applies to 3D decks only");
  std::string no_plane = replaced(deck_2d, "  plane: stress\n", "");
  expect_error(no_plane, position_of(no_plane, "discretization"), "discretization: missing required key 'plane'");
  std::string short_point = replaced(deck_3d, "max: [1, 1, 0.002]", "max: [1, 1]");
  expect_error(short_point, position_of(short_point, "[1, 1]"), "expected [x, y, z] (m)");
}

// A bar (dimension: 1): area A, points [x], x components only, Young's modulus alone, a precrack at a point; the
// models without a 1D form are refused by name.
TEST(Deck, OneDimensionalBar) {
  const Problem p = parse(deck_1d);
  EXPECT_EQ(p.dimension, 1);
  EXPECT_DOUBLE_EQ(p.area, 2e-6);
  EXPECT_DOUBLE_EQ(p.cross_section(), 2e-6);
  EXPECT_DOUBLE_EQ(p.materials[0].elastic.youngs_modulus, 700e6);
  ASSERT_EQ(p.precracks.size(), 1u);
  EXPECT_TRUE(p.precracks[0].is_point);
  EXPECT_DOUBLE_EQ(p.precracks[0].at, 0.0301);
  const std::string resolved = resolved_deck_yaml(p);
  EXPECT_EQ(resolved_deck_yaml(parse(resolved)), resolved);

  Simulation sim(p);
  const Discretization& disc = sim.discretization();
  ASSERT_EQ(disc.num_points(), 50u);
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    EXPECT_EQ(disc.x(i, 1), 0.0);
    EXPECT_DOUBLE_EQ(disc.volume[i], 1e-3 * 2e-6);
  }
  // The precrack at x = 30.1 mm cuts the bonds of the points 28…30 mm to those of 31…33 mm: 1 + 2 + 3 pairs.
  const BondList& bonds = sim.bonds();
  std::size_t crossing = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b)
      crossing += (disc.x(i, 0) - 0.0301) * (disc.x(bonds.neighbors[b], 0) - 0.0301) < 0;
  EXPECT_EQ(crossing, 0u) << "no bond crosses the precrack";

  std::string lps = replaced(deck_1d, "model: thermoviscoelastic", "model: lps");
  expect_error(lps, position_of(lps, "lps"), "model lps has no 1D form (discretization.dimension: 1); in 1D use pmb, thermoviscoelastic");
  std::string y = replaced(deck_1d, "displacement: {x: \"0\"}", "displacement: {x: \"0\", y: \"0\"}");
  expect_error(y, position_of(y, "y: \"0\""), "'y' applies to 2D and 3D decks only, and this deck has dimension 1");
  std::string nu = replaced(deck_1d, "    youngs_modulus: 700 MPa\n", "    youngs_modulus: 700 MPa\n    poisson_ratio: 0.3\n");
  expect_error(nu, position_of(nu, "0.3"), "a 1D bar takes youngs_modulus only; remove poisson_ratio");
  std::string shear = replaced(deck_1d, "{youngs_modulus: 200 MPa", "{shear_modulus: 200 MPa");
  expect_error(shear, position_of(shear, "shear_modulus: 200"), "'shear_modulus' applies to 2D and 3D decks only");
  std::string thickness = replaced(deck_1d, "  area: 2 mm^2\n", "  thickness: 2 mm\n");
  expect_error(thickness, position_of(thickness, "thickness"), "'thickness' applies to 2D decks only, and this deck has dimension 1");
  std::string segment = replaced(deck_1d, "  - at: 0.0301", "  - segment: {from: [0.03], to: [0.03]}");
  expect_error(segment, position_of(segment, "segment"), "'segment' applies to 2D decks only");
  std::string point = replaced(deck_1d, "point: [0.0495]", "point: [0.0495, 0]");
  expect_error(point, position_of(point, "[0.0495, 0]"), "expected [x] (m)");
  std::string area_in_2d = replaced(deck_2d, "  thickness: 1 mm\n", "  thickness: 1 mm\n  area: 1\n");
  expect_error(area_in_2d, position_of(area_in_2d, "area"), "'area' applies to 1D decks only");
}

// creep_substeps follow a load jump; only load_history: steps has one.
TEST(Deck, CreepSubstepsNeedSteppedLoads) {
  std::string substeps = replaced(deck_1d, "end_time: 2 ms}", "end_time: 2 ms, creep_substeps: 4}");
  expect_error(substeps, position_of(substeps, "4}"), "solver.creep_substeps: creep substeps follow a load jump");
  EXPECT_NO_THROW(parse(replaced(deck_1d, "end_time: 2 ms}", "end_time: 2 ms, creep_substeps: 4, load_history: steps}")));
}

TEST(Deck, ExclusivePairsNeedExactlyOne) {
  std::string both = replaced(deck_2d, "horizon_factor: 3.015", "horizon_factor: 3.015\n  horizon: 1.5 mm");
  expect_error(both, position_of(both, "horizon:"), "discretization: give only one of 'horizon_factor' and 'horizon'");
  std::string neither = replaced(deck_2d, "  horizon_factor: 3.015\n", "");
  expect_error(neither, {1, 1}, "discretization: missing one of 'horizon_factor' or 'horizon'");
  std::string steps = replaced(deck_2d, "end_time: 100 us", "end_time: 100 us\n  num_steps: 10");
  expect_error(steps, position_of(steps, "num_steps"), "solver: give only one of 'end_time' and 'num_steps'");
  std::string no_steps = replaced(deck_2d, "  end_time: 100 us\n", "");
  expect_error(no_steps, position_of(no_steps, "solver"), "solver: missing one of 'end_time' or 'num_steps'");
  std::string criteria = replaced(deck_2d, "critical_stretch: 1e-3", "critical_stretch: 1e-3\n      fracture_energy: 3.8");
  expect_error(criteria, position_of(criteria, "fracture_energy"), "give only one of 'critical_stretch' and 'fracture_energy'");
  std::string shape_and_file = replaced(deck_2d, "    material: glass\n", "    material: glass\n    points_file: p.txt\n");
  expect_error(shape_and_file, position_of(shape_and_file, "shape: {box: {min: [0, 0], max: [0.05"),
               "bodies.plate: give only one of 'points_file' and 'shape'");
  std::string bc_kinds = replaced(deck_2d, "{node_set: top, velocity:", "{node_set: top, displacement: {x: 0}, velocity:");
  expect_error(bc_kinds, position_of(bc_kinds, "velocity: {y: \"-20"), "give only one of 'displacement' and 'velocity'");
}

TEST(Deck, YamlSyntaxErrorHasAPosition) {
  std::string deck = replaced(deck_2d, "no_fail: [left]", "no_fail: [left");
  std::vector<Diagnostic> errors = errors_of(deck);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_GT(errors[0].pos.line, 0);
  EXPECT_NE(errors[0].message.find("invalid YAML"), std::string::npos);
}

TEST(Deck, DuplicateKey) {
  std::string deck = replaced(deck_2d, "    density: 2.44 g/cm^3\n", "    density: 2.44 g/cm^3\n    density: 2440\n");
  expect_error(deck, position_of(deck, "density: 2440"), "materials.glass: duplicate key 'density' (first given at line 10)");
}

TEST(Deck, ReportsEveryErrorInPositionOrder) {
  std::string deck = replaced(deck_2d, "density: 2.44 g/cm^3", "density: -1");
  deck = replaced(deck, "material: glass", "material: steel");
  deck = replaced(deck, "safety_factor: 0.7", "safety_factor: 0");
  deck = replaced(deck, "critical_stretch", "critical_strech");
  std::vector<Diagnostic> errors = errors_of(deck);
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_NE(errors[0].message.find("density"), std::string::npos);
  EXPECT_NE(errors[1].message.find("critical_strech"), std::string::npos);
  EXPECT_NE(errors[2].message.find("unknown material 'steel'"), std::string::npos);
  EXPECT_NE(errors[3].message.find("safety_factor"), std::string::npos);
  try {
    parse(deck);
  } catch (const InputError& e) {
    std::string what = e.what();  // one line per error
    EXPECT_EQ(std::count(what.begin(), what.end(), '\n'), 3);
  }
}

// Fixture decks (also used by the command-line exit-status test): the first line says where the
// error is and what the message contains. bad_empty_node_set.yaml parses; the geometry stage
// reports it, at the node set's position.
TEST(Deck, BadDeckFixtures) {
  fs::path folder = fs::path(PERIDOT_SOURCE_DIR) / "tests/data/decks";
  int checked = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    std::string name = entry.path().filename().string();
    if (name.rfind("bad_", 0) != 0) continue;
    SCOPED_TRACE(name);
    std::ifstream in(entry.path());
    std::string first_line;
    std::getline(in, first_line);
    std::smatch m;
    ASSERT_TRUE(std::regex_match(first_line, m, std::regex(R"(# expect: (\d+):(\d+) (.*))"))) << first_line;
    int line = std::stoi(m[1]), column = std::stoi(m[2]);
    std::string message = m[3];
    ++checked;
    if (name == "bad_empty_node_set.yaml") {
      Problem p = load_deck(entry.path().string());
      ASSERT_FALSE(p.node_sets.empty());
      EXPECT_EQ(p.node_sets.back().pos.line, line);
      EXPECT_EQ(p.node_sets.back().pos.column, column);
      continue;
    }
    // Some problems are visible only once the points, bonds or loads exist: the deck parses, the set-up
    // refuses it (a body bonded across models, a load that is inf at a point, too many points or steps).
    try {
      const Problem p = load_deck(entry.path().string());
      Simulation sim(p);
      ADD_FAILURE() << "parsed and set up without error";
    } catch (const InputError& e) {
      ASSERT_FALSE(e.diagnostics().empty());
      const Diagnostic& d = e.diagnostics()[0];
      EXPECT_EQ(d.pos.file, entry.path().string());
      EXPECT_EQ(d.pos.line, line) << d.str();
      EXPECT_EQ(d.pos.column, column) << d.str();
      EXPECT_NE(d.message.find(message), std::string::npos) << d.str();
    }
  }
  EXPECT_GE(checked, 9);
}

// The example on every model page (docs/models/<name>.md), set in a tiny deck of each dimension, parses
// to a material of that model.
TEST(Deck, ModelPageExamplesParse) {
  for (const ModelInfo& model : material_models()) {
    const std::string example(model.doc.example);
    std::smatch name;
    ASSERT_TRUE(std::regex_search(example, name, std::regex(R"(^materials:\n  (\w+):\n)")))
        << model.name << ": the example must be a materials: block with one material";
    struct Setting {
      int dimension;
      const char* discretization;
      const char* box;
    };
    for (const Setting& setting : {Setting{3, "dimension: 3", "{min: [0, 0, 0], max: [0.01, 0.01, 0.01]}"},
                                   Setting{2, "dimension: 2, plane: stress", "{min: [0, 0], max: [0.01, 0.01]}"}}) {
      if (model.dimension != 0 && model.dimension != setting.dimension) continue;  // e.g. correspondence: 3D only
      const std::string deck = fmt::format(
          "discretization: {{{}, spacing: 1 mm, horizon_factor: 3.015}}\n{}\nbodies:\n"
          "  sample: {{material: {}, shape: {{box: {}}}}}\nsolver: {{num_steps: 1}}\n",
          setting.discretization, example, name[1].str(), setting.box);
      try {
        const Problem problem = parse(deck);
        ASSERT_EQ(problem.materials.size(), 1u);
        EXPECT_EQ(problem.materials[0].model, model.name);
        // The resolved deck writes the model's own keys back so that it parses to the same problem.
        const std::string resolved = resolved_deck_yaml(problem);
        EXPECT_EQ(resolved_deck_yaml(parse(resolved)), resolved) << model.name;
      } catch (const InputError& e) {
        std::string all;
        for (const Diagnostic& d : e.diagnostics()) all += d.str() + "\n";
        ADD_FAILURE() << model.name << ": the page's example does not parse:\n" << deck << all;
      }
    }
  }
}

// Every solver type, with and without its optional keys, resolves to a deck that parses to the same problem;
// its keys are in SolverSpec::parameters with their defaults.
TEST(Deck, SolverTypesRoundTrip) {
  const std::string head =
      "discretization: {dimension: 2, plane: stress, spacing: 1 mm, horizon_factor: 3.015}\n"
      "materials: {m: {model: lps, density: 1000, youngs_modulus: 1 GPa, poisson_ratio: 0.3}}\n"
      "bodies: {b: {material: m, shape: {box: {min: [0, 0], max: [0.01, 0.01]}}}}\n";
  for (const char* solver : {"solver: {num_steps: 3}", "solver: {type: explicit, end_time: 1 us, time_step: 1 ns, damping: 5}",
                             "solver: {type: relaxation}", "solver: {type: relaxation, load_steps: 4, ramp: false, tolerance: 1e-6}"}) {
    const Problem first = parse(head + solver + "\n");
    const std::string resolved = resolved_deck_yaml(first);
    const Problem second = parse(resolved);
    EXPECT_EQ(resolved_deck_yaml(second), resolved) << solver;
    EXPECT_EQ(second.solver.type, first.solver.type) << solver;
    ASSERT_EQ(second.solver.parameters.entries().size(), first.solver.parameters.entries().size()) << solver;
  }
  const Problem relaxation = parse(head + "solver: {type: relaxation, load_steps: 4, ramp: false}\n");
  EXPECT_EQ(relaxation.solver.type, "relaxation");
  EXPECT_EQ(relaxation.solver.parameters.integer("load_steps"), 4);
  EXPECT_FALSE(relaxation.solver.parameters.boolean("ramp"));
  EXPECT_DOUBLE_EQ(relaxation.solver.parameters.number("tolerance"), 1e-8);  // defaults filled in
  EXPECT_EQ(relaxation.solver.parameters.integer("max_iterations"), 100000);
  EXPECT_DOUBLE_EQ(relaxation.solver.parameters.number("end_time"), 1.0);
  const Problem explicit_ = parse(head + "solver: {num_steps: 3}\n");
  EXPECT_EQ(explicit_.solver.type, "explicit");
  EXPECT_FALSE(explicit_.solver.parameters.has("end_time"));
  EXPECT_DOUBLE_EQ(explicit_.solver.parameters.number("safety_factor"), 0.8);
}

}  // namespace
}  // namespace peridot

namespace peridot {
namespace {

const std::string deck_contact = R"deck(discretization: {dimension: 3, spacing: 1 mm, horizon_factor: 3}
materials:
  al: {model: pmb, density: 2700, youngs_modulus: 70 GPa}
bodies:
  plate: {material: al, shape: {box: {min: [0, 0, 0], max: [0.01, 0.01, 0.002]}}}
  chip: {material: al, shape: {box: {min: [0, 0, 0.006], max: [0.002, 0.002, 0.008]}}}
rigid_walls:
  - {name: floor, point: [0, 0, 0], normal: [0, 0, 1]}
rigid_bodies:
  - name: ball
    sphere: {center: [0.005, 0.005, 0.005], radius: 1 mm}
    mass: 3 g
    velocity: [0, 0, -50]
  - name: punch
    cylinder: {center: [0.005, 0.005, 0.003], axis: [0, 0, 2], radius: 1 mm, length: 2 mm}
    displacement: {z: "-10*t"}
  - {name: anvil, box: {min: [-1, -1, -1], max: [1, 1, -0.001]}}
contact:
  stiffness_factor: 10
  friction:
    - {bodies: [plate, chip], coefficient: 0.3}
solver: {end_time: 1 us}
)deck";

TEST(Deck, RigidBodiesAndContact) {
  const Problem p = parse(deck_contact);
  ASSERT_EQ(p.rigid_bodies.size(), 3u);
  EXPECT_EQ(p.rigid_bodies[0].motion, RigidMotionKind::free);
  EXPECT_DOUBLE_EQ(p.rigid_bodies[0].mass, 0.003);
  EXPECT_DOUBLE_EQ(p.rigid_bodies[0].velocity.z, -50);
  EXPECT_EQ(p.rigid_bodies[1].motion, RigidMotionKind::prescribed);
  EXPECT_DOUBLE_EQ(p.rigid_bodies[1].axis.z, 1.0);
  EXPECT_EQ(p.rigid_bodies[2].motion, RigidMotionKind::fixed);
  EXPECT_EQ(p.rigid_bodies[2].shape, RigidShapeKind::box);
  ASSERT_TRUE(p.contact.has_value());
  EXPECT_DOUBLE_EQ(p.contact->stiffness_factor, 10);
  EXPECT_DOUBLE_EQ(p.contact->distance_factor, 1.35);
  EXPECT_DOUBLE_EQ(p.contact->reference_fraction, 0.9);
  ASSERT_EQ(p.contact->friction.size(), 1u);
  EXPECT_EQ(p.contact->friction[0].second, "chip");
  const std::string resolved = resolved_deck_yaml(p);
  EXPECT_EQ(resolved_deck_yaml(parse(resolved)), resolved);

  std::string velocity = replaced(deck_contact, "    mass: 3 g\n", "");
  expect_error(velocity, position_of(velocity, "[0, 0, -50]"), "velocity is the initial velocity of a free body: give its mass");
  std::string both = replaced(deck_contact, "    mass: 3 g\n", "    mass: 3 g\n    displacement: {z: \"t\"}\n");
  expect_error(both, position_of(both, "displacement: {z: \"t\"}"), "give only one of 'mass' and 'displacement'");
  std::string same = replaced(deck_contact, "name: anvil", "name: floor");
  expect_error(same, position_of(same, "{name: floor, box"), "two rigid walls or bodies are named 'floor'");
  // Many bodies, the last named like the first (the names are compared after the list has grown several times:
  // the fuzzer found them compared through views into the list's old storage).
  std::string planes;
  for (int k = 0; k < 12; ++k) planes += fmt::format("  - {{name: plane_with_a_long_name_{}, plane: {{point: [0, 0, -{}], normal: [0, 0, 1]}}}}\n", k, k + 2);
  planes += "  - {name: plane_with_a_long_name_0, plane: {point: [0, 0, -20], normal: [0, 0, 1]}}\n";
  std::string many = replaced(deck_contact, "  - {name: anvil, box:", planes + "  - {name: anvil, box:");
  expect_error(many, position_of(many, "{name: plane_with_a_long_name_0, plane: {point: [0, 0, -20]"),
               "two rigid walls or bodies are named 'plane_with_a_long_name_0'");
  std::string shapes = replaced(deck_contact, "  - {name: anvil, box:", "  - {name: anvil, sphere: {center: [0, 0, 0], radius: 1}, box:");
  expect_error(shapes, position_of(shapes, "box: {min: [-1"), "give only one of 'sphere' and 'box'");
  std::string unknown = replaced(deck_contact, "[plate, chip]", "[plate, chips]");
  expect_error(unknown, position_of(unknown, "[plate, chips]"), "no body is named 'chips'");
  std::string three = replaced(deck_contact, "[plate, chip]", "[plate, chip, plate]");
  expect_error(three, position_of(three, "[plate, chip, plate]"), "give two bodies, or one for friction within it");
  std::string twice = replaced(deck_contact, "    - {bodies: [plate, chip], coefficient: 0.3}\n",
                               "    - {bodies: [plate, chip], coefficient: 0.3}\n    - {bodies: [chip, plate], coefficient: 0.1}\n");
  expect_error(twice, position_of(twice, "{bodies: [chip, plate]"), "the friction of 'chip' and 'plate' is given twice");
  std::string relaxation = replaced(deck_contact, "solver: {end_time: 1 us}", "solver: {type: relaxation}");
  relaxation = replaced(relaxation, "    velocity: [0, 0, -50]\n", "");
  expect_error(relaxation, position_of(relaxation, "name: ball"), "a moving or free rigid body is not supported with solver type 'relaxation'");
  std::string flat = replaced(replaced(deck_contact, "dimension: 3,", "dimension: 2, plane: stress,"), "cylinder:", "cylinder:");
  expect_error(flat, position_of(flat, "cylinder:"), "'cylinder' applies to 3D decks only");
}

}  // namespace
}  // namespace peridot
