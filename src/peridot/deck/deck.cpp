// Section parsers: each reads one section through a MapReader (which does all per-key validation)
// and adds only what involves several keys or sections: elastic constants, horizons, references.
#include "peridot/deck/deck.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <span>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "peridot/deck/map_reader.hpp"
#include "peridot/deck/model_schema.hpp"
#include "peridot/deck/solver_schema.hpp"

namespace peridot {

namespace {

namespace fs = std::filesystem;

/// Horizon as given in one place: in metres or as a multiple of the spacing.
struct HorizonInput {
  std::optional<double> horizon;
  std::optional<double> factor;
  SourcePos pos;
  bool given() const { return horizon || factor; }
};

/// The text of `map[key]` when it is a scalar, else "". A missing key of a const node is an invalid node that
/// throws when asked its type, so presence is asked first.
std::string scalar_at(const YAML::Node& map, const char* key) {
  if (!map.IsMap()) return {};
  const YAML::Node value = map[key];
  return value.IsDefined() && value.IsScalar() ? value.Scalar() : std::string();
}

/// "pmb, thermoviscoelastic": the models with a 1D form.
std::string one_dimensional_models() {
  std::vector<std::string_view> names;
  for (const ModelInfo& m : material_models())
    if (m.one_dimensional) names.push_back(m.name);
  return fmt::format("{}", fmt::join(names, ", "));
}

HorizonInput read_horizon(const MapReader& r) {
  HorizonInput h{r.optional_number("horizon"), r.optional_number("horizon_factor"), {}};
  h.pos = r[h.horizon ? "horizon" : "horizon_factor"].pos;
  return h;
}

/// Deck-wide state the section parsers share.
struct Parser {
  DeckContext& ctx;
  std::string base_dir;
  Problem& p;
  std::optional<double> spacing;
  SourcePos discretization_pos;

  std::string resolve_file(const Value& v, const std::string& path, bool must_exist) {
    std::string resolved = fs::absolute(fs::path(base_dir) / v.text).lexically_normal().string();
    std::error_code error;
    if (must_exist && !fs::exists(resolved, error)) {
      ctx.error(v.pos, path, "file not found: " + resolved);
    } else if (must_exist && !fs::is_regular_file(resolved, error)) {  // a folder, /dev/zero, a pipe: never read
      ctx.error(v.pos, path, "not a regular file: " + resolved);
    }
    return resolved;
  }

  void check_reference(const Value& v, const std::string& path, std::string_view what, const std::string& name,
                       const std::vector<std::string_view>& known) {
    if (std::find(known.begin(), known.end(), name) != known.end()) return;
    std::string_view guess = closest_match(name, known);
    ctx.error(v.pos, path,
              fmt::format("unknown {} '{}'{}; {}", what, name, guess.empty() ? "" : fmt::format(" (did you mean '{}'?)", guess),
                          known.empty() ? fmt::format("no {} is defined", what)
                                        : fmt::format("defined: {}", fmt::join(known, ", "))));
  }

  template <class Spec>
  static std::vector<std::string_view> names_of(const std::vector<Spec>& items) {
    std::vector<std::string_view> names;
    for (const Spec& item : items) names.push_back(item.name);
    return names;
  }

  // -- iteration over named mappings and lists ------------------------------------------------

  template <class Fn>
  void for_each_named(const Value& section, const std::string& path, Fn fn) {
    if (!section.node.IsMap()) return;
    for (auto it = section.node.begin(); it != section.node.end(); ++it)
      fn(it->first.Scalar(), node_pos(ctx, it->first), it->second, path + "." + it->first.Scalar());
  }

  template <class Fn>
  void for_each_item(const Value& section, const std::string& path, Fn fn) {
    if (!section.node.IsSequence()) return;
    for (std::size_t i = 0; i < section.node.size(); ++i) {
      const YAML::Node item = section.node[i];
      fn(item, node_pos(ctx, item), fmt::format("{}[{}]", path, i));
    }
  }

  // -- discretization --------------------------------------------------------------------------

  /// The dimension decides which keys are allowed everywhere, so it is read before anything else.
  void peek_dimension(const YAML::Node& discretization) {
    if (!discretization.IsMap()) return;
    const std::string d = scalar_at(discretization, "dimension");
    if (d == "1" || d == "2" || d == "3") ctx.dimension = std::stoi(d);
  }

  void parse_discretization(const Value& v) {
    peek_dimension(v.node);
    discretization_pos = v.key_pos;
    MapReader r(ctx, v.node, v.key_pos, "discretization", deck_section("discretization").keys);
    p.dimension = ctx.dimension == 0 ? 3 : ctx.dimension;
    p.plane = r["plane"].text == "stress" ? PlaneKind::stress : r["plane"].text == "strain" ? PlaneKind::strain : PlaneKind::none;
    p.thickness = p.dimension == 2 ? r["thickness"].number : 1.0;
    p.area = p.dimension == 1 ? r["area"].number : 1.0;
    spacing = r.optional_number("spacing");
    p.spacing = spacing.value_or(0);
    p.lattice_origin = r["lattice_origin"].point;
    p.jitter = r["jitter"].number;
    p.seed = static_cast<std::uint64_t>(r["seed"].integer);
    const std::string& partial = r["partial_volume"].text;
    p.partial_volume = partial == "extended"  ? PartialVolumeKind::extended
                       : partial == "horizon" ? PartialVolumeKind::horizon
                                              : PartialVolumeKind::none;
    p.quadrature = r["quadrature"].text == "isotropic" ? QuadratureKind::isotropic : QuadratureKind::one_point;
    p.quadrature_pos = r["quadrature"].pos;
    HorizonInput h = read_horizon(r);
    if (h.given()) p.horizon = resolve_horizon(h, "discretization");
  }

