#include "peridot/output/exodus_writer.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

#include <exodusII.h>
#include <netcdf.h>
#include <unistd.h>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/output/exodus_pieces.hpp"

namespace peridot {

namespace {

/// Exodus keeps the last error per process; turn it into a readable sentence.
std::string exodus_message(int status) {
  const char* msg = nullptr;
  const char* func = nullptr;
  int code = 0;
  ex_get_err(&msg, &func, &code);
  std::string text;
  if (msg && *msg) text = msg;
  if (func && *func) text += std::string(text.empty() ? "" : " ") + "(in " + func + ")";
  // The code is a netCDF status (negative), an errno (positive) or an Exodus code (1000+); nc_strerror
  // knows the first two.
  if (code != 0 && code < 1000) text += std::string(text.empty() ? "" : ": ") + nc_strerror(code);
  if (text.empty()) text = "status " + std::to_string(status);
  return text;
}

[[noreturn]] void throw_exodus(const std::string& path, const char* what, int status) {
  throw std::runtime_error("Exodus output '" + path + "': " + what + " failed: " + exodus_message(status));
}

/// Exodus takes names as char*[] (non-const, for historical reasons); keep the strings alive alongside.
std::vector<char*> name_pointers(std::vector<std::string>& names) {
  std::vector<char*> out;
  out.reserve(names.size());
  for (auto& n : names) out.push_back(n.data());
  return out;
}

std::vector<std::string> nodal_variable_names(int dimension, const std::vector<std::string>& extra_fields) {
  std::vector<std::string> names;
  for (const PointField& field : point_fields())
    if (field.scope == FieldScope::always)
      for (const std::string& name : variable_names(field, dimension)) names.push_back(name);
  names.insert(names.end(), extra_fields.begin(), extra_fields.end());
  return names;
}

/// An optional field's values: its State array, or State::point_outputs under its name.
const std::vector<double>& optional_field(const State& state, const std::string& name) {
  const PointField* field = find_point_field(name);
  const ConstFieldStorage where = field ? field->in(state) : ConstFieldStorage{};
  if (where.scalar) return *where.scalar;
  return state.point_outputs.at(name);
}

}  // namespace

const std::vector<std::string>& ExodusWriter::optional_fields() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const PointField& field : point_fields())
      if (field.scope != FieldScope::always) all.emplace_back(field.name);
    return all;
  }();
  return names;
}

double ExodusWriter::equivalent_radius(double volume, int dimension, double cross_section) {
  if (dimension == 1) return 0.5 * volume / cross_section;
  if (dimension == 2) return std::sqrt(volume / (std::numbers::pi * cross_section));
  return std::cbrt(3.0 * volume / (4.0 * std::numbers::pi));
}

void ExodusWriter::check(int status, const char* what) const {
  if (status < 0) throw_exodus(path_, what, status);
}

std::string ExodusWriter::piece_path(const std::string& path, int rank, int ranks) {
  const std::string count = std::to_string(ranks);
  std::string index = std::to_string(rank);
  index.insert(0, count.size() > index.size() ? count.size() - index.size() : 0, '0');
  return path + "." + count + "." + index;
}

