// Exodus II meshes through libexodusii: node coordinates and element blocks (SPHERE, TRI3, QUAD4, TET4, WEDGE6,
// HEX8 under their usual spellings), node sets and side sets (unnamed: nodelist_<id>, surface_<id>). A SPHERE
// element's volume is its attribute named "volume", or, unnamed, its second attribute (Sierra and Peridigm write
// radius, then volume).
#include <algorithm>
#include <optional>

#include <exodusII.h>
#include <fmt/format.h>

#include "peridot/geometry/mesh.hpp"

namespace peridot {

namespace {

/// The element shape of an Exodus topology name with this many nodes per element; none for others (a HEX20,
/// a SHELL4, a BEAM2, ...).
std::optional<ElementShape> shape_of(const std::string& topology, std::int64_t nodes) {
  const std::string t = upper_case(topology);
  auto is = [&](std::initializer_list<const char*> names, std::int64_t count) {
    return nodes == count && std::any_of(names.begin(), names.end(), [&](const char* n) { return t == n; });
  };
  if (is({"SPHERE", "SPHERE1"}, 1)) return ElementShape::sphere;
  if (is({"HEX", "HEX8", "HEXAHEDRON"}, 8)) return ElementShape::hex8;
  if (is({"TET", "TET4", "TETRA", "TETRA4"}, 4)) return ElementShape::tet4;
  if (is({"WEDGE", "WEDGE6"}, 6)) return ElementShape::wedge6;
  if (is({"QUAD", "QUAD4"}, 4)) return ElementShape::quad4;
  if (is({"TRI", "TRI3", "TRIANGLE", "TRIANGLE3"}, 3)) return ElementShape::tri3;
  return std::nullopt;
}

class ExodusFile {
 public:
  ExodusFile(const std::string& path, const SourcePos& pos) : path_(path), pos_(pos) {
    ex_opts(EX_DEFAULT);  // no printing, no abort: a failure is an InputError
    int word = sizeof(double), io_word = 0;
    float version = 0;
    id_ = ex_open(path.c_str(), EX_READ, &word, &io_word, &version);
    if (id_ < 0) throw InputError(pos, fmt::format("cannot read '{}' as an Exodus II file", path));
    ex_set_int64_status(id_, EX_ALL_INT64_API);
  }
  ~ExodusFile() { ex_close(id_); }
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;

  int id() const { return id_; }
  void check(int status, const char* what) const {
    if (status < 0) throw InputError(pos_, fmt::format("'{}': reading it as Exodus II failed in {} (status {})", path_, what, status));
  }
  /// The names of every entity of a type, "" where the file has none.
  std::vector<std::string> names(ex_entity_type type, std::size_t count) const {
    const auto length = static_cast<std::size_t>(std::max<std::int64_t>(ex_inquire_int(id_, EX_INQ_DB_MAX_USED_NAME_LENGTH), 32));
    ex_set_max_name_length(id_, static_cast<int>(length));
    std::vector<std::vector<char>> buffers(count, std::vector<char>(length + 1, '\0'));
    std::vector<char*> pointers;
    for (auto& b : buffers) pointers.push_back(b.data());
    if (count > 0) check(ex_get_names(id_, type, pointers.data()), "ex_get_names");
    std::vector<std::string> out;
    for (auto& b : buffers) out.emplace_back(b.data());
    return out;
  }

