// Abaqus input files (.inp): *NODE, *ELEMENT (C3D8*, C3D4*, C3D6*; CPS4*, CPE4*, CPS3*, CPE3* in 2D), *ELSET and
// *NSET, flat or inside one part (an instance placed where the part was drawn); every other keyword is passed
// over. An *ELEMENT section with elset= is a block of that name; *ELSET and *NSET (with or without GENERATE) are
// element and node sets. Names compare without case, as in Abaqus. A problem is reported at its line of the file.
#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <type_traits>

#include <fmt/format.h>

#include "peridot/geometry/mesh.hpp"

namespace peridot {

namespace {

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(trim(field));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::optional<ElementShape> shape_of(const std::string& type) {
  auto starts = [&](const char* prefix) { return type.rfind(prefix, 0) == 0; };
  if (starts("C3D8")) return ElementShape::hex8;
  if (starts("C3D4")) return ElementShape::tet4;
  if (starts("C3D6")) return ElementShape::wedge6;
  if (starts("CPS4") || starts("CPE4")) return ElementShape::quad4;
  if (starts("CPS3") || starts("CPE3")) return ElementShape::tri3;
  return std::nullopt;
}

class Reader {
 public:
  Reader(const std::string& path, const SourcePos& pos) : path_(path), pos_(pos) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(SourcePos{path_, line_number_, 1}, fmt::format("{}: {}", path_, message));
  }

  Mesh read() {
    std::ifstream in(path_);
    if (!in) throw InputError(pos_, fmt::format("cannot open '{}'", path_));
    enum class Section { none, node, element, set, instance } section = Section::none;
    std::size_t block = 0;
    bool generate = false;
    int parts = 0;
    std::string line;
    while (std::getline(in, line)) {
      ++line_number_;
      line = trim(line);
      if (line.empty() || line.rfind("**", 0) == 0) continue;
      if (line[0] == '*') {
        const std::vector<std::string> fields = split_commas(line);
        const std::string keyword = upper_case(fields[0]);
        std::map<std::string, std::string> options;
        for (std::size_t i = 1; i < fields.size(); ++i) {
          const auto equal = fields[i].find('=');
          options[upper_case(trim(fields[i].substr(0, equal)))] = equal == std::string::npos ? "" : trim(fields[i].substr(equal + 1));
        }
        section = Section::none;
        if (keyword == "*PART" && ++parts > 1) fail("a second *PART; export the mesh flat (one part, or none)");
        if (keyword == "*NODE") section = Section::node;
        if (keyword == "*INSTANCE") section = Section::instance;
        if (keyword == "*ELEMENT") {
          const std::string type = upper_case(options["TYPE"]);
          const std::optional<ElementShape> shape = shape_of(type);
          if (!shape)
            fail(fmt::format("element type '{}' is not supported (C3D8*, C3D4*, C3D6*, and in 2D CPS4*, CPE4*, CPS3*, "
                             "CPE3*)",
                             options["TYPE"]));
          MeshBlock b;
          b.shape = *shape;
          b.name = options.contains("ELSET") ? upper_case(options["ELSET"]) : fmt::format("ELEMENTS_{}", mesh_.blocks.size() + 1);
          // elset= also makes an element set of that name, which *ELSET lines may name (as in Abaqus).
          block_set_ = options.contains("ELSET") ? set_named(labels_[0], b.name) : no_set;
          mesh_.blocks.push_back(std::move(b));
          block = mesh_.blocks.size() - 1;
          section = Section::element;
        }
        if (keyword == "*ELSET" || keyword == "*NSET") {
          sets_ = &labels_[keyword == "*NSET"];
          const std::string option = keyword.substr(1);
          if (keyword == "*NSET" && options.contains("ELSET")) fail("*NSET, ELSET= is not read: list the set's nodes");
          if (!options.contains(option)) fail(fmt::format("{} without {}=", keyword, upper_case(option)));
          current_set_ = set_named(*sets_, upper_case(options[option]));
          generate = options.contains("GENERATE");
          section = Section::set;
        }
        continue;
      }
      const std::vector<std::string> fields = split_commas(line);
      switch (section) {
        case Section::node: {
          if (fields.size() < 3) fail("a node needs its number and 2 or 3 coordinates");
          const auto id = integer(fields[0]);
          node_index_[id] = mesh_.nodes.size();
          mesh_.nodes.push_back({number(fields[1]), number(fields[2]), fields.size() > 3 && !fields[3].empty() ? number(fields[3]) : 0.0});
          break;
        }
        case Section::element: element_line(fields, block); break;
        case Section::set: set_line(fields, generate); break;
        case Section::instance: fail("an *INSTANCE moved or turned: not applied here; export the mesh flat");
        case Section::none: break;
      }
    }
    if (pending_ > 0) fail("the last element has too few nodes");
    // Nodes by number, then element sets by element number: both may come before or after what they name.
    for (std::size_t b = 0; b < mesh_.blocks.size(); ++b)
      for (std::size_t k = 0; k < mesh_.blocks[b].connectivity.size(); ++k) {
        const auto found = node_index_.find(mesh_.blocks[b].connectivity[k]);
        if (found == node_index_.end()) {
          line_number_ = block_lines_[b];
          fail(fmt::format("block '{}' names node {}, which no *NODE gives", mesh_.blocks[b].name,
                           mesh_.blocks[b].connectivity[k]));
        }
        mesh_.blocks[b].connectivity[k] = static_cast<std::int64_t>(found->second);
      }
    auto indices = [&](const LabelSet& set, const std::map<std::int64_t, std::size_t>& index, const char* what,
                       const char* keyword) {
      std::vector<std::size_t> out;
      for (std::int64_t label : set.labels) {
        const auto found = index.find(label);
        if (found == index.end()) {
          line_number_ = set.line;
          fail(fmt::format("{} set '{}' names {} {}, which no {} gives", what, set.name, what, label, keyword));
        }
        out.push_back(found->second);
      }
      return out;
    };
    for (const LabelSet& set : labels_[0]) mesh_.element_sets.push_back({set.name, indices(set, element_index_, "element", "*ELEMENT")});
    for (const LabelSet& set : labels_[1]) {
      if (set.labels.empty()) {
        line_number_ = set.line;
        fail(fmt::format("node set '{}' names no node", set.name));
      }
      mesh_.node_sets.push_back({set.name, indices(set, node_index_, "node", "*NODE")});
    }
    mesh_.file = path_;
    mesh_.dimension = 3;
    return std::move(mesh_);
  }