ExodusWriter::ExodusWriter(const std::string& path, const Discretization& disc,
                           const std::vector<NodeSetOutput>& node_sets, const std::string& title,
                           double cross_section, const std::vector<std::string>& extra_fields, const ExodusPiece* piece)
    : path_(path) {
  const std::size_t n = piece ? piece->point_index.size() : disc.num_points();
  PERIDOT_REQUIRE(disc.dimension >= 1 && disc.dimension <= 3, "Exodus output needs dimension 1, 2 or 3");
  PERIDOT_REQUIRE(n <= disc.num_points(), "an Exodus piece with more points than the discretization");
  PERIDOT_REQUIRE(disc.x.size() == disc.num_points(), "disc.x and disc.volume differ in size");
  PERIDOT_REQUIRE(disc.block.empty() || disc.block.size() == disc.num_points(), "disc.block and disc.volume differ in size");
  PERIDOT_REQUIRE(disc.input_id.empty() || disc.input_id.size() == disc.num_points(),
                  "disc.input_id and disc.volume differ in size");
  PERIDOT_REQUIRE(disc.dimension == 3 || cross_section > 0, "1D and 2D Exodus output need a positive cross-section");
  ExodusMesh mesh;
  mesh.dimension = disc.dimension;
  mesh.title = title;
  for (int d = 0; d < disc.dimension; ++d) {
    mesh.coord[d].resize(n);
    for (std::size_t i = 0; i < n; ++i) mesh.coord[d][i] = disc.x(i, d);
  }
  mesh.node_id.resize(n);
  mesh.block.resize(n);
  mesh.radius.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t id = disc.id_of(i) + 1;
    PERIDOT_REQUIRE(id <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
                    "disc.input_id does not fit a 32-bit Exodus id");
    mesh.node_id[i] = static_cast<int>(id);
    mesh.block[i] = disc.block.empty() ? 0 : disc.block[i];
    mesh.radius[i] = equivalent_radius(disc.volume[i], disc.dimension, cross_section);
  }
  mesh.block_names = disc.block_names;
  mesh.node_sets = node_sets;
  volume_.assign(disc.volume.begin(), disc.volume.begin() + static_cast<std::ptrdiff_t>(n));
  extra_fields_ = extra_fields;
  create(mesh, piece);
}

ExodusWriter::ExodusWriter(const std::string& path, const ExodusMesh& mesh, const std::vector<std::string>& extra_fields,
                           const ExodusPiece* piece)
    : path_(path) {
  extra_fields_ = extra_fields;
  create(mesh, piece);
}