  /// δ (m) from a horizon input; checks it against the spacing. 0 when it cannot be resolved.
  double resolve_horizon(const HorizonInput& h, const std::string& path) {
    if (h.factor && !spacing) {
      ctx.error(h.pos, path, "horizon_factor needs discretization.spacing; give the horizon in m instead");
      return 0;
    }
    double delta = h.horizon ? *h.horizon : *h.factor * *spacing;
    if (!spacing) return delta;
    double ratio = delta / *spacing;
    if (ratio < 1 - 1e-9) {
      ctx.error(h.pos, path,
                fmt::format("horizon δ = {:g} m is not larger than the spacing Δx = {:g} m (δ/Δx = {:g}); "
                            "a point needs neighbours beyond the adjacent ones, typically δ ≈ 3Δx",
                            delta, *spacing, ratio));
    } else if (ratio < 1 + 1e-9) {  // the m = 1 of convergence studies (Madenci & Oterkus)
      ctx.warning(h.pos, path,
                  "horizon δ = Δx: each point is bonded to its nearest lattice neighbours only (m = 1), a coarse "
                  "quadrature of the model's sums; typically δ ≈ 3Δx");
    } else if (ratio > 6) {
      ctx.warning(h.pos, path,
                  fmt::format("horizon δ/Δx = {:g} is unusually large (> 6): many bonds per point, a slow run", ratio));
    }
    return delta;
  }

  // -- materials -------------------------------------------------------------------------------

  void parse_materials(const Value& v) {
    for_each_named(v, "materials", [&](const std::string& name, const SourcePos& pos, const YAML::Node& node,
                                       const std::string& path) {
      const ModelInfo* model = find_model(scalar_at(node, "model"));
      MapReader r(ctx, node, pos, path, model ? material_keys(*model) : common_material_keys());
      MaterialSpec m;
      m.name = name;
      m.pos = pos;
      if (model) m.model = std::string(model->name);
      m.density = r["density"].number;
      std::string influence = r["influence"].text;
      if (model && !model->influence.empty()) {
        if (r.given("influence") && influence != model->influence)
          ctx.error(r["influence"].pos, r.path_of("influence"),
                    fmt::format("model {} is calibrated for influence {} only; give that or leave influence out",
                                model->name, model->influence));
        influence = model->influence;
      }
      m.influence = influence == "inverse_distance" ? InfluenceKind::inverse_distance
                    : influence == "gaussian"       ? InfluenceKind::gaussian
                                                    : InfluenceKind::constant;
      if (model) m.elastic = resolve_elastic(r, *model);
      if (r.given("damage")) m.damage = parse_damage(r["damage"], r.path_of("damage"));
      if (model) read_parameters(r, model->keys, model->sections, m.parameters);
      if (model && model->dimension != 0 && model->dimension != p.dimension)
        ctx.error(r["model"].pos, r.path_of("model"),
                  fmt::format("model {} is implemented in {}D only (discretization.dimension: {})", model->name,
                              model->dimension, p.dimension));
      else if (model && p.dimension == 1 && !model->one_dimensional)
        ctx.error(r["model"].pos, r.path_of("model"),
                  fmt::format("model {} has no 1D form (discretization.dimension: 1); in 1D use {}", model->name,
                              one_dimensional_models()));
      if (model && model->check) model->check(r, m.parameters, ctx);
      p.materials.push_back(std::move(m));
    });
  }

  /// A model's or solver's own keys, valid values and defaults, into `parameters`; a mapping key is read
  /// with its section's table (path "materials.<name>.KEY") and stored as "KEY.SUBKEY", a sequence key's items
  /// each with the table of "materials.<name>.KEY[i]" and stored as "KEY[i].SUBKEY".
  void read_parameters(const MapReader& r, const std::vector<KeySpec>& keys, const std::vector<SectionSpec>& sections,
                       Parameters& parameters, const std::string& prefix = "") {
    auto table = [&](const std::string& path) -> const SectionSpec& {
      const auto section = std::find_if(sections.begin(), sections.end(), [&](const SectionSpec& s) { return s.path == path; });
      PERIDOT_REQUIRE(section != sections.end(), "no table for the section " + path);
      return *section;
    };
    for (const KeySpec& k : keys) {
      const std::string name = prefix + std::string(k.key);
      if (k.type == ValueType::mapping) {
        if (!r.given(k.key)) continue;
        const SectionSpec& section = table(fmt::format("materials.<name>.{}", k.key));
        const Value& v = r[k.key];
        MapReader nested(ctx, v.node, v.key_pos, r.path_of(k.key), section.keys);
        read_parameters(nested, section.keys, sections, parameters, name + ".");
        continue;
      }
      if (k.type == ValueType::sequence) {
        if (!r.given(k.key)) continue;
        const SectionSpec& section = table(fmt::format("materials.<name>.{}[i]", k.key));
        std::size_t index = 0;
        for_each_item(r[k.key], r.path_of(k.key), [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
          MapReader item(ctx, node, pos, path, section.keys);
          read_parameters(item, section.keys, sections, parameters, fmt::format("{}[{}].", name, index++));
        });
        continue;
      }
      if (!r.given(k.key) && k.default_yaml.empty()) continue;  // absent, or invalid (reported)
      const Value& v = r[k.key];
      const SourcePos pos = r.given(k.key) ? v.pos : r.owner();
      if (k.type == ValueType::choice || k.type == ValueType::text) parameters.set_text(name, v.text, pos);
      else if (k.type == ValueType::integer) parameters.set_integer(name, v.integer, pos);
      else if (k.type == ValueType::boolean) parameters.set_boolean(name, v.boolean, pos);
      else parameters.set_number(name, v.number, pos);
    }
  }

  DamageSpec parse_damage(const Value& v, const std::string& path) {
    MapReader r(ctx, v.node, v.key_pos, path, damage_keys());
    DamageSpec d{true, r.optional_number("critical_stretch"), r.optional_number("fracture_energy")};
    if (r.given("criterion") && r["criterion"].text == "energy") {
      d.criterion = DamageCriterion::energy;
      if (r.present("critical_stretch"))  // the work criterion has no stretch threshold
        ctx.error(r["criterion"].pos, r.path_of("criterion"),
                  "energy needs fracture_energy (Gc), not critical_stretch; give fracture_energy instead");
    }
    return d;
  }

