#include "peridot/deck/peridigm_import.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <tinyxml2.h>
#include <yaml-cpp/yaml.h>

#include "peridot/core/error.hpp"

namespace peridot {

namespace {

namespace fs = std::filesystem;

/// A Peridigm parameter list read from either syntax: a list of named entries, each a value or a list.
struct Entry {
  std::string name;
  std::string value;
  std::vector<Entry> children;
  bool is_list = false;
  int line = 0, column = 0;

  const Entry* find(std::string_view key) const {
    for (const Entry& e : children)
      if (e.name == key) return &e;
    return nullptr;
  }
};

Entry from_yaml(const YAML::Node& node, const std::string& name, const std::string& file) {
  Entry e;
  e.name = name;
  e.line = node.Mark().line + 1;
  e.column = node.Mark().column + 1;
  if (node.IsMap()) {
    e.is_list = true;
    for (const auto& item : node) e.children.push_back(from_yaml(item.second, item.first.as<std::string>(), file));
  } else if (node.IsScalar()) {
    e.value = node.Scalar();
  } else if (!node.IsNull()) {
    throw InputError(SourcePos{file, e.line, e.column}, fmt::format("'{}': a Peridigm deck has no lists here", name));
  }
  return e;
}

Entry from_xml(const tinyxml2::XMLElement& element, const std::string& file) {
  Entry e;
  e.line = element.GetLineNum();
  e.column = 1;
  if (const char* name = element.Attribute("name")) e.name = name;
  const std::string tag = element.Name();
  if (tag == "Parameter") {
    const char* value = element.Attribute("value");
    if (!value) throw InputError(SourcePos{file, e.line, 1}, fmt::format("Parameter '{}' has no value", e.name));
    e.value = value;
    return e;
  }
  if (tag != "ParameterList")
    throw InputError(SourcePos{file, e.line, 1}, fmt::format("<{}>: a Peridigm XML deck holds ParameterList and Parameter", tag));
  e.is_list = true;
  for (const tinyxml2::XMLElement* child = element.FirstChildElement(); child; child = child->NextSiblingElement())
    e.children.push_back(from_xml(*child, file));
  return e;
}

Entry read_deck(const std::string& path) {
  const std::string extension = fs::path(path).extension().string();
  if (extension == ".xml") {
    tinyxml2::XMLDocument document;
    if (document.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS)
      throw InputError(SourcePos{path, std::max(document.ErrorLineNum(), 0), document.ErrorLineNum() > 0 ? 1 : 0},
                       fmt::format("not readable as XML: {}", document.ErrorStr() ? document.ErrorStr() : "unknown error"));
    const tinyxml2::XMLElement* root = document.RootElement();
    if (!root) throw InputError(SourcePos{path, 0, 0}, "an empty XML file");
    return from_xml(*root, path);
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(SourcePos{path, 0, 0}, "cannot read the Peridigm deck");
  } catch (const YAML::ParserException& e) {
    throw InputError(SourcePos{path, e.mark.line + 1, e.mark.column + 1}, "invalid YAML: " + e.msg);
  }
  if (root.IsMap() && root["Peridigm"]) return from_yaml(root["Peridigm"], "Peridigm", path);
  return from_yaml(root, "Peridigm", path);
}

/// A name usable in a Peridot deck: "My Material" → my_material.
std::string deck_name(const std::string& name) {
  std::string out;
  for (char c : name) out += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(static_cast<unsigned char>(c))) : '_';
  return out.empty() ? "unnamed" : out;
}

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

class Translator {
 public:
  Translator(std::string path, const std::string& output_path)
      : path_(std::move(path)), deck_dir_(fs::absolute(path_).parent_path()),
        out_dir_(fs::absolute(output_path).parent_path()), stem_(fs::path(output_path).stem().string()) {}

  PeridigmImport run() {
    const Entry root = read_deck(path_);
    result_.notes.push_back("units: a Peridigm deck has none; Peridot reads every number as SI (m, kg, s, Pa)");
    const std::set<std::string> sections = {"Discretization", "Materials", "Damage Models", "Blocks",
                                            "Boundary Conditions", "Solver", "Output", "Verbose"};
    for (const Entry& e : root.children)
      if (!sections.contains(e.name) && e.name.rfind("Output", 0) != 0) note(e, "has no equivalent and is left out");

    deck_["discretization"]["dimension"] = 3;
    const Entry& discretization = need(root, "Discretization");
    discretization_type_ = need(discretization, "Type").value;
    materials(root);
    blocks(root, discretization);
    bond_filters(discretization);
    boundary_conditions(root);
    solver(root);
    output(root);

    YAML::Emitter out;
    out << YAML::Comment(fmt::format("Translated from {} by peridot import-peridigm.", fs::path(path_).filename().string()));
    out << YAML::Newline;
    for (const std::string& n : result_.notes) out << YAML::Comment("note: " + n) << YAML::Newline;
    out << deck_;
    result_.deck = std::string(out.c_str()) + "\n";
    return std::move(result_);
  }