void ExodusWriter::create(const ExodusMesh& mesh, const ExodusPiece* piece) {
  const std::string& path = path_;
  dimension_ = mesh.dimension;
  num_points_ = mesh.num_points();
  const std::size_t n = num_points_;
  PERIDOT_REQUIRE(dimension_ >= 1 && dimension_ <= 3, "Exodus output needs dimension 1, 2 or 3");
  PERIDOT_REQUIRE(n > 0 || piece, "Exodus output of an empty discretization");
  // The default (32-bit integer) Exodus API numbers nodes with int.
  PERIDOT_REQUIRE(n < static_cast<std::size_t>(std::numeric_limits<int>::max()),
                  "too many points for 32-bit Exodus ids");
  PERIDOT_REQUIRE(mesh.block.size() == n && mesh.radius.size() == n, "Exodus mesh arrays differ in size");
  for (int d = 0; d < dimension_; ++d) PERIDOT_REQUIRE(mesh.coord[d].size() == n, "Exodus mesh arrays differ in size");
  for (const auto& set : mesh.node_sets)
    for (std::uint32_t p : set.points)
      PERIDOT_REQUIRE(p < n, "node set '" + set.name + "' names point " + std::to_string(p) + " of " +
                                 std::to_string(n));
  if (piece) {
    PERIDOT_REQUIRE(piece->point_index.size() == n, "an Exodus piece's point_index does not match its points");
    PERIDOT_REQUIRE(piece->blocks.size() == piece->block_sizes.size() && piece->node_set_sizes.size() == mesh.node_sets.size(),
                    "an Exodus piece's global counts do not match its blocks and node sets");
    point_index_ = piece->point_index;
    piece_ = true;
  }
  global_points_ = piece ? piece->global_points : n;

  // Blocks: those present, ascending (a piece: every block of the whole problem, some perhaps empty here).
  std::vector<std::int32_t> blocks;
  if (piece) {
    blocks = piece->blocks;
  } else {
    blocks = mesh.block;
    std::sort(blocks.begin(), blocks.end());
    blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
  }
  std::vector<std::size_t> block_count(blocks.size(), 0);  // elements per entry of `blocks`
  for (std::size_t i = 0; i < n; ++i) {
    PERIDOT_REQUIRE(mesh.block[i] >= 0, "negative block index");
    const auto b = std::lower_bound(blocks.begin(), blocks.end(), mesh.block[i]);
    PERIDOT_REQUIRE(b != blocks.end() && *b == mesh.block[i], "a point of a block the piece does not list");
    ++block_count[static_cast<std::size_t>(b - blocks.begin())];
  }
  // Element order: stable counting sort of the points by block.
  element_points_.resize(n);
  {
    std::vector<std::size_t> next(blocks.size(), 0);
    for (std::size_t b = 1; b < blocks.size(); ++b) next[b] = next[b - 1] + block_count[b - 1];
    for (std::size_t i = 0; i < n; ++i) {
      const auto b = std::lower_bound(blocks.begin(), blocks.end(), mesh.block[i]) - blocks.begin();
      element_points_[next[b]++] = static_cast<std::uint32_t>(i);
    }
  }
  // Node ids must be unique for readers.
  const std::vector<int>& node_id = mesh.node_id;
  {
    std::vector<int> sorted = node_id;
    std::sort(sorted.begin(), sorted.end());
    PERIDOT_REQUIRE(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end(), "duplicate node ids");
    PERIDOT_REQUIRE(sorted.empty() || sorted.front() > 0, "node ids start at 1");
  }

  for (const std::string& name : extra_fields_)
    PERIDOT_REQUIRE(std::find(optional_fields().begin(), optional_fields().end(), name) != optional_fields().end(),
                    "unknown optional Exodus field");
  variable_names_ = nodal_variable_names(dimension_, extra_fields_);
  buffer_.assign(n, 0.0);

  // Doubles on disk and in the API. EX_LARGE_MODEL (netCDF 64-bit offset) lifts the 2 GiB limits per
  // variable and stores each nodal variable on its own. Not in share mode (EX_NOSHARE, which is what
  // ex_create does anyway): netCDF then keeps the record count in memory until ex_update, which is what
  // makes frames appear whole (see write_frame).
  int comp_ws = sizeof(double);
  int io_ws = sizeof(double);
  ex_opts(EX_DEFAULT);  // no abort, no printing: every failure becomes an exception with the message
  // Created under another name and renamed once the header is complete, so that a process killed while
  // creating it never leaves a file of this name that cannot be opened.
  const std::string creating = path + ".creating";
  ::unlink(creating.c_str());  // a stale one, or a symlink of that name: removed, not followed
  exoid_ = ex_create(creating.c_str(), EX_CLOBBER | EX_LARGE_MODEL | EX_NOSHARE, &comp_ws, &io_ws);
  if (exoid_ < 0) {
    exoid_ = -1;
    throw_exodus(path_, "creating the file", -1);
  }

  try {
    // Exodus cuts names at 32 characters unless told the longest one first (names are stored in the file up
    // to the netCDF limit; readers ask the file how long its names are).
    std::size_t longest_name = MAX_NAME_LENGTH;
    for (const auto& name : mesh.block_names) longest_name = std::max(longest_name, name.size());
    for (const auto& set : mesh.node_sets) longest_name = std::max(longest_name, set.name.size());
    PERIDOT_REQUIRE(longest_name <= NC_MAX_NAME, "a block or node set name is longer than 256 characters");
    check(ex_set_max_name_length(exoid_, static_cast<int>(longest_name)), "ex_set_max_name_length");

    ex_init_params init{};
    // Exodus titles hold at most MAX_LINE_LENGTH characters; longer ones are cut rather than refused.
    mesh.title.copy(init.title, MAX_LINE_LENGTH);
    init.num_dim = dimension_;
    init.num_nodes = static_cast<int64_t>(n);
    init.num_elem = static_cast<int64_t>(n);
    init.num_elem_blk = static_cast<int64_t>(blocks.size());
    init.num_node_sets = static_cast<int64_t>(mesh.node_sets.size());
    // Serial: the node number map below is the classic node_num_map, no named map. A piece adds "point_index".
    init.num_node_maps = piece && n > 0 ? 1 : 0;  // a piece without points has no node to map
    check(ex_put_init_ext(exoid_, &init), "ex_put_init_ext");

    if (piece) {  // Nemesis: this is piece `rank` of `ranks`, and what the whole problem holds
      char file_type[] = "p";
      check(ex_put_init_info(exoid_, piece->ranks, 1, file_type), "ex_put_init_info");
      check(ex_put_init_global(exoid_, static_cast<int64_t>(piece->global_points), static_cast<int64_t>(piece->global_points),
                               static_cast<int64_t>(blocks.size()), static_cast<int64_t>(mesh.node_sets.size()), 0),
            "ex_put_init_global");
      std::vector<int> ids, counts;
      for (std::size_t b = 0; b < blocks.size(); ++b) {
        ids.push_back(blocks[b] + 1);
        counts.push_back(static_cast<int>(piece->block_sizes[b]));
      }
      if (!ids.empty()) check(ex_put_eb_info_global(exoid_, ids.data(), counts.data()), "ex_put_eb_info_global");
      if (!mesh.node_sets.empty()) {
        std::vector<int> set_ids, set_counts, factors(mesh.node_sets.size(), 0);
        for (std::size_t s = 0; s < mesh.node_sets.size(); ++s) {
          set_ids.push_back(static_cast<int>(s + 1));
          set_counts.push_back(static_cast<int>(piece->node_set_sizes[s]));
        }
        check(ex_put_ns_param_global(exoid_, set_ids.data(), set_counts.data(), factors.data()), "ex_put_ns_param_global");
      }
      // Every point internal: a point belongs to one rank, no node is shared.
      check(ex_put_loadbal_param(exoid_, static_cast<int64_t>(n), 0, 0, static_cast<int64_t>(n), 0, 0, 0, piece->rank),
            "ex_put_loadbal_param");
      std::vector<int> local(n);
      for (std::size_t i = 0; i < n; ++i) local[i] = static_cast<int>(i + 1);
      if (n > 0) {
        check(ex_put_processor_node_maps(exoid_, local.data(), nullptr, nullptr, piece->rank), "ex_put_processor_node_maps");
        check(ex_put_processor_elem_maps(exoid_, local.data(), nullptr, piece->rank), "ex_put_processor_elem_maps");
      }
    }

    if (n > 0) {
      check(ex_put_coord(exoid_, mesh.coord[0].data(), dimension_ >= 2 ? mesh.coord[1].data() : nullptr,
                         dimension_ == 3 ? mesh.coord[2].data() : nullptr),
            "ex_put_coord");
    }
    {
      std::vector<std::string> coord_names{"x", "y", "z"};
      coord_names.resize(static_cast<std::size_t>(dimension_));
      auto ptrs = name_pointers(coord_names);
      check(ex_put_coord_names(exoid_, ptrs.data()), "ex_put_coord_names");
    }
    if (n > 0) check(ex_put_id_map(exoid_, EX_NODE_MAP, node_id.data()), "ex_put_id_map (nodes)");
    if (piece && n > 0) {
      std::vector<int> index(n);
      for (std::size_t i = 0; i < n; ++i) index[i] = static_cast<int>(piece->point_index[i] + 1);
      check(ex_put_num_map(exoid_, EX_NODE_MAP, 1, index.data()), "ex_put_num_map (point_index)");
      char name[] = "point_index";
      check(ex_put_name(exoid_, EX_NODE_MAP, 1, name), "ex_put_name (point_index)");
    }

    std::vector<std::string> block_names;
    std::size_t first = 0;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const ex_entity_id id = blocks[b] + 1;
      const std::size_t count = block_count[b];
      check(ex_put_block(exoid_, EX_ELEM_BLOCK, id, "SPHERE", static_cast<int64_t>(count), 1, 0, 0, 1),
            "ex_put_block");
      if (count > 0) {  // an empty block (of a piece) has no connectivity or attribute variable
        std::vector<int> conn(count);
        std::vector<double> radius(count);
        for (std::size_t e = 0; e < count; ++e) {
          const std::uint32_t p = element_points_[first + e];
          conn[e] = static_cast<int>(p) + 1;
          radius[e] = mesh.radius[p];
        }
        check(ex_put_conn(exoid_, EX_ELEM_BLOCK, id, conn.data(), nullptr, nullptr), "ex_put_conn");
        check(ex_put_attr(exoid_, EX_ELEM_BLOCK, id, radius.data()), "ex_put_attr");
      }
      std::vector<std::string> attr_names{"radius"};
      auto attr_ptrs = name_pointers(attr_names);
      check(ex_put_attr_names(exoid_, EX_ELEM_BLOCK, id, attr_ptrs.data()), "ex_put_attr_names");
      const auto k = static_cast<std::size_t>(blocks[b]);
      block_names.push_back(k < mesh.block_names.size() && !mesh.block_names[k].empty()
                                ? mesh.block_names[k]
                                : "block_" + std::to_string(k));
      first += count;
    }
    if (!blocks.empty()) {
      auto ptrs = name_pointers(block_names);
      check(ex_put_names(exoid_, EX_ELEM_BLOCK, ptrs.data()), "ex_put_names (blocks)");
    }
    if (n > 0) {
      // Element ids = node id of the element's point, so that a reader can tell either by the same number.
      std::vector<int> elem_id(n);
      for (std::size_t e = 0; e < n; ++e) elem_id[e] = node_id[element_points_[e]];
      check(ex_put_id_map(exoid_, EX_ELEM_MAP, elem_id.data()), "ex_put_id_map (elements)");
    }

    if (!mesh.node_sets.empty()) {
      std::vector<std::string> set_names;
      for (std::size_t s = 0; s < mesh.node_sets.size(); ++s) {
        const ex_entity_id id = static_cast<ex_entity_id>(s + 1);
        const auto& points = mesh.node_sets[s].points;
        check(ex_put_set_param(exoid_, EX_NODE_SET, id, static_cast<int64_t>(points.size()), 0),
              "ex_put_set_param");
        if (!points.empty()) {  // an empty set has no node list variable to write into
          std::vector<int> nodes(points.size());
          for (std::size_t k = 0; k < points.size(); ++k) nodes[k] = static_cast<int>(points[k]) + 1;
          check(ex_put_set(exoid_, EX_NODE_SET, id, nodes.data(), nullptr), "ex_put_set");
        }
        set_names.push_back(mesh.node_sets[s].name);
      }
      auto ptrs = name_pointers(set_names);
      check(ex_put_names(exoid_, EX_NODE_SET, ptrs.data()), "ex_put_names (node sets)");
    }

    if (n > 0) {  // Exodus has no nodal variables without nodes: a piece without points holds times only
      check(ex_put_variable_param(exoid_, EX_NODAL, static_cast<int>(variable_names_.size())),
            "ex_put_variable_param");
      auto var_ptrs = name_pointers(variable_names_);
      check(ex_put_variable_names(exoid_, EX_NODAL, static_cast<int>(var_ptrs.size()), var_ptrs.data()),
            "ex_put_variable_names");
    }
    // The mesh alone, with zero time steps, is a valid file from here on.
    check(ex_update(exoid_), "ex_update");
    if (::rename(creating.c_str(), path.c_str()) != 0)
      throw std::runtime_error(fmt::format("{}: cannot rename {} to it: {}", path_, creating, std::strerror(errno)));
  } catch (...) {
    release();
    ::unlink(creating.c_str());
    throw;
  }
}