 private:
  std::string path_;
  SourcePos pos_;
  int id_ = -1;
};

}  // namespace

Mesh read_exodus_mesh(const std::string& path, const SourcePos& pos) {
  ExodusFile file(path, pos);
  ex_init_params init{};
  file.check(ex_get_init_ext(file.id(), &init), "ex_get_init_ext");
  Mesh mesh;
  mesh.file = path;
  mesh.dimension = static_cast<int>(init.num_dim);
  if (mesh.dimension < 1 || mesh.dimension > 3 || init.num_nodes < 0)
    throw InputError(pos, fmt::format("'{}': {} coordinates per node", path, init.num_dim));
  const auto node_count = static_cast<std::size_t>(init.num_nodes);
  std::vector<double> coordinate[3];
  for (auto& c : coordinate) c.assign(node_count, 0.0);
  if (node_count > 0)
    file.check(ex_get_coord(file.id(), coordinate[0].data(), mesh.dimension >= 2 ? coordinate[1].data() : nullptr,
                            mesh.dimension == 3 ? coordinate[2].data() : nullptr),
               "ex_get_coord");
  mesh.nodes.resize(node_count);
  for (std::size_t i = 0; i < node_count; ++i) mesh.nodes[i] = {coordinate[0][i], coordinate[1][i], coordinate[2][i]};

  const auto block_count = static_cast<std::size_t>(std::max<std::int64_t>(init.num_elem_blk, 0));
  std::vector<std::int64_t> ids(block_count);
  if (block_count > 0) file.check(ex_get_ids(file.id(), EX_ELEM_BLOCK, ids.data()), "ex_get_ids");
  const std::vector<std::string> names = file.names(EX_ELEM_BLOCK, block_count);
  for (std::size_t b = 0; b < block_count; ++b) {
    ex_block param{};
    param.id = ids[b];
    param.type = EX_ELEM_BLOCK;
    file.check(ex_get_block_param(file.id(), &param), "ex_get_block_param");
    MeshBlock block;
    block.name = names[b].empty() ? fmt::format("block_{}", ids[b]) : names[b];
    const std::optional<ElementShape> shape = shape_of(param.topology, param.num_nodes_per_entry);
    if (!shape)
      throw InputError(pos, fmt::format("'{}': block '{}' has elements of type {} with {} nodes; supported are SPHERE, "
                                        "HEX8, TET4, WEDGE6 and, in 2D, QUAD4 and TRI3",
                                        path, block.name, param.topology, param.num_nodes_per_entry));
    block.shape = *shape;
    const auto elements = static_cast<std::size_t>(std::max<std::int64_t>(param.num_entry, 0));
    block.connectivity.resize(elements * static_cast<std::size_t>(corner_count(block.shape)));
    if (elements > 0)
      file.check(ex_get_conn(file.id(), EX_ELEM_BLOCK, ids[b], block.connectivity.data(), nullptr, nullptr), "ex_get_conn");
    for (std::int64_t& node : block.connectivity) {
      if (node < 1 || node > init.num_nodes)
        throw InputError(pos, fmt::format("'{}': block '{}' names node {}, and the file has {} nodes", path, block.name,
                                          node, init.num_nodes));
      --node;  // Exodus numbers nodes from 1
    }
    if (block.shape == ElementShape::sphere && elements > 0) {
      const auto attributes = static_cast<std::size_t>(std::max<std::int64_t>(param.num_attribute, 0));
      std::vector<std::string> attribute_names(attributes);
      std::vector<std::vector<char>> buffers(attributes, std::vector<char>(MAX_STR_LENGTH + 1, '\0'));
      std::vector<char*> pointers;
      for (auto& buffer : buffers) pointers.push_back(buffer.data());
      if (attributes > 0 && ex_get_attr_names(file.id(), EX_ELEM_BLOCK, ids[b], pointers.data()) >= 0)
        for (std::size_t a = 0; a < attributes; ++a) attribute_names[a] = upper_case(buffers[a].data());
      std::size_t volume_index = attributes;
      for (std::size_t a = 0; a < attributes; ++a)
        if (attribute_names[a] == "VOLUME") volume_index = a;
      if (volume_index == attributes && attributes >= 2 && attribute_names[1].empty()) volume_index = 1;
      if (volume_index == attributes)
        throw InputError(pos, fmt::format("'{}': SPHERE block '{}' gives no volume: an attribute named volume, or a "
                                          "second attribute (radius, volume) is needed",
                                          path, block.name));
      std::vector<double> values(elements * attributes);
      file.check(ex_get_attr(file.id(), EX_ELEM_BLOCK, ids[b], values.data()), "ex_get_attr");
      block.sphere_volume.resize(elements);
      for (std::size_t e = 0; e < elements; ++e) block.sphere_volume[e] = values[e * attributes + volume_index];
    }
    mesh.blocks.push_back(std::move(block));
  }

  // Node sets (1-based node numbers) and side sets (1-based element numbers in block order, with the side of each).
  std::size_t element_count = 0;
  for (const MeshBlock& block : mesh.blocks) element_count += block.size();
  for (const ex_entity_type type : {EX_NODE_SET, EX_SIDE_SET}) {
    const bool nodes = type == EX_NODE_SET;
    const auto count = static_cast<std::size_t>(std::max<std::int64_t>(nodes ? init.num_node_sets : init.num_side_sets, 0));
    if (count == 0) continue;
    std::vector<std::int64_t> set_ids(count);
    file.check(ex_get_ids(file.id(), type, set_ids.data()), "ex_get_ids");
    const std::vector<std::string> set_names = file.names(type, count);
    for (std::size_t s = 0; s < count; ++s) {
      const std::string name =
          set_names[s].empty() ? fmt::format("{}_{}", nodes ? "nodelist" : "surface", set_ids[s]) : set_names[s];
      std::int64_t entries = 0, distribution = 0;
      file.check(ex_get_set_param(file.id(), type, set_ids[s], &entries, &distribution), "ex_get_set_param");
      if (entries <= 0)
        throw InputError(pos, fmt::format("'{}': {} set '{}' names no {}", path, nodes ? "node" : "side", name,
                                          nodes ? "node" : "element side"));
      std::vector<std::int64_t> members(static_cast<std::size_t>(entries)), sides(nodes ? 0 : members.size());
      file.check(ex_get_set(file.id(), type, set_ids[s], members.data(), nodes ? nullptr : sides.data()), "ex_get_set");
      const auto limit = static_cast<std::int64_t>(nodes ? node_count : element_count);
      std::vector<std::size_t> indices;
      for (std::int64_t member : members) {
        if (member < 1 || member > limit)
          throw InputError(pos, fmt::format("'{}': {} set '{}' names {} {}, and the file has {}", path,
                                            nodes ? "node" : "side", name, nodes ? "node" : "element", member, limit));
        indices.push_back(static_cast<std::size_t>(member - 1));
      }
      if (nodes) mesh.node_sets.push_back({name, std::move(indices)});
      else mesh.side_sets.push_back({name, std::move(indices)});
    }
  }
  return mesh;
}

}  // namespace peridot