 private:
  [[noreturn]] void fail(const Entry& at, const std::string& message) const {
    throw InputError(SourcePos{path_, at.line, at.column}, message);
  }
  void note(const Entry& at, const std::string& message) {
    result_.notes.push_back(fmt::format("{}:{}: '{}' {}", fs::path(path_).filename().string(), at.line, at.name, message));
  }
  const Entry& need(const Entry& list, std::string_view key) const {
    const Entry* e = list.find(key);
    if (!e) fail(list, fmt::format("'{}' lacks '{}'", list.name, key));
    return *e;
  }
  /// A file named in the Peridigm deck, as the Peridot deck names it (relative to the output's folder).
  std::string relocated(const std::string& file) const {
    const fs::path absolute = fs::absolute(deck_dir_ / file).lexically_normal();
    return absolute.lexically_relative(out_dir_).string();
  }
  std::string read_file(const Entry& at, const std::string& file) const {
    std::ifstream in(deck_dir_ / file);
    if (!in) fail(at, fmt::format("cannot read '{}'", (deck_dir_ / file).string()));
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  std::string add_file(const std::string& suffix, std::string contents) {
    const std::string name = fmt::format("{}_{}.txt", stem_, suffix);
    result_.files.emplace_back((out_dir_ / name).string(), std::move(contents));
    return name;
  }
  double number(const Entry& e) const {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(e.value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || e.value.find_first_not_of(" \t", used) != std::string::npos)
      fail(e, fmt::format("'{}' is not a number", e.value));
    return v;
  }

  void materials(const Entry& root) {
    const Entry& list = need(root, "Materials");
    for (const Entry& m : list.children) {
      const std::string kind = need(m, "Material Model").value;
      static const std::map<std::string, std::string> models = {
          {"Elastic", "lps"}, {"Elastic Plastic", "lps_plastic"}, {"Elastic Plastic Hardening", "lps_plastic"},
          {"Viscoelastic", "lps_viscoelastic"}, {"Elastic Correspondence", "correspondence"},
          {"Elastic Bond Based", "pmb"}};
      const auto model = models.find(kind);
      if (model == models.end())
        fail(need(m, "Material Model"), fmt::format("material model '{}' has no Peridot equivalent (translated: {})", kind,
                                                    "Elastic, Elastic Plastic, Elastic Plastic Hardening, Viscoelastic, "
                                                    "Elastic Correspondence, Elastic Bond Based"));
      YAML::Node out;
      out["model"] = model->second;
      static const std::vector<std::pair<std::string, std::string>> keys = {
          {"Density", "density"}, {"Bulk Modulus", "bulk_modulus"}, {"Shear Modulus", "shear_modulus"},
          {"Young's Modulus", "youngs_modulus"}, {"Poisson's Ratio", "poisson_ratio"},
          {"Yield Stress", "yield_stress"}, {"Hardening Modulus", "hardening_modulus"},
          {"lambda_i", "relaxing_fraction"}, {"tau b", "relaxation_time"},
          {"Hourglass Coefficient", "hourglass_coefficient"}, {"Thermal Expansion Coefficient", "thermal_expansion"}};
      const bool bond_based = model->second == "pmb";
      for (const Entry& p : m.children) {
        if (p.name == "Material Model") continue;
        const auto key = std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.first == p.name; });
        if (key == keys.end()) {
          note(p, fmt::format("of material '{}' has no equivalent and is left out", m.name));
          continue;
        }
        if (bond_based && (key->second == "shear_modulus" || key->second == "poisson_ratio" || key->second == "youngs_modulus")) {
          note(p, fmt::format("of material '{}': a bond-based solid takes the bulk modulus alone (ν = 1/4)", m.name));
          continue;
        }
        // The model's own keys: only the model that has them takes them.
        static const std::map<std::string, std::string> owner = {
            {"yield_stress", "lps_plastic"}, {"hardening_modulus", "lps_plastic"}, {"relaxing_fraction", "lps_viscoelastic"},
            {"relaxation_time", "lps_viscoelastic"}, {"hourglass_coefficient", "correspondence"}};
        if (const auto o = owner.find(key->second); o != owner.end() && o->second != model->second) {
          note(p, fmt::format("of material '{}' has no meaning for a {} material ({}) and is left out", m.name, kind,
                              model->second));
          continue;
        }
        out[key->second] = YAML::Load(p.value);
      }
      if (model->second == "correspondence") out["constitutive_law"] = "hypoelastic";
      materials_[m.name] = out;
    }
  }