ExodusWriter::ExodusWriter(ExodusWriter&& other) noexcept
    : exoid_(std::exchange(other.exoid_, -1)),
      path_(std::move(other.path_)),
      dimension_(other.dimension_),
      num_points_(other.num_points_),
      frames_(other.frames_),
      extra_fields_(std::move(other.extra_fields_)),
      element_points_(std::move(other.element_points_)),
      point_index_(std::move(other.point_index_)),
      piece_(other.piece_),
      global_points_(other.global_points_),
      variable_names_(std::move(other.variable_names_)),
      volume_(std::move(other.volume_)),
      buffer_(std::move(other.buffer_)) {}

ExodusWriter& ExodusWriter::operator=(ExodusWriter&& other) noexcept {
  if (this != &other) {
    release();
    exoid_ = std::exchange(other.exoid_, -1);
    path_ = std::move(other.path_);
    dimension_ = other.dimension_;
    num_points_ = other.num_points_;
    frames_ = other.frames_;
    extra_fields_ = std::move(other.extra_fields_);
    element_points_ = std::move(other.element_points_);
    point_index_ = std::move(other.point_index_);
    piece_ = other.piece_;
    global_points_ = other.global_points_;
    variable_names_ = std::move(other.variable_names_);
    volume_ = std::move(other.volume_);
    buffer_ = std::move(other.buffer_);
  }
  return *this;
}