  /// All four of K, G, E, ν from the ones given: the first two known (for a bond-based model the
  /// implied ν counts as known) determine the rest; any further one given must agree with them.
  ElasticConstants resolve_elastic(const MapReader& r, const ModelInfo& model) {
    struct Known {
      std::string_view key;
      double value;
      SourcePos pos;
    };
    static constexpr std::string_view order[] = {"youngs_modulus", "poisson_ratio", "bulk_modulus", "shear_modulus"};
    for (std::string_view key : order)
      if (r.present(key) && !r.given(key)) return {};  // already reported as invalid
    if (p.dimension == 1) {
      // A bar is Young's modulus alone: ν and the moduli of a 3D solid do not enter a 1D model.
      for (std::string_view key : order)
        if (key != "youngs_modulus" && r.given(key))
          ctx.error(r[key].pos, r.path_of(key), "a 1D bar takes youngs_modulus only; remove " + std::string(key));
      if (!r.given("youngs_modulus")) {
        ctx.error(r.owner(), r.path(), fmt::format("model {} in 1D needs youngs_modulus", model.name));
        return {};
      }
      const double E = r["youngs_modulus"].number;
      return {E / 3, E / 2, E, 0.0};  // ν = 0: a bar's lateral strain is not modelled
    }

    std::vector<Known> known;
    std::string implied;  // why ν is known without being given
    if (model.bond_based) {
      double nu = bond_based_poisson_ratio(p.dimension, p.plane);
      implied = fmt::format("the ν = {:.4g} that bond-based model {} implies in {}", nu, model.name,
                            p.dimension == 3 ? "3D" : p.plane == PlaneKind::stress ? "plane stress" : "plane strain");
      if (auto given_nu = r.optional_number("poisson_ratio"); given_nu && std::abs(*given_nu - nu) > 1e-3)
        ctx.error(r["poisson_ratio"].pos, r.path_of("poisson_ratio"),
                  fmt::format("{:g} contradicts {} (1/4 in 3D and plane strain, 1/3 in plane stress); "
                              "remove poisson_ratio or use a state-based model such as lps", *given_nu, implied));
      known.push_back({"poisson_ratio", nu, {}});
    }
    for (std::string_view key : order)
      if (r.given(key) && !(model.bond_based && key == "poisson_ratio")) known.push_back({key, r[key].number, r[key].pos});

    if (known.size() < 2) {
      ctx.error(r.owner(), r.path(),
                model.bond_based ? fmt::format("model {} needs one of youngs_modulus, bulk_modulus, shear_modulus", model.name)
                                 : fmt::format("give two of youngs_modulus, poisson_ratio, bulk_modulus, shear_modulus{}",
                                               known.empty() ? "" : fmt::format(" (only {} is given)", known[0].key)));
      return {};
    }
    auto value_of = [&](std::string_view key) -> std::optional<double> {
      for (const Known& k : std::span(known).first(2))
        if (k.key == key) return k.value;
      return std::nullopt;
    };
    auto [E, nu] = young_and_poisson(value_of("youngs_modulus"), value_of("poisson_ratio"), value_of("bulk_modulus"),
                                     value_of("shear_modulus"));
    std::string basis = known[0].pos.line > 0 ? fmt::format("{} {:g} and {} {:g}", known[0].key, known[0].value, known[1].key, known[1].value)
                                              : fmt::format("{} {:g} and {}", known[1].key, known[1].value, implied);
    if (!(E > 0) || !(nu > -1 && nu < 0.5)) {
      ctx.error(known[1].pos, r.path(),
                fmt::format("{} give E = {:g} Pa, ν = {:g}: no stable isotropic material (needs E > 0, -1 < ν < 0.5)", basis, E, nu));
      return {};
    }
    ElasticConstants c{E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu)), E, nu};
    // Values given stay exactly as given, so that the resolved deck reads back to the same numbers.
    for (const Known& k : std::span(known).subspan(2)) {
      double& derived = constant(c, k.key);
      if (std::abs(k.value - derived) > 1e-3 * std::abs(derived))
        ctx.error(k.pos, r.path_of(k.key),
                  fmt::format("{:g} contradicts the {:g} that {} give; give only two elastic constants", k.value, derived, basis));
      derived = k.value;
    }
    for (const Known& k : std::span(known).first(2)) constant(c, k.key) = k.value;
    return c;
  }

  static double& constant(ElasticConstants& c, std::string_view key) {
    return key == "youngs_modulus" ? c.youngs_modulus
           : key == "poisson_ratio" ? c.poisson_ratio
           : key == "bulk_modulus"  ? c.bulk_modulus
                                    : c.shear_modulus;
  }

  /// (E, ν) from exactly two of E, ν, K, G (isotropic linear elasticity).
  static std::pair<double, double> young_and_poisson(std::optional<double> E, std::optional<double> nu,
                                                     std::optional<double> K, std::optional<double> G) {
    if (E && nu) return {*E, *nu};
    if (E && K) return {*E, (3 * *K - *E) / (6 * *K)};
    if (E && G) return {*E, *E / (2 * *G) - 1};
    if (nu && K) return {3 * *K * (1 - 2 * *nu), *nu};
    if (nu && G) return {2 * *G * (1 + *nu), *nu};
    return {9 * *K * *G / (3 * *K + *G), (3 * *K - 2 * *G) / (2 * (3 * *K + *G))};
  }

  // -- shapes ----------------------------------------------------------------------------------

