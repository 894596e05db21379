// Gmsh meshes, format 4.1, ASCII or binary (the format Gmsh writes by default since version 4). Read by hand:
// Debian's libgmsh brings the whole of Gmsh (OpenCASCADE, FLTK) to read one file, and the format is small and
// documented. The elements of the highest dimension in the file are taken (the lines and faces Gmsh also saves
// on boundaries are points of no body); each entity block is a block named entity_<tag>, each physical group of
// that dimension an element set, and each physical group of a lower dimension (a boundary surface, curve or
// point) a node set of its elements' nodes, named as in $PhysicalNames (else physical_<tag>).
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_map>

#include <fmt/format.h>

#include "peridot/geometry/mesh.hpp"

namespace peridot {

namespace {

struct GmshType {
  int nodes;      ///< nodes per element
  int dimension;  ///< 0 point, 1 line, 2 surface, 3 volume
  const char* name;
};

/// Gmsh's element types 1–19 (first and second order); 0 nodes for a type not listed.
GmshType gmsh_type(int type) {
  static const GmshType types[] = {
      {0, 0, "?"},           {2, 1, "2-node line"},      {3, 2, "3-node triangle"},   {4, 2, "4-node quadrangle"},
      {4, 3, "4-node tetrahedron"}, {8, 3, "8-node hexahedron"}, {6, 3, "6-node prism"}, {5, 3, "5-node pyramid"},
      {3, 1, "3-node line"}, {6, 2, "6-node triangle"},  {9, 2, "9-node quadrangle"}, {10, 3, "10-node tetrahedron"},
      {27, 3, "27-node hexahedron"}, {18, 3, "18-node prism"}, {14, 3, "14-node pyramid"}, {1, 0, "point"},
      {8, 2, "8-node quadrangle"}, {20, 3, "20-node hexahedron"}, {15, 3, "15-node prism"}, {13, 3, "13-node pyramid"}};
  return type >= 1 && type <= 19 ? types[type] : types[0];
}

std::optional<ElementShape> shape_of(int type) {
  switch (type) {
    case 2: return ElementShape::tri3;
    case 3: return ElementShape::quad4;
    case 4: return ElementShape::tet4;
    case 5: return ElementShape::hex8;
    case 6: return ElementShape::wedge6;
    default: return std::nullopt;
  }
}

class Reader {
 public:
  Reader(const std::string& path, const SourcePos& pos) : path_(path), pos_(pos) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(pos, fmt::format("cannot open '{}'", path));
    std::ostringstream content;
    content << in.rdbuf();
    data_ = content.str();
  }

  [[noreturn]] void fail(const std::string& message) const {
    if (binary_) throw InputError(pos_, fmt::format("'{}' (binary, at byte {}): {}", path_, at_, message));
    throw InputError(SourcePos{path_, line_, 1}, fmt::format("{}: {}", path_, message));
  }

  Mesh read() {
    bool format_seen = false, nodes_seen = false, elements_seen = false;
    while (true) {
      const std::string header = next_line();
      if (header.empty() && at_ >= data_.size()) break;
      if (header.empty() || header[0] != '$') continue;
      const std::string section = header.substr(1);
      if (section == "MeshFormat") {
        read_format();
        format_seen = true;
      } else if (!format_seen) {
        fail("no $MeshFormat first: not a Gmsh mesh");
      } else if (section == "PhysicalNames") {
        read_physical_names();
      } else if (section == "Entities") {
        read_entities();
      } else if (section == "Nodes") {
        read_nodes();
        nodes_seen = true;
      } else if (section == "Elements") {
        read_elements();
        elements_seen = true;
      } else {
        skip_section(section);  // $PartitionedEntities, $Periodic, $NodeData, ...: not needed for points
        continue;
      }
      expect_line("$End" + section);
    }
    if (!format_seen) fail("no $MeshFormat: not a Gmsh mesh");
    if (!nodes_seen || !elements_seen) fail("no $Nodes or no $Elements section");
    return assemble();
  }

 private:
  // -- reading ------------------------------------------------------------------------------------------

  std::string next_line() {
    const std::size_t end = data_.find('\n', at_);
    std::string line = data_.substr(at_, end == std::string::npos ? std::string::npos : end - at_);
    at_ = end == std::string::npos ? data_.size() : end + 1;
    ++line_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return line;
  }

  void expect_line(const std::string& expected) {
    if (binary_) {  // binary data ends where its text resumes, after a newline
      while (at_ < data_.size() && (data_[at_] == '\n' || data_[at_] == '\r')) ++at_;
    } else {
      skip_space();
    }
    const std::string line = next_line();
    if (line != expected) fail(fmt::format("expected {} here, found '{}'", expected, line.substr(0, 40)));
  }

  void skip_section(const std::string& section) {
    const std::size_t found = data_.find("\n$End" + section, at_ > 0 ? at_ - 1 : 0);
    if (found == std::string::npos) fail(fmt::format("${} is never closed", section));
    for (std::size_t i = at_; i <= found && i < data_.size(); ++i) line_ += data_[i] == '\n' ? 1 : 0;
    at_ = found + 1;
    next_line();  // $End<section>
  }