ExodusWriter::~ExodusWriter() { release(); }

void ExodusWriter::release() noexcept {
  if (exoid_ >= 0) ex_close(exoid_);
  exoid_ = -1;
}

void ExodusWriter::close() {
  if (exoid_ < 0) return;
  const int id = std::exchange(exoid_, -1);  // closed (or unusable) whatever ex_close says
  check(ex_close(id), "ex_close");
}

// What a reader sees if the process dies while a frame is written.
// The file is netCDF-3 (64-bit offset) and ex_create opens it without NC_SHARE (checked: Exodus 6.02 on
// Debian 12 calls nc_create with NC_64BIT_OFFSET|NC_CLASSIC_MODEL). Every time step is one "record" of the
// unlimited dimension time_step, and the number of records is a single 4-byte count in the file header.
// Without NC_SHARE, netCDF writes that count to the file only in nc_sync/nc_close (ex_update/ex_close). The
// values of an unfinished frame may reach the file earlier (netCDF writes its 8 KiB buffer out whenever it
// fills), but they lie beyond the record count the header states, so a reader (Exodus, netCDF4-python,
// ParaView) sees exactly the frames whose write_frame() had returned, each with its time, and nothing of the
// unfinished one; the file is merely longer than its header says. ExodusWriter.DeathMidFrameLeavesCompleteFrames
// checks this with a process killed by SIGXFSZ after part of a frame went to disk. nc_sync writes the buffered values
// before the header page with the count, so a kill inside ex_update leaves the old count or the new count
// with its values already handed to the kernel.
// Writing the time last adds nothing to that here; it keeps the order right for a file in share mode, where
// the count is written as soon as a record grows, so that a reader trusting time_whole finds the time of
// step k only once its values are there. Beware: ex_open(EX_WRITE) of this Exodus version always sets
// NC_SHARE, so appending to an existing file (a restart, say) would show partial frames after a kill.
// Not covered: a crash of the machine itself or a full disk. Nothing is fsync'ed (unless netCDF was built
// with fsync), so after a power loss the kernel may have written the header before the data.
void ExodusWriter::write_frame(double time, const State& state) {
  PERIDOT_REQUIRE(exoid_ >= 0, "write_frame on a closed Exodus writer");
  PERIDOT_REQUIRE(volume_.size() == num_points_, "write_frame(State) on a writer made without a discretization");
  const std::size_t n = num_points_;
  // Everything is checked before anything is written, so that a bad state never leaves half a frame behind.
  // A piece writes the first n points of its rank's state (owned points first, then ghosts).
  const bool exact = !piece_;
  auto fits = [&](std::size_t size) { return exact ? size == n : size >= n; };
  PERIDOT_REQUIRE(fits(state.u.size()) && fits(state.v.size()) && fits(state.force.size()),
                  "state vector fields do not match the discretization");
  for (const std::vector<double>* field : {&state.damage, &state.dilatation, &state.weighted_volume})
    PERIDOT_REQUIRE(field->empty() || fits(field->size()), "state scalar field does not match the discretization");
  // Where each variable's values come from: a vector field's component, a scalar array, zeros, the volume.
  struct Source {
    const VectorField* vector = nullptr;
    int component = 0;
    const double* values = nullptr;  // null with no vector: zeros
  };
  std::vector<Source> sources;
  for (const PointField& field : point_fields()) {
    if (field.scope != FieldScope::always) continue;
    const ConstFieldStorage where = field.in(state);
    if (where.vector) {
      for (int d = 0; d < dimension_; ++d) sources.push_back({where.vector, d, nullptr});
      continue;
    }
    if (!where.scalar) sources.push_back({nullptr, 0, volume_.data()});  // no storage: the volume
    else sources.push_back({nullptr, 0, where.scalar->empty() ? nullptr : where.scalar->data()});
  }
  for (const std::string& name : extra_fields_) {
    const std::vector<double>& field = optional_field(state, name);
    PERIDOT_REQUIRE(fits(field.size()), "optional state field does not match the discretization");
    sources.push_back({nullptr, 0, field.data()});
  }
  PERIDOT_ASSERT(sources.size() == variable_names_.size());
  write_frame(time, [&](std::size_t k) -> const double* {
    const Source& source = sources[k];
    if (source.vector) {
      for (std::size_t i = 0; i < n; ++i) buffer_[i] = (*source.vector)(i, source.component);
      return buffer_.data();
    }
    if (source.values) return source.values;
    std::fill(buffer_.begin(), buffer_.end(), 0.0);
    return buffer_.data();
  });
}