  std::optional<Shape> parse_shape(const YAML::Node& node, const SourcePos& owner, const std::string& path) {
    MapReader r(ctx, node, owner, path, deck_section("shape").keys);
    for (std::string_view kind : {"box", "cylinder", "tube", "sphere"})
      if (r.given(kind)) return parse_primitive(kind, r[kind], r.path_of(kind));
    for (std::string_view kind : {"union", "difference"}) {
      if (!r.given(kind)) continue;
      Shape s;
      s.kind = kind == "union" ? Shape::Kind::union_of : Shape::Kind::difference;
      for_each_item(r[kind], r.path_of(kind), [&](const YAML::Node& item, const SourcePos& pos, const std::string& item_path) {
        if (auto child = parse_shape(item, pos, item_path)) s.children.push_back(std::move(*child));
      });
      if (r[kind].node.size() == 0) ctx.error(r[kind].pos, r.path_of(kind), "needs at least one shape");
      return s;
    }
    return std::nullopt;
  }

  /// A box's min and max corners; an error at max unless it exceeds min in every coordinate of the deck.
  void read_corners(const MapReader& r, const std::string& path, Vec3& lo, Vec3& hi) {
    lo = r["min"].point;
    hi = r["max"].point;
    for (int d = 0; d < p.dimension; ++d)
      if (r.given("min") && r.given("max") && !(lo[d] < hi[d]))
        ctx.error(r["max"].pos, path, fmt::format("max must exceed min in every coordinate ({} is not)", "xyz"[d]));
  }

  Shape parse_primitive(std::string_view kind, const Value& v, const std::string& path) {
    MapReader r(ctx, v.node, v.key_pos, path, deck_section("shape." + std::string(kind)).keys);
    Shape s;
    if (kind == "box") {
      s.kind = Shape::Kind::box;
      read_corners(r, path, s.lo, s.hi);
      return s;
    }
    s.kind = kind == "cylinder" ? Shape::Kind::cylinder : kind == "tube" ? Shape::Kind::tube : Shape::Kind::sphere;
    s.center = r["center"].point;
    s.radius = kind == "tube" ? r["outer_radius"].number : r["radius"].number;
    if (kind == "sphere") return s;
    s.length = r["length"].number;
    s.inner_radius = kind == "tube" ? r["inner_radius"].number : 0;
    if (kind == "tube" && r.given("inner_radius") && r.given("outer_radius") && !(s.inner_radius < s.radius))
      ctx.error(r["inner_radius"].pos, path, "inner_radius must be smaller than outer_radius");
    // In 2D a cylinder or tube is a disc or annulus in the xy plane: its axis is z.
    s.axis = p.dimension == 2 ? Vec3{0, 0, 1} : r["axis"].point;
    if (norm(s.axis) == 0) {
      ctx.error(r["axis"].pos, r.path_of("axis"), "must not be zero");
    } else {
      s.axis = (1 / norm(s.axis)) * s.axis;
    }
    return s;
  }

  // -- bodies, pre-cracks, node sets -----------------------------------------------------------