  void blocks(const Entry& root, const Entry& discretization) {
    const Entry& list = need(root, "Blocks");
    const Entry* damage_models = root.find("Damage Models");
    std::optional<double> common_horizon;
    std::string text_file;
    if (discretization_type_ == "Text File") {
      // Peridigm: x y z block volume per line; Peridot: x y z volume block.
      const Entry& file = need(discretization, "Input Mesh File");
      std::istringstream in(read_file(file, file.value));
      std::string converted = "# x y z volume block, from " + file.value + " (Peridigm: x y z block volume)\n";
      int line_number = 0;
      for (std::string line; std::getline(in, line);) {
        ++line_number;
        const auto hash = line.find('#');
        const std::vector<std::string> columns = words(line.substr(0, hash));
        if (columns.empty()) continue;
        if (columns.size() != 5)
          throw InputError(SourcePos{(deck_dir_ / file.value).string(), line_number, 1},
                           fmt::format("a Peridigm text file has 5 columns (x y z block volume), this line {}", columns.size()));
        converted += fmt::format("{} {} {} {} {}\n", columns[0], columns[1], columns[2], columns[4], columns[3]);
        const std::string& block_id = columns[3];
        if (block_id.empty() || block_id.size() > 9 ||
            !std::all_of(block_id.begin(), block_id.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
          throw InputError(SourcePos{(deck_dir_ / file.value).string(), line_number, 1},
                           fmt::format("the block column (the fourth) holds '{}', not a block number", block_id));
        file_blocks_.push_back(std::stoi(block_id));
      }
      text_file = add_file("points", std::move(converted));
    } else if (discretization_type_ == "PdQuickGrid") {
      quick_grid(need(discretization, "TensorProduct3DMeshGenerator"));
    } else if (discretization_type_ != "Exodus") {
      fail(need(discretization, "Type"), fmt::format("discretization type '{}' is not translated (Exodus, Text File, PdQuickGrid)",
                                                     discretization_type_));
    }
    if (const Entry* h = discretization.find("Horizon")) common_horizon = number(*h);
    for (const Entry& e : discretization.children)
      if (e.name != "Type" && e.name != "Input Mesh File" && e.name != "Horizon" && e.name != "Bond Filters" &&
          e.name != "TensorProduct3DMeshGenerator" && !(e.name == "Omit Bonds Between Blocks" && e.value == "None"))
        note(e, "of the discretization has no equivalent and is left out");

    std::map<std::pair<std::string, std::string>, std::string> material_of;  // (material, damage model) → Peridot name
    for (const Entry& block : list.children) {
      const Entry& material = need(block, "Material");
      if (!materials_.contains(material.value)) fail(material, fmt::format("no material '{}' in Materials", material.value));
      const Entry* damage = block.find("Damage Model");
      const std::string damage_name = damage ? damage->value : "";
      auto& name = material_of[{material.value, damage_name}];
      if (name.empty()) {
        name = deck_name(material.value) + (damage ? "_" + deck_name(damage_name) : "");
        YAML::Node spec = YAML::Clone(materials_.at(material.value));
        if (damage) {
          const Entry* model = damage_models ? damage_models->find(damage_name) : nullptr;
          if (!model) fail(*damage, fmt::format("no damage model '{}' in Damage Models", damage_name));
          const Entry& type = need(*model, "Damage Model");
          if (type.value == "Critical Stretch") {
            spec["damage"]["critical_stretch"] = YAML::Load(need(*model, "Critical Stretch").value);
            for (const Entry& p : model->children)
              if (p.name != "Damage Model" && p.name != "Critical Stretch")
                note(p, fmt::format("of damage model '{}' has no equivalent and is left out", damage_name));
          } else {
            note(type, fmt::format("'{}' has no equivalent: block '{}' does not break bonds", type.value, block.name));
          }
        }
        deck_["materials"][name] = spec;
      }
      const Entry* horizon = block.find("Horizon");
      if (!horizon && !common_horizon) fail(block, fmt::format("block '{}' has no Horizon", block.name));
      const double delta = horizon ? number(*horizon) : *common_horizon;
      if (!first_horizon_) {
        first_horizon_ = delta;
        deck_["discretization"]["horizon"] = YAML::Load(horizon ? horizon->value : discretization.find("Horizon")->value);
      }
      const bool own_horizon = *first_horizon_ != delta;
      for (const std::string& block_name : words(need(block, "Block Names").value)) {
        YAML::Node body;
        body["material"] = name;
        if (discretization_type_ == "Exodus") {
          body["mesh"]["file"] = relocated(need(discretization, "Input Mesh File").value);
          body["mesh"]["format"] = "exodus";
          body["mesh"]["block"] = block_name;
        } else if (discretization_type_ == "Text File") {
          body["points_file"] = text_file;
          const auto id = block_name.rfind("block_", 0) == 0 ? block_name.substr(6) : block_name;
          if (id.empty() || !std::all_of(id.begin(), id.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
            fail(block, fmt::format("block name '{}': a text-file discretization names its blocks block_<number>", block_name));
          if (id.size() > 9) fail(block, fmt::format("block name '{}': the block number is too large", block_name));
          body["block"] = std::stoi(id);
          // Peridot numbers the points body by body (file order within each); Peridigm's node ids are file rows.
          for (std::size_t row = 0; row < file_blocks_.size(); ++row)
            if (file_blocks_[row] == std::stoi(id)) input_id_of_row_[row] = next_input_id_++;
        } else {
          body["shape"] = YAML::Clone(grid_shape_);
        }
        if (own_horizon) body["horizon"] = YAML::Load(horizon->value);
        deck_["bodies"][deck_name(block_name)] = body;
      }
    }
  }

  void quick_grid(const Entry& grid) {
    double origin[3], length[3], count[3];
    const char* axes = "XYZ";
    for (int d = 0; d < 3; ++d) {
      origin[d] = number(need(grid, fmt::format("{} Origin", axes[d])));
      length[d] = number(need(grid, fmt::format("{} Length", axes[d])));
      count[d] = number(need(grid, fmt::format("Number Points {}", axes[d])));
      if (!(length[d] > 0) || !(count[d] >= 1)) fail(grid, fmt::format("a {} length or point count that is not positive", axes[d]));
    }
    const double spacing = length[0] / count[0];
    for (int d = 1; d < 3; ++d)
      if (std::abs(length[d] / count[d] - spacing) > 1e-9 * spacing)
        note(grid, fmt::format("has cells of {:g} x {:g} x {:g}; Peridot's lattice is cubic: spacing {:g}, so the point "
                               "count along {} differs", spacing, length[1] / count[1], length[2] / count[2], spacing, axes[d]));
    deck_["discretization"]["spacing"] = spacing;
    YAML::Node origin_node, min, max;
    for (int d = 0; d < 3; ++d) {
      origin_node.push_back(origin[d]);
      min.push_back(origin[d]);
      max.push_back(origin[d] + length[d]);
    }
    origin_node.SetStyle(YAML::EmitterStyle::Flow);
    deck_["discretization"]["lattice_origin"] = origin_node;  // points at the cell centres, as PdQuickGrid
    grid_shape_["box"]["min"] = min;
    grid_shape_["box"]["max"] = max;
    grid_shape_["box"]["min"].SetStyle(YAML::EmitterStyle::Flow);
    grid_shape_["box"]["max"].SetStyle(YAML::EmitterStyle::Flow);
  }

  void bond_filters(const Entry& discretization) {
    const Entry* filters = discretization.find("Bond Filters");
    if (!filters) return;
    for (const Entry& f : filters->children) {
      const Entry& type = need(f, "Type");
      if (type.value != "Rectangular_Plane") {
        note(type, fmt::format("bond filter type '{}' has no equivalent and is left out", type.value));
        continue;
      }
      auto vector = [&](const char* key) {
        const std::vector<std::string> w = words(need(f, key).value);
        if (w.size() != 3) fail(need(f, key), fmt::format("'{}' is not three numbers", key));
        std::array<double, 3> v{};
        for (int d = 0; d < 3; ++d) v[d] = number(Entry{key, w[d], {}, false, need(f, key).line, need(f, key).column});
        return v;
      };
      const auto n = vector("Normal"), corner = vector("Lower_Left_Corner"), a = vector("Bottom_Unit_Vector");
      const double bottom = number(need(f, "Bottom_Length")), side = number(need(f, "Side_Length"));
      const std::array<double, 3> b = {n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0]};
      YAML::Node rectangle, origin, edge1, edge2;
      for (int d = 0; d < 3; ++d) {
        origin.push_back(corner[d]);
        edge1.push_back(bottom * a[d]);
        edge2.push_back(side * b[d]);
      }
      for (YAML::Node* v : {&origin, &edge1, &edge2}) v->SetStyle(YAML::EmitterStyle::Flow);
      rectangle["rectangle"]["origin"] = origin;
      rectangle["rectangle"]["edge1"] = edge1;
      rectangle["rectangle"]["edge2"] = edge2;
      deck_["precracks"].push_back(rectangle);
    }
  }

  /// A node set the boundary conditions name: defined in the section (a file of 1-based node ids, or the ids
  /// themselves), else a node set of the Exodus mesh.
  std::string node_set(const Entry& at, const std::string& name, const Entry& section) {
    const std::string peridot_name = deck_name(name);
    if (!node_sets_.insert(peridot_name).second) return peridot_name;
    const Entry* definition = section.find(name);
    YAML::Node set;
    if (definition && !definition->is_list) {
      std::vector<std::string> ids = words(definition->value);
      const bool inline_ids = !ids.empty() && std::all_of(ids.begin(), ids.end(), [](const std::string& w) {
        return std::all_of(w.begin(), w.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
      });
      if (!inline_ids) {
        std::istringstream in(read_file(*definition, definition->value));
        ids.clear();
        for (std::string line; std::getline(in, line);)
          for (const std::string& w : words(line.substr(0, line.find('#')))) ids.push_back(w);
      }
      std::string converted;  // 0-based point ids (Peridigm's are 1-based)
      for (const std::string& word : ids) {
        long long value = 0;
        try {
          value = std::stoll(word);
        } catch (const std::exception&) {
          fail(*definition, fmt::format("node set '{}': '{}' is not a node id", name, word));
        }
        if (value < 1) fail(*definition, fmt::format("node set '{}': node id {} (Peridigm's ids start at 1)", name, value));
        std::size_t id = static_cast<std::size_t>(value - 1);
        if (discretization_type_ == "Text File") {
          const auto found = input_id_of_row_.find(id);
          if (found == input_id_of_row_.end())
            fail(*definition, fmt::format("node set '{}': node {} is not a point of any block of the text file", name, value));
          id = found->second;
        }
        converted += std::to_string(id) + "\n";
      }
      if (discretization_type_ == "Exodus")
        note(*definition, "lists node ids: they are taken as the mesh's points in element order (one block)");
      set["ids_file"] = add_file(peridot_name, std::move(converted));
    } else if (discretization_type_ == "Exodus") {
      set["mesh_set"] = name;
    } else {
      fail(at, fmt::format("node set '{}' is not defined in Boundary Conditions", name));
    }
    deck_["node_sets"][peridot_name] = set;
    return peridot_name;
  }

  void boundary_conditions(const Entry& root) {
    const Entry* section = root.find("Boundary Conditions");
    if (!section) return;
    for (const Entry& bc : section->children) {
      if (!bc.is_list) continue;  // a node set definition, read when a condition names it
      const Entry& type = need(bc, "Type");
      const Entry* set = bc.find("Node Set");
      const std::string coordinate = bc.find("Coordinate") ? need(bc, "Coordinate").value : "";
      if (coordinate != "x" && coordinate != "y" && coordinate != "z")
        fail(bc, fmt::format("boundary condition '{}': Coordinate must be x, y or z", bc.name));
      const std::string& expression = need(bc, "Value").value;
      YAML::Node out;
      const bool everywhere = !set || set->value == "All" || set->value == "all";
      if (!everywhere) out["node_set"] = node_set(*set, set->value, *section);
      if (type.value == "Prescribed Displacement") {
        if (everywhere) fail(bc, fmt::format("boundary condition '{}' needs a Node Set", bc.name));
        out["displacement"][coordinate] = expression;
        deck_["boundary_conditions"].push_back(out);
      } else if (type.value == "Initial Displacement" || type.value == "Initial Velocity") {
        out[type.value == "Initial Velocity" ? "velocity" : "displacement"][coordinate] = expression;
        deck_["initial_conditions"].push_back(out);
      } else if (type.value == "Body Force") {
        out[coordinate] = expression;
        deck_["body_forces"].push_back(out);
        note(bc, "is taken as a force density (N/m³)");
      } else {
        note(type, fmt::format("boundary condition type '{}' has no equivalent and is left out", type.value));
      }
    }
  }

  void solver(const Entry& root) {
    const Entry& s = need(root, "Solver");
    YAML::Node out;
    const Entry* t0 = s.find("Initial Time");
    if (t0 && number(*t0) != 0) note(*t0, "is not 0: Peridot starts at t = 0, and the run covers Final Time - Initial Time");
    const double end = number(need(s, "Final Time")) - (t0 ? number(*t0) : 0.0);
    if (!(end > 0)) fail(need(s, "Final Time"), "Final Time is not after Initial Time");
    // The deck's own text when the run starts at 0 (no round-off in the translation).
    const YAML::Node end_time = t0 && number(*t0) != 0 ? YAML::Node(end) : YAML::Load(need(s, "Final Time").value);
    bool found = false;
    for (const Entry& e : s.children) {
      if (e.name == "Initial Time" || e.name == "Final Time" || e.name == "Verbose") continue;
      if ((e.name == "Verlet" || e.name == "QuasiStatic" || e.name == "NOXQuasiStatic") && found) {
        note(e, "is a second solver; the first is translated");
        continue;
      }
      if (e.name == "Verlet") {
        found = true;
        out["type"] = "explicit";
        out["end_time"] = end_time;
        for (const Entry& p : e.children) {
          if (p.name == "Safety Factor") out["safety_factor"] = YAML::Load(p.value);
          else if (p.name == "Fixed dt") out["time_step"] = YAML::Load(p.value);
          else note(p, "of the Verlet solver has no equivalent and is left out");
        }
      } else if (e.name == "QuasiStatic" || e.name == "NOXQuasiStatic") {
        found = true;
        // Both of Peridigm's quasi-static solvers are Newton methods, as Peridot's implicit solver is (its
        // iterations are Newton iterations too).
        out["type"] = "implicit";
        out["end_time"] = end_time;
        for (const Entry& p : e.children) {
          if (p.name == "Number of Load Steps") out["load_steps"] = YAML::Load(p.value);
          else if (p.name == "Maximum Solver Iterations") out["max_iterations"] = YAML::Load(p.value);
          else if (p.name == "Relative Tolerance") out["tolerance"] = YAML::Load(p.value);
          else note(p, fmt::format("of the {} solver has no equivalent (Peridot's implicit solver stops at a relative "
                                   "force residual and chooses its own linear solver) and is left out", e.name));
        }
      } else {
        note(e, "solver has no equivalent and is left out");
      }
    }
    if (!found) fail(s, "the Solver section has no Verlet or QuasiStatic solver");
    deck_["solver"] = out;
  }

  void output(const Entry& root) {
    YAML::Node out;
    out["directory"] = "output";
    bool written = false;
    for (const Entry& o : root.children) {
      if (o.name.rfind("Output", 0) != 0) continue;
      std::string file = "peridigm";
      long long every = 1;
      for (const Entry& p : o.children) {
        if (p.name == "Output Filename") file = p.value;
        else if (p.name == "Output Frequency") every = std::llround(number(p));
        else if (p.name == "Output File Type" && p.value != "ExodusII") note(p, "is not ExodusII: Exodus II is written");
        else if (p.name == "Output Variables") note(p, "is not needed: Peridot writes every field its problem has");
        else if (p.name != "Output File Type") note(p, "of the output has no equivalent and is left out");
      }
      if (written) {
        note(o, "is a second output; Peridot writes one Exodus file");
        continue;
      }
      written = true;
      out["exodus"]["every"] = every;
      out["exodus"]["file"] = deck_name(file) + ".e";
      out["history"]["every"] = every;
    }
    deck_["output"] = out;
  }

  std::string path_;
  fs::path deck_dir_, out_dir_;
  std::string stem_;
  std::string discretization_type_;
  PeridigmImport result_;
  YAML::Node deck_;
  std::map<std::string, YAML::Node> materials_;
  YAML::Node grid_shape_;
  std::optional<double> first_horizon_;
  std::vector<int> file_blocks_;                          ///< text file: each data row's block
  std::map<std::size_t, std::size_t> input_id_of_row_;    ///< text file: data row → Peridot input id
  std::size_t next_input_id_ = 0;
  std::set<std::string> node_sets_;
};

}  // namespace

PeridigmImport import_peridigm(const std::string& path, const std::string& output_path) {
  return Translator(path, output_path).run();
}

}  // namespace peridot