void ExodusWriter::write_frame(double time, const std::function<const double*(std::size_t)>& column) {
  PERIDOT_REQUIRE(exoid_ >= 0, "write_frame on a closed Exodus writer");
  const int step = frames_ + 1;
  const auto count = static_cast<int64_t>(num_points_);
  // Exodus variable indices are 1-based, in variable_names_ order. A piece without points has no values.
  for (std::size_t k = 0; k < variable_names_.size(); ++k) {
    const double* values = column(k);
    if (count > 0) check(ex_put_var(exoid_, step, EX_NODAL, static_cast<int>(k + 1), 1, count, values), "ex_put_var");
  }
  check(ex_put_time(exoid_, step, &time), "ex_put_time");
  check(ex_update(exoid_), "ex_update");
  frames_ = step;
}

int ExodusWriter::copy_frames(const std::vector<std::string>& earlier, double time_step, std::int64_t last_step,
                              std::int64_t every) {
  PERIDOT_REQUIRE(exoid_ >= 0, "copy_frames on a closed Exodus writer");
  PERIDOT_REQUIRE(!earlier.empty(), "copy_frames without earlier files");
  const std::size_t n = num_points_;
  // This writer's points by their index in the whole problem (a serial writer: the index itself).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> mine;  // (index in the whole problem, point here)
  if (piece_) {
    mine.reserve(n);
    for (std::size_t i = 0; i < n; ++i) mine.emplace_back(point_index_[i], static_cast<std::uint32_t>(i));
    std::sort(mine.begin(), mine.end());
  }
  auto here = [&](std::uint32_t g) -> std::int64_t {
    if (!piece_) return g < n ? static_cast<std::int64_t>(g) : -1;
    const auto it = std::lower_bound(mine.begin(), mine.end(), std::make_pair(g, std::uint32_t{0}));
    return it != mine.end() && it->first == g ? static_cast<std::int64_t>(it->second) : -1;
  };
  // Per earlier file, which of its points are this writer's, and where they go.
  struct Source {
    ExodusInput input;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> moves;  // (point there, point here)
  };
  std::vector<Source> sources;
  std::vector<std::uint8_t> found(n, 0);
  std::size_t matched = 0;
  for (const std::string& path : earlier) {
    ExodusInput input(path);
    if (input.global_points() != global_points_)
      throw std::runtime_error("Exodus file '" + path + "' has other points than this run writes");
    if (input.num_points() > 0 && input.variable_names() != variable_names_)  // (a piece without points has none)
      throw std::runtime_error("Exodus file '" + path + "' has other fields than this run writes");
    const std::vector<std::uint32_t> index = input.point_index();
    std::vector<std::pair<std::uint32_t, std::uint32_t>> moves;
    for (std::size_t k = 0; k < index.size(); ++k) {
      const std::int64_t i = here(index[k]);
      if (i < 0) continue;
      if (found[static_cast<std::size_t>(i)]++)
        throw std::runtime_error("Exodus file '" + path + "' repeats a point of the earlier results");
      moves.emplace_back(static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(i));
      ++matched;
    }
    sources.push_back({std::move(input), std::move(moves)});
  }
  if (matched != n)
    throw std::runtime_error("Exodus file '" + earlier.front() + "' has other points than this run writes");
  int steps = sources.front().input.steps();
  for (const Source& source : sources) steps = std::min(steps, source.input.steps());  // a stopped run's pieces
  std::vector<double> values(n), column;
  int copied = 0;
  for (int step = 1; step <= steps; ++step) {
    const double time = sources.front().input.time(step);
    const auto run_step = static_cast<std::int64_t>(std::llround(time / time_step));
    if (run_step > last_step || run_step % every != 0) continue;
    write_frame(time, [&](std::size_t variable) {
      for (const Source& source : sources) {
        if (source.moves.empty()) continue;
        source.input.read_variable(step, variable, column);
        for (const auto& [there, at] : source.moves) values[at] = column[there];
      }
      return values.data();
    });
    ++copied;
  }
  return copied;
}

}  // namespace peridot