  void parse_bodies(const Value& v) {
    // `bodies: {}`, or `bodies:` with every body commented out (a null value): a missing key is reported already.
    const bool empty = (v.node.IsMap() && v.node.size() == 0) || v.node.IsNull();
    if (empty && v.key_pos.line > 0) ctx.error(v.pos, "bodies", "no body is given; a deck needs at least one");
    std::vector<std::string_view> materials = names_of(p.materials);
    for_each_named(v, "bodies", [&](const std::string& name, const SourcePos& pos, const YAML::Node& node,
                                    const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("bodies.<name>").keys);
      BodySpec b;
      b.name = name;
      b.pos = pos;
      b.material = r["material"].text;
      if (r.given("material")) check_reference(r["material"], r.path_of("material"), "material", b.material, materials);
      if (r.given("shape")) b.shape = parse_shape(r["shape"].node, r["shape"].key_pos, r.path_of("shape"));
      if (r.given("mesh")) b.mesh = parse_mesh(r["mesh"], r.path_of("mesh"));
      if (r.given("points_file")) b.points_file = resolve_file(r["points_file"], r.path_of("points_file"), true);
      if (r.given("block")) b.block_filter = static_cast<int>(r["block"].integer);
      if (r.given("block") && !r.present("points_file"))
        ctx.error(r["block"].key_pos, path, "'block' filters the rows of a points_file, and this body has none (a mesh takes mesh.block)");
      HorizonInput h = read_horizon(r);
      b.horizon = h.given() ? resolve_horizon(h, path) : p.horizon;
      if (r.given("volume_constraint")) {
        b.volume_constraint = r["volume_constraint"].number;
        if (!r.present("shape"))
          ctx.error(r["volume_constraint"].key_pos, r.path_of("volume_constraint"),
                    "the layer is made on the lattice around a shape, and this body has none");
      }
      p.bodies.push_back(std::move(b));
    });
    check_spacing_given();
  }

  MeshSpec parse_mesh(const Value& v, const std::string& path) {
    MapReader r(ctx, v.node, v.key_pos, path, deck_section("bodies.<name>.mesh").keys);
    MeshSpec m;
    m.pos = r.given("file") ? r["file"].pos : v.key_pos;
    if (r.given("file")) m.file = resolve_file(r["file"], r.path_of("file"), true);
    m.block = r["block"].text;
    m.scale = r["scale"].number;
    if (r.given("format")) {
      m.format = r["format"].text;
    } else if (r.given("file")) {
      std::string extension = fs::path(m.file).extension().string();
      std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
      if (extension == ".e" || extension == ".exo" || extension == ".g" || extension == ".gen")
        m.format = "exodus";
      else if (extension == ".inp")
        m.format = "abaqus";
      else if (extension == ".msh")
        m.format = "gmsh";
      else
        ctx.error(r["file"].pos, r.path_of("file"),
                  fmt::format("cannot tell the mesh format from the extension '{}' (exodus: .e, .exo, .g, .gen; abaqus: "
                              ".inp; gmsh: .msh); give format",
                              extension));
    }
    return m;
  }

  /// The lattice spacing is needed as soon as one body is a shape filled on the lattice, or partial volumes
  /// are asked for.
  void check_spacing_given() {
    if (p.quadrature == QuadratureKind::isotropic)
      for (const BodySpec& b : p.bodies)
        if (!b.shape) {
          ctx.error(p.quadrature_pos, "discretization.quadrature",
                    fmt::format("isotropic quadrature is fitted to the lattice; body '{}' is read from a file", b.name));
          break;
        }
    if (spacing) return;
    if (p.partial_volume != PartialVolumeKind::none) {
      ctx.error(discretization_pos, "discretization",
                "partial_volume needs 'spacing' (the size of the cells the horizon cuts)");
      return;
    }
    for (const BodySpec& b : p.bodies)
      if (b.shape) {
        ctx.error(discretization_pos, "discretization",
                  fmt::format("missing required key 'spacing' (body '{}' is filled from a shape on the lattice)", b.name));
        return;
      }
  }

  void parse_precracks(const Value& v) {
    for_each_item(v, "precracks", [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("precracks[i]").keys);
      PrecrackSpec c;
      c.pos = pos;
      c.is_segment = !r.present("rectangle") && !r.present("at");
      if (r.given("at")) c.is_point = true, c.at = r["at"].number;
      if (r.given("segment")) {
        MapReader s(ctx, r["segment"].node, r["segment"].key_pos, r.path_of("segment"), deck_section("precracks[i].segment").keys);
        c.a = s["from"].point;
        c.b = s["to"].point;
        if (s.given("from") && s.given("to") && norm(c.b - c.a) == 0) ctx.error(s["to"].pos, s.path(), "from and to coincide");
      }
      if (r.given("rectangle")) {
        MapReader s(ctx, r["rectangle"].node, r["rectangle"].key_pos, r.path_of("rectangle"),
                    deck_section("precracks[i].rectangle").keys);
        c.origin = s["origin"].point;
        c.edge1 = s["edge1"].point;
        c.edge2 = s["edge2"].point;
        if (s.given("edge1") && s.given("edge2") && norm(cross(c.edge1, c.edge2)) == 0)
          ctx.error(s["edge2"].pos, s.path(), "edge1 and edge2 must span a parallelogram (they are parallel or zero)");
      }
      p.precracks.push_back(c);
    });
  }

  void parse_node_sets(const Value& v) {
    std::vector<std::string_view> bodies = names_of(p.bodies);
    for_each_named(v, "node_sets", [&](const std::string& name, const SourcePos& pos, const YAML::Node& node,
                                       const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("node_sets.<name>").keys);
      NodeSetSpec n;
      n.name = name;
      n.pos = pos;
      if (r.given("shape")) n.shape = parse_shape(r["shape"].node, r["shape"].key_pos, r.path_of("shape"));
      if (r.given("ids_file")) n.ids_file = resolve_file(r["ids_file"], r.path_of("ids_file"), true);
      n.bodies = r["bodies"].names;
      for (const std::string& body : n.bodies) check_reference(r["bodies"], r.path_of("bodies"), "body", body, bodies);
      if (r.given("mesh_set")) {
        n.mesh_set = r["mesh_set"].text;
        const bool meshed = std::any_of(p.bodies.begin(), p.bodies.end(), [&](const BodySpec& body) {
          return body.mesh && (n.bodies.empty() || std::find(n.bodies.begin(), n.bodies.end(), body.name) != n.bodies.end());
        });
        if (!meshed)
          ctx.error(r["mesh_set"].pos, r.path_of("mesh_set"),
                    n.bodies.empty() ? "no body is read from a mesh" : "none of its bodies is read from a mesh");
      }
      p.node_sets.push_back(std::move(n));
    });
    // Each volume-constraint layer is a node set of its own, named after its body.
    for (const BodySpec& body : p.bodies) {
      if (body.volume_constraint <= 0) continue;
      NodeSetSpec n;
      n.name = body.name + "_constraint";
      n.pos = body.pos;
      n.mesh_set = n.name;
      n.bodies = {body.name};
      n.generated = true;
      for (const NodeSetSpec& given : p.node_sets)
        if (given.name == n.name)
          ctx.error(given.pos, "node_sets." + given.name,
                    fmt::format("is the name of the volume-constraint layer of body '{}'; rename this node set", body.name));
      p.node_sets.push_back(std::move(n));
    }
  }

  void check_node_sets(const Value& v, const std::string& path, const std::vector<std::string>& names) {
    std::vector<std::string_view> known = names_of(p.node_sets);
    for (const std::string& name : names) check_reference(v, path, "node set", name, known);
  }

  // -- loads -------------------------------------------------------------------------------------

  /// The x, y, z expressions of a section; reports a section that gives none of them.
  std::array<std::optional<Expression>, 3> components_of(const MapReader& r) {
    std::array<std::optional<Expression>, 3> components;
    bool any_present = false;
    for (std::size_t d = 0; d < 3; ++d) {
      std::string_view key = std::string_view("xyz").substr(d, 1);
      any_present = any_present || r.present(key);
      if (r.given(key)) components[d] = r[key].expression;
    }
    if (!any_present)
      ctx.error(r.owner(), r.path(), p.dimension == 1   ? "give x"
                                     : p.dimension == 2 ? "give at least one of x, y"
                                                        : "give at least one of x, y, z");
    return components;
  }

  /// The components of `r`'s displacement or velocity, read against their section's keys.
  std::array<std::optional<Expression>, 3> components_of(const MapReader& r, const std::string& key, const std::string& section) {
    return components_of(MapReader(ctx, r[key].node, r[key].key_pos, r.path_of(key), deck_section(section + "." + key).keys));
  }

  std::string node_set_of(const MapReader& r) {
    if (!r.given("node_set")) return "";
    const Value& v = r["node_set"];
    check_node_sets(v, r.path_of("node_set"), {v.text});
    return v.text;
  }

  void parse_initial_conditions(const Value& v) {
    for_each_item(v, "initial_conditions", [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("initial_conditions[i]").keys);
      InitialConditionSpec ic;
      ic.pos = pos;
      ic.node_set = node_set_of(r);
      for (auto kind : {InitialConditionSpec::Kind::displacement, InitialConditionSpec::Kind::velocity}) {
        std::string key = kind == InitialConditionSpec::Kind::displacement ? "displacement" : "velocity";
        if (!r.given(key)) continue;
        ic.kind = kind;
        auto components = components_of(r, key, "initial_conditions[i]");
        std::copy(components.begin(), components.end(), ic.component);
      }
      p.initial_conditions.push_back(std::move(ic));
    });
  }

  void parse_boundary_conditions(const Value& v) {
    for_each_item(v, "boundary_conditions", [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("boundary_conditions[i]").keys);
      std::string node_set = node_set_of(r);
      for (auto kind : {BoundaryConditionSpec::Kind::displacement, BoundaryConditionSpec::Kind::velocity}) {
        std::string key = kind == BoundaryConditionSpec::Kind::displacement ? "displacement" : "velocity";
        if (!r.given(key)) continue;
        auto components = components_of(r, key, "boundary_conditions[i]");
        // One condition per prescribed component: x and y of a point can be held independently.
        for (int d = 0; d < 3; ++d)
          if (const auto& e = components[static_cast<std::size_t>(d)])
            p.boundary_conditions.push_back({pos, kind, node_set, d, *e});
      }
    });
  }

  void parse_body_forces(const Value& v) {
    for_each_item(v, "body_forces", [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("body_forces[i]").keys);
      BodyForceSpec f;
      f.pos = pos;
      f.node_set = node_set_of(r);
      auto components = components_of(r);
      std::copy(components.begin(), components.end(), f.component);
      p.body_forces.push_back(std::move(f));
    });
  }

  void parse_tractions(const Value& v) {
    for_each_item(v, "tractions", [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("tractions[i]").keys);
      TractionSpec t;
      t.pos = pos;
      t.node_set = node_set_of(r);
      t.depth = r.optional_number("depth").value_or(p.spacing);
      if (!(t.depth > 0))
        ctx.error(pos, path + ".depth", "give the layer's depth (there is no lattice spacing to default to)");
      auto components = components_of(r);
      std::copy(components.begin(), components.end(), t.component);
      p.tractions.push_back(std::move(t));
    });
  }

  void parse_temperature(const Value& v) {
    MapReader r(ctx, v.node, v.key_pos, "temperature", deck_section("temperature").keys);
    TemperatureSpec t;
    t.pos = v.key_pos;
    t.value = r["value"].expression;
    t.reference = r["reference"].number;
    p.temperature = std::move(t);
  }

  /// A unit vector from a point key (in 2D its z, in 1D its y and z dropped); an error when it is zero.
  Vec3 unit_vector(const MapReader& r, std::string_view key) {
    Vec3 n = r[key].point;
    if (!r.given(key)) return n;
    if (p.dimension <= 2) n.z = 0;
    if (p.dimension == 1) n.y = 0;
    if (norm(n) == 0) {
      ctx.error(r[key].pos, r.path_of(key),
                p.dimension == 1 ? "must not be zero (in 1D: its x)" : "must not be zero (in 2D: its x, y must not both be zero)");
      return n;
    }
    return (1 / norm(n)) * n;
  }

  void parse_rigid_walls(const Value& v) {
    std::vector<std::string_view> names;
    for_each_item(v, "rigid_walls", [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("rigid_walls[i]").keys);
      RigidWallSpec w;
      w.name = r["name"].text;
      w.pos = pos;
      w.point = r["point"].point;
      w.normal = unit_vector(r, "normal");
      w.speed = r["speed"].number;
      w.stiffness_factor = r["stiffness_factor"].number;
      w.contact = r["contact"].text == "symmetry" ? WallContactKind::symmetry : WallContactKind::penalty;
      if (w.contact == WallContactKind::symmetry && w.speed != 0)
        ctx.error(r["speed"].pos, r.path_of("speed"),
                  "a wall with contact: symmetry must be at rest (its mirror images would move with it)");
      p.rigid_walls.push_back(std::move(w));
    });
    for (const RigidWallSpec& w : p.rigid_walls) {
      if (std::find(names.begin(), names.end(), w.name) != names.end())
        ctx.error(w.pos, "rigid_walls", fmt::format("two walls are named '{}'", w.name));
      names.push_back(w.name);
    }
  }

  void parse_rigid_bodies(const Value& v) {
    std::vector<std::string> names;  // copies: a view into p.rigid_bodies dangles when it grows
    for (const RigidWallSpec& w : p.rigid_walls) names.push_back(w.name);
    for_each_item(v, "rigid_bodies", [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
      MapReader r(ctx, node, pos, path, deck_section("rigid_bodies[i]").keys);
      RigidBodySpec b;
      b.name = r["name"].text;
      b.pos = pos;
      b.stiffness_factor = r["stiffness_factor"].number;
      if (r.given("indenter_stiffness")) b.indenter_stiffness = r["indenter_stiffness"].number;
      for (std::string_view kind : {"sphere", "cylinder", "box", "plane"}) {
        if (!r.given(kind)) continue;
        MapReader s(ctx, r[kind].node, r[kind].key_pos, r.path_of(kind), deck_section("rigid_bodies[i]." + std::string(kind)).keys);
        if (kind == "sphere" || kind == "cylinder") {
          b.shape = kind == "sphere" ? RigidShapeKind::sphere : RigidShapeKind::cylinder;
          b.center = s["center"].point;
          b.radius = s["radius"].number;
          if (kind == "cylinder") b.axis = unit_vector(s, "axis"), b.length = s["length"].number;
        } else if (kind == "box") {
          b.shape = RigidShapeKind::box;
          read_corners(s, s.path_of("max"), b.lo, b.hi);
        } else {
          b.shape = RigidShapeKind::plane;
          b.center = s["point"].point;
          b.axis = unit_vector(s, "normal");
        }
      }
      if (r.given("displacement")) {
        b.motion = RigidMotionKind::prescribed;
        MapReader d(ctx, r["displacement"].node, r["displacement"].key_pos, r.path_of("displacement"),
                    deck_section("rigid_bodies[i].displacement").keys);
        const std::array<std::optional<Expression>, 3> components = components_of(d);
        for (std::size_t c = 0; c < 3; ++c) b.displacement[c] = components[c];
      } else if (r.given("mass")) {
        b.motion = RigidMotionKind::free;
        b.mass = r["mass"].number;
        b.velocity = r["velocity"].point;
      }
      if (r.given("velocity") && !r.given("mass"))
        ctx.error(r["velocity"].pos, r.path_of("velocity"),
                  "velocity is the initial velocity of a free body: give its mass too (a prescribed motion is a "
                  "displacement)");
      if (std::find(names.begin(), names.end(), b.name) != names.end())
        ctx.error(pos, path, fmt::format("two rigid walls or bodies are named '{}'", b.name));
      p.rigid_bodies.push_back(std::move(b));
      names.push_back(p.rigid_bodies.back().name);
    });
  }

  void parse_contact(const Value& v) {
    MapReader r(ctx, v.node, v.key_pos, "contact", deck_section("contact").keys);
    ContactSpec c;
    c.pos = v.key_pos;
    c.stiffness_factor = r["stiffness_factor"].number;
    c.distance_factor = r["distance_factor"].number;
    c.reference_fraction = r["reference_fraction"].number;
    c.skin = r["skin"].number;
    c.barrier_fraction = r["barrier_fraction"].number;
    for_each_item(r["friction"], r.path_of("friction"), [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
      MapReader f(ctx, node, pos, path, deck_section("contact.friction[i]").keys);
      FrictionSpec spec;
      spec.pos = pos;
      spec.coefficient = f["coefficient"].number;
      const std::vector<std::string>& bodies = f["bodies"].names;
      if (f.given("bodies")) {
        if (bodies.empty() || bodies.size() > 2)
          ctx.error(f["bodies"].pos, f.path_of("bodies"), "give two bodies, or one for friction within it");
        for (const std::string& name : bodies)
          if (std::none_of(p.bodies.begin(), p.bodies.end(), [&](const BodySpec& b) { return b.name == name; }))
            ctx.error(f["bodies"].pos, f.path_of("bodies"), fmt::format("no body is named '{}'", name));
        if (!bodies.empty()) spec.first = bodies.front(), spec.second = bodies.back();
      }
      for (const FrictionSpec& other : c.friction)
        if ((other.first == spec.first && other.second == spec.second) || (other.first == spec.second && other.second == spec.first))
          ctx.error(pos, path, fmt::format("the friction of '{}' and '{}' is given twice", spec.first, spec.second));
      c.friction.push_back(std::move(spec));
    });
    p.contact = std::move(c);
  }

  // -- solver and output -------------------------------------------------------------------------

  /// The type's keys (deck/solver_schema.hpp) into p.solver.parameters; an unknown type is reported by the
  /// reader (the keys of the default type are then read).
  void parse_solver(const Value& v) {
    p.solver.pos = v.key_pos;
    const YAML::Node type = v.node.IsMap() ? v.node["type"] : YAML::Node();
    const SolverInfo* solver = type && type.IsScalar() ? find_solver(type.Scalar()) : nullptr;
    if (!solver) solver = &solver_types().front();
    MapReader r(ctx, v.node, v.key_pos, "solver", solver_keys(*solver));
    p.solver.type = std::string(solver->name);
    read_parameters(r, solver->keys, {}, p.solver.parameters);
  }

  /// An output file is a plain name inside output.directory: no directory part (a path could leave the
  /// folder or land on another output), not a name the run writes itself, not the other output's name.
  void check_output_name(const Value& v, const std::string& path, const std::string& other) {
    const std::string& name = v.text;
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
      ctx.error(v.pos, path, fmt::format("'{}' is not a file name; give a name without a directory part: the file is "
                                         "written inside output.directory", name));
    else if (name == "run.log" || name == "resolved_deck.yaml" || name.ends_with(".partial") ||
             name.ends_with(".before-restart") || name.ends_with(".tmp") ||
             (name.starts_with("checkpoint_") && name.ends_with(".nc")))
      ctx.error(v.pos, path, fmt::format("'{}' is a name the run writes itself (run.log, resolved_deck.yaml, "
                                         "checkpoint_*.nc, *.partial, *.before-restart and *.tmp are taken); choose "
                                         "another", name));
    else if (name == other)
      ctx.error(v.pos, path, fmt::format("'{}' is also the Exodus file's name; the two outputs need different names", name));
  }

  void parse_output(const Value& v) {
    MapReader r(ctx, v.node, v.key_pos, "output", deck_section("output").keys);
    OutputSpec& o = p.output;
    o.pos = v.key_pos;
    o.directory = resolve_file(r["directory"], r.path_of("directory"), false);
    o.progress = r["progress"].boolean;
    if (r.given("exodus")) {
      MapReader e(ctx, r["exodus"].node, r["exodus"].key_pos, r.path_of("exodus"), deck_section("output.exodus").keys);
      o.exodus_every = e["every"].integer;
      o.exodus_file = e["file"].text;
      check_output_name(e["file"], e.path_of("file"), "");
    }
    if (r.given("history")) {
      MapReader h(ctx, r["history"].node, r["history"].key_pos, r.path_of("history"), deck_section("output.history").keys);
      o.history_every = h["every"].integer;
      o.history_file = h["file"].text;
      check_output_name(h["file"], h.path_of("file"), o.exodus_every > 0 ? o.exodus_file : "");
      o.reaction_sets = h["reaction"].names;
      check_node_sets(h["reaction"], h.path_of("reaction"), o.reaction_sets);
      for_each_item(h["probes"], h.path_of("probes"), [&](const YAML::Node& node, const SourcePos& pos, const std::string& path) {
        MapReader q(ctx, node, pos, path, deck_section("output.history.probes[i]").keys);
        o.probes.push_back({q["name"].text, pos, q["point"].point, q["field"].text});
      });
    }
    if (r.given("checkpoint")) {
      MapReader c(ctx, r["checkpoint"].node, r["checkpoint"].key_pos, r.path_of("checkpoint"),
                  deck_section("output.checkpoint").keys);
      o.checkpoint_every = c["every"].integer;
      o.checkpoint_wall_time = c["wall_time"].number;
      o.checkpoint_keep = c["keep"].integer;
      if (!o.checkpoints() && !c.given("every") && !c.given("wall_time"))
        ctx.error(r["checkpoint"].key_pos, r.path_of("checkpoint"),
                  "give every (steps) or wall_time (e.g. 2 h), or both: when to write a checkpoint");
    }
  }

  // -- the whole deck ----------------------------------------------------------------------------

  void parse(const YAML::Node& root) {
    MapReader r(ctx, root, SourcePos{ctx.file(), 1, 1}, "", deck_section("").keys);
    // A required section that is missing or not a mapping is already reported; skip it.
    if (r.given("discretization")) parse_discretization(r["discretization"]);
    parse_materials(r["materials"]);
    parse_bodies(r["bodies"]);
    parse_precracks(r["precracks"]);
    parse_node_sets(r["node_sets"]);
    p.no_fail_sets = r["no_fail"].names;
    check_node_sets(r["no_fail"], "no_fail", p.no_fail_sets);
    parse_initial_conditions(r["initial_conditions"]);
    parse_boundary_conditions(r["boundary_conditions"]);
    parse_body_forces(r["body_forces"]);
    parse_tractions(r["tractions"]);
    parse_rigid_walls(r["rigid_walls"]);
    parse_rigid_bodies(r["rigid_bodies"]);
    if (r.given("contact")) parse_contact(r["contact"]);
    if (r.given("temperature")) parse_temperature(r["temperature"]);
    if (r.given("solver")) parse_solver(r["solver"]);
    if (const SolverInfo* solver = find_solver(p.solver.type); solver && solver->check) solver->check(p, ctx);
    if (r.given("decomposition")) {
      MapReader d(ctx, r["decomposition"].node, r["decomposition"].key_pos, "decomposition",
                  deck_section("decomposition").keys);
      const std::string& method = d["method"].text;
      p.partition = method == "rib" ? PartitionMethod::rib : method == "hsfc" ? PartitionMethod::hsfc : PartitionMethod::rcb;
    }
    if (r.given("output")) {
      parse_output(r["output"]);
    } else if (!r.present("output")) {
      Value defaults;  // an absent output section still gets its defaults
      defaults.key_pos = r.owner();
      parse_output(defaults);
    }
  }
};