  void skip_space() {
    while (at_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[at_]))) {
      if (data_[at_] == '\n') ++line_;
      ++at_;
    }
  }

  std::string token() {
    skip_space();
    const std::size_t begin = at_;
    while (at_ < data_.size() && !std::isspace(static_cast<unsigned char>(data_[at_]))) ++at_;
    if (begin == at_) fail("the file ends inside a section");
    return data_.substr(begin, at_ - begin);
  }

  template <class T>
  T raw() {
    if (at_ + sizeof(T) > data_.size()) fail("the file ends inside a section");
    T value;
    std::memcpy(&value, data_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }

  std::int64_t integer() {
    if (binary_) return raw<std::int32_t>();
    const std::string t = token();
    char* end = nullptr;
    const long long value = std::strtoll(t.c_str(), &end, 10);
    if (*end != '\0') fail(fmt::format("'{}' is not an integer", t));
    return value;
  }
  std::uint64_t size() {
    if (binary_) return raw<std::uint64_t>();
    const std::int64_t value = integer();
    if (value < 0) fail(fmt::format("a count or tag of {}", value));
    return static_cast<std::uint64_t>(value);
  }
  double number() {
    if (binary_) return raw<double>();
    const std::string t = token();
    char* end = nullptr;
    const double value = std::strtod(t.c_str(), &end);
    if (*end != '\0') fail(fmt::format("'{}' is not a number", t));
    return value;
  }
  /// A count of items that each take at least `bytes` of a binary file: more than the file holds is a damaged file.
  std::uint64_t count(std::size_t bytes) {
    const std::uint64_t n = size();
    const std::size_t least = binary_ ? bytes : 2;  // a number and a space or newline as text
    if (n > (data_.size() - std::min(at_, data_.size())) / least + 1) fail(fmt::format("a count of {}, more than the file holds", n));
    return n;
  }

  // -- sections -----------------------------------------------------------------------------------------

  void read_format() {
    std::istringstream fields(next_line());
    std::string version;
    int file_type = -1, data_size = 0;
    fields >> version >> file_type >> data_size;
    if (version != "4.1")
      fail(fmt::format("Gmsh format {}; format 4.1 is read (Gmsh: File > Export, Version 4 ASCII or binary)", version));
    if (file_type == 1) {
      if (data_size != 8) fail(fmt::format("binary with {}-byte sizes; 8 is read", data_size));
      binary_ = true;
      if (raw<std::int32_t>() != 1) fail("binary of the other byte order");
    } else if (file_type != 0) {
      fail("the file type is neither 0 (ASCII) nor 1 (binary)");
    }
  }

  void read_physical_names() {  // text in binary files too
    const bool was_binary = binary_;
    binary_ = false;
    const std::uint64_t n = count(6);
    for (std::uint64_t k = 0; k < n; ++k) {
      const int dimension = static_cast<int>(integer());
      const std::int64_t tag = integer();
      skip_space();
      std::string rest = next_line();
      if (rest.size() >= 2 && rest.front() == '"' && rest.back() == '"') rest = rest.substr(1, rest.size() - 2);
      physical_names_[{dimension, tag}] = rest;
    }
    binary_ = was_binary;
  }

  void read_entities() {
    std::uint64_t counts[4];
    for (auto& c : counts) c = count(4);
    for (int dimension = 0; dimension < 4; ++dimension)
      for (std::uint64_t k = 0; k < counts[dimension]; ++k) {
        const std::int64_t tag = integer();
        for (int i = 0; i < (dimension == 0 ? 3 : 6); ++i) number();
        const std::uint64_t physicals = count(4);
        std::vector<std::int64_t>& groups = entity_groups_[{dimension, tag}];
        for (std::uint64_t p = 0; p < physicals; ++p) groups.push_back(integer());
        if (dimension > 0) {
          const std::uint64_t bounding = count(4);
          for (std::uint64_t b = 0; b < bounding; ++b) integer();
        }
      }
  }

  void read_nodes() {
    const std::uint64_t blocks = count(8);
    const std::uint64_t total = count(8);
    size();  // smallest tag
    size();  // largest tag
    mesh_.nodes.reserve(total);
    for (std::uint64_t b = 0; b < blocks; ++b) {
      integer();  // entity dimension
      integer();  // entity tag
      if (integer() != 0) fail("parametric node coordinates are not read; save without them");
      const std::uint64_t n = count(8);
      std::vector<std::uint64_t> tags(n);
      for (auto& t : tags) t = size();
      for (std::uint64_t i = 0; i < n; ++i) {
        const double x = number(), y = number(), z = number();
        if (!node_index_.emplace(tags[i], mesh_.nodes.size()).second) fail(fmt::format("node {} is given twice", tags[i]));
        mesh_.nodes.push_back({x, y, z});
      }
    }
  }

  void read_elements() {
    const std::uint64_t blocks = count(8);
    count(8);  // elements
    size();    // smallest tag
    size();    // largest tag
    for (std::uint64_t b = 0; b < blocks; ++b) {
      EntityBlock block;
      block.dimension = static_cast<int>(integer());
      block.entity = integer();
      block.type = static_cast<int>(integer());
      const GmshType type = gmsh_type(block.type);
      if (type.nodes == 0) fail(fmt::format("element type {} is not a Gmsh type this reader knows", block.type));
      const std::uint64_t n = count(8);
      block.line = line_;
      block.nodes.reserve(n * static_cast<std::uint64_t>(type.nodes));
      for (std::uint64_t e = 0; e < n; ++e) {
        size();  // element tag
        for (int i = 0; i < type.nodes; ++i) block.nodes.push_back(size());
      }
      max_dimension_ = std::max(max_dimension_, type.dimension);
      entity_blocks_.push_back(std::move(block));
    }
  }

  // -- assembly -----------------------------------------------------------------------------------------

  Mesh assemble() {
    mesh_.file = path_;
    mesh_.dimension = 3;
    std::map<std::int64_t, std::vector<std::size_t>> group_elements;  // physical tag → elements
    std::size_t first = 0;
    for (const EntityBlock& entity : entity_blocks_) {
      const GmshType type = gmsh_type(entity.type);
      if (type.dimension != max_dimension_) continue;  // boundary lines and faces, points
      const std::optional<ElementShape> shape = shape_of(entity.type);
      if (!shape) {
        line_ = entity.line;
        fail(fmt::format("{} elements (type {}) are not supported: 4-node tetrahedra, 8-node hexahedra, 6-node prisms, "
                         "and in 2D 3-node triangles and 4-node quadrangles",
                         type.name, entity.type));
      }
      MeshBlock block;
      block.name = fmt::format("entity_{}", entity.entity);
      block.shape = *shape;
      for (std::uint64_t tag : entity.nodes) {
        const auto found = node_index_.find(tag);
        if (found == node_index_.end()) {
          line_ = entity.line;
          fail(fmt::format("an element of entity {} names node {}, which $Nodes does not give", entity.entity, tag));
        }
        block.connectivity.push_back(static_cast<std::int64_t>(found->second));
      }
      const auto groups = entity_groups_.find({max_dimension_, entity.entity});
      if (groups != entity_groups_.end())
        for (std::int64_t group : groups->second)
          for (std::size_t e = 0; e < block.size(); ++e) group_elements[std::abs(group)].push_back(first + e);
      first += block.size();
      mesh_.blocks.push_back(std::move(block));
    }
    for (auto& [tag, elements] : group_elements) {
      const auto name = physical_names_.find({max_dimension_, tag});
      mesh_.element_sets.push_back(
          {name != physical_names_.end() ? name->second : fmt::format("physical_{}", tag), std::move(elements)});
    }
    // Physical groups of boundary faces, lines and points: node sets of their elements' nodes.
    std::map<std::pair<int, std::int64_t>, std::vector<std::size_t>> group_nodes;
    for (const EntityBlock& entity : entity_blocks_) {
      if (entity.dimension >= max_dimension_) continue;
      const auto groups = entity_groups_.find({entity.dimension, entity.entity});
      if (groups == entity_groups_.end()) continue;
      for (std::int64_t group : groups->second) {
        std::vector<std::size_t>& nodes = group_nodes[{entity.dimension, std::abs(group)}];
        for (std::uint64_t tag : entity.nodes) {
          const auto found = node_index_.find(tag);
          if (found == node_index_.end()) {
            line_ = entity.line;
            fail(fmt::format("an element of entity {} names node {}, which $Nodes does not give", entity.entity, tag));
          }
          nodes.push_back(found->second);
        }
      }
    }
    for (auto& [key, nodes] : group_nodes) {
      const auto name = physical_names_.find(key);
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      mesh_.node_sets.push_back(
          {name != physical_names_.end() ? name->second : fmt::format("physical_{}", key.second), std::move(nodes)});
    }
    return std::move(mesh_);
  }

  struct EntityBlock {
    int dimension = 0, type = 0, line = 0;
    std::int64_t entity = 0;
    std::vector<std::uint64_t> nodes;
  };

  std::string path_;
  SourcePos pos_;
  std::string data_;
  std::size_t at_ = 0;
  int line_ = 0;
  bool binary_ = false;
  Mesh mesh_;
  std::unordered_map<std::uint64_t, std::size_t> node_index_;
  std::map<std::pair<int, std::int64_t>, std::string> physical_names_;
  std::map<std::pair<int, std::int64_t>, std::vector<std::int64_t>> entity_groups_;
  std::vector<EntityBlock> entity_blocks_;
  int max_dimension_ = 0;
};

}  // namespace

Mesh read_gmsh_mesh(const std::string& path, const SourcePos& pos) { return Reader(path, pos).read(); }

}  // namespace peridot