 private:
  /// The whole field as a number (std::stod) or an integer (std::stoll), else a failure naming it.
  template <class T>
  T parse(const std::string& text, const char* what) const {
    std::size_t used = 0;
    T value{};
    try {
      if constexpr (std::is_floating_point_v<T>) value = std::stod(text, &used);
      else value = std::stoll(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size()) fail(fmt::format("'{}' is not {}", text, what));
    return value;
  }
  double number(const std::string& text) const { return parse<double>(text, "a number"); }
  std::int64_t integer(const std::string& text) const { return parse<std::int64_t>(text, "an integer"); }

  // An element's number and nodes; a long element continues on the next line after a trailing comma.
  void element_line(const std::vector<std::string>& fields, std::size_t b) {
    MeshBlock& block = mesh_.blocks[b];
    if (block_lines_.size() <= b) block_lines_.resize(b + 1, line_number_);
    std::size_t k = 0;
    if (pending_ == 0) {
      const std::int64_t id = integer(fields[0]);
      if (element_index_.contains(id)) fail(fmt::format("element {} is given twice", id));
      element_index_[id] = element_count_++;
      if (block_set_ != no_set) labels_[0][block_set_].labels.push_back(id);
      pending_ = corner_count(block.shape);
      k = 1;
    }
    for (; k < fields.size(); ++k) {
      if (fields[k].empty()) continue;
      if (pending_ == 0) fail(fmt::format("too many nodes for a {} element", element_name(block.shape)));
      block.connectivity.push_back(integer(fields[k]));
      --pending_;
    }
  }

  // A line of an *ELSET or *NSET: element or node numbers, other sets of its kind by name, or with GENERATE
  // first, last[, step].
  void set_line(const std::vector<std::string>& fields, bool generate) {
    LabelSet& set = (*sets_)[current_set_];
    const char* what = sets_ == &labels_[0] ? "element" : "node";
    if (generate) {
      if (fields.size() < 2) fail("GENERATE takes first, last[, step]");
      const std::int64_t from = integer(fields[0]), to = integer(fields[1]);
      const std::int64_t step = fields.size() > 2 && !fields[2].empty() ? integer(fields[2]) : 1;
      if (step < 1 || to < from || (to - from) / step > 100000000) fail("GENERATE: first, last, step out of order");
      for (std::int64_t e = from; e <= to; e += step) set.labels.push_back(e);
      return;
    }
    for (const std::string& field : fields) {
      if (field.empty()) continue;
      if (std::isalpha(static_cast<unsigned char>(field[0]))) {  // another set, by name
        const std::string name = upper_case(field);
        const auto other = std::find_if(sets_->begin(), sets_->end(), [&](const LabelSet& s) { return s.name == name; });
        if (other == sets_->end() || &*other == &set) fail(fmt::format("{} set '{}' is not defined above", what, field));
        // Both hold numbers until the end of the file, when every set becomes indices.
        const std::vector<std::int64_t> copied = other->labels;
        set.labels.insert(set.labels.end(), copied.begin(), copied.end());
        continue;
      }
      set.labels.push_back(integer(field));
    }
  }

  /// An *ELSET or *NSET as the file gives it: element or node numbers, and the line it starts at.
  struct LabelSet {
    std::string name;
    std::vector<std::int64_t> labels;
    int line = 0;
  };
  static constexpr std::size_t no_set = static_cast<std::size_t>(-1);

  /// The set of that name, made here if new (a set named again grows, as in Abaqus).
  std::size_t set_named(std::vector<LabelSet>& sets, const std::string& name) {
    const auto known = std::find_if(sets.begin(), sets.end(), [&](const LabelSet& s) { return s.name == name; });
    if (known != sets.end()) return static_cast<std::size_t>(known - sets.begin());
    sets.push_back({name, {}, line_number_});
    return sets.size() - 1;
  }

  std::string path_;
  SourcePos pos_;
  int line_number_ = 0;
  Mesh mesh_;
  std::map<std::int64_t, std::size_t> node_index_, element_index_;
  std::size_t element_count_ = 0;
  int pending_ = 0;  ///< nodes still expected for the element being read
  std::vector<LabelSet> labels_[2];  ///< element sets, node sets
  std::vector<LabelSet>* sets_ = nullptr;  ///< those of the *ELSET or *NSET whose lines are being read
  std::size_t current_set_ = 0;
  std::size_t block_set_ = no_set;  ///< the element set the *ELEMENT section being read adds to
  std::vector<int> block_lines_;
};

}  // namespace

Mesh read_abaqus_mesh(const std::string& path, const SourcePos& pos) { return Reader(path, pos).read(); }

}  // namespace peridot