/// Sets one DeckOverride in the loaded tree (InputError when its path runs into a scalar or past a list).
void apply_override(YAML::Node root, const DeckOverride& set, const std::string& file) {
  auto fail = [&](const std::string& why) {
    throw InputError(SourcePos{file, 0, 0}, fmt::format("parameter '{}': {}", set.path, why));
  };
  YAML::Node value;
  try {
    value = YAML::Load(set.yaml);
  } catch (const YAML::ParserException& e) {
    fail(fmt::format("'{}' is not a YAML value: {}", set.yaml, e.msg));
  }
  std::vector<std::string> keys;
  for (std::size_t begin = 0;;) {
    const std::size_t dot = set.path.find('.', begin);
    keys.push_back(set.path.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin));
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  YAML::Node node = root;
  std::string walked;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::string& key = keys[k];
    if (key.empty()) fail("an empty key");
    YAML::Node next;
    if (node.IsSequence()) {
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), index);
      if (ec != std::errc() || end != key.data() + key.size() || index >= node.size())
        fail(fmt::format("'{}' is a list of {}, and '{}' is not one of its indices", walked, node.size(), key));
      if (k + 1 == keys.size()) {
        node[index] = value;
        return;
      }
      next.reset(node[index]);
    } else if (node.IsMap() || !node.IsDefined() || node.IsNull()) {
      if (k + 1 == keys.size()) {
        node[key] = value;
        return;
      }
      next.reset(node[key]);
    } else {
      fail(fmt::format("'{}' is a value, not a map or a list", walked));
    }
    node.reset(next);
    walked += (walked.empty() ? "" : ".") + key;
  }
}

void sort_by_position(std::vector<Diagnostic>& diagnostics) {
  std::stable_sort(diagnostics.begin(), diagnostics.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::pair(a.pos.line, a.pos.column) < std::pair(b.pos.line, b.pos.column);
  });
}

}  // namespace

Problem parse_deck(const std::string& yaml_text, const std::string& file_name_for_messages, const std::string& base_dir,
                   const std::vector<DeckOverride>& overrides) {
  DeckContext ctx(file_name_for_messages);
  Problem problem;
  problem.deck_path = file_name_for_messages;
  problem.deck_dir = fs::absolute(base_dir.empty() ? fs::path(".") : fs::path(base_dir)).lexically_normal().string();
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw InputError(ctx.pos(e.mark), "invalid YAML: " + e.msg);
  }
  if (!overrides.empty() && !root.IsDefined()) root = YAML::Node(YAML::NodeType::Map);
  for (const DeckOverride& set : overrides) apply_override(root, set, file_name_for_messages);
  Parser{ctx, problem.deck_dir, problem, std::nullopt, SourcePos{}}.parse(root);
  sort_by_position(ctx.errors());
  if (!ctx.errors().empty()) throw InputError(std::move(ctx.errors()));
  sort_by_position(ctx.warnings());
  problem.warnings = std::move(ctx.warnings());
  return problem;
}

Problem load_deck(const std::string& path, const std::vector<DeckOverride>& overrides) {
  std::ifstream in(path);
  if (!in) throw InputError(SourcePos{path, 0, 0}, "cannot read the deck file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_deck(text.str(), path, fs::absolute(path).parent_path().string(), overrides);
}

}  // namespace peridot
