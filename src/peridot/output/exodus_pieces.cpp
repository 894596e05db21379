#include "peridot/output/exodus_pieces.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>

#include <exodusII.h>
#include <netcdf.h>

#include <fmt/format.h>

#include "peridot/state/point_fields.hpp"

namespace peridot {

namespace fs = std::filesystem;

namespace {

std::string library_message() {
  const char* msg = nullptr;
  const char* func = nullptr;
  int code = 0;
  ex_get_err(&msg, &func, &code);
  std::string text = msg && *msg ? msg : "";
  if (code != 0 && code < 1000) text += std::string(text.empty() ? "" : ": ") + nc_strerror(code);
  return text.empty() ? "unknown error" : text;
}

/// Names of up to the file's longest name length.
std::string read_name(int exoid, ex_entity_type type, ex_entity_id id) {
  std::vector<char> name(NC_MAX_NAME + 1, '\0');
  if (ex_get_name(exoid, type, id, name.data()) < 0) return {};
  return name.data();
}

}  // namespace

ExodusInput::ExodusInput(const std::string& path) : path_(path) {
  ex_opts(EX_DEFAULT);
  int cpu_word_size = 8, io_word_size = 0;
  float version = 0;
  exoid_ = ex_open(path.c_str(), EX_READ, &cpu_word_size, &io_word_size, &version);
  if (exoid_ < 0) {
    exoid_ = -1;
    throw std::runtime_error(fmt::format("Exodus file '{}': cannot open it: {}", path, library_message()));
  }
  try {
    const int longest = static_cast<int>(ex_inquire_int(exoid_, EX_INQ_DB_MAX_USED_NAME_LENGTH));
    check(ex_set_max_name_length(exoid_, std::max(longest, 32)), "ex_set_max_name_length");
    ex_init_params params{};
    check(ex_get_init_ext(exoid_, &params), "ex_get_init_ext");
    num_points_ = static_cast<std::size_t>(params.num_nodes);
    dimension_ = static_cast<int>(params.num_dim);
    global_points_ = num_points_;
    int variables = 0;
    check(ex_get_variable_param(exoid_, EX_NODAL, &variables), "ex_get_variable_param");
    for (int k = 0; k < variables; ++k) {
      std::vector<char> name(NC_MAX_NAME + 1, '\0');
      check(ex_get_variable_name(exoid_, EX_NODAL, k + 1, name.data()), "ex_get_variable_name");
      variable_names_.emplace_back(name.data());
    }
    // A piece carries the Nemesis parameters (its rank count, the whole problem's size); a whole file none.
    int procs = 0, in_file = 0;
    char type[2] = {};
    if (ex_get_init_info(exoid_, &procs, &in_file, type) == 0 && type[0] == 'p' && procs > 1) {
      ranks_ = procs;
      int nodes = 0, elems = 0, blocks = 0, sets = 0, sides = 0;
      check(ex_get_init_global(exoid_, &nodes, &elems, &blocks, &sets, &sides), "ex_get_init_global");
      global_points_ = static_cast<std::uint64_t>(nodes);
    }
  } catch (...) {
    ex_close(exoid_);
    exoid_ = -1;
    throw;
  }
}

ExodusInput::ExodusInput(ExodusInput&& other) noexcept
    : path_(std::move(other.path_)),
      exoid_(std::exchange(other.exoid_, -1)),
      num_points_(other.num_points_),
      dimension_(other.dimension_),
      ranks_(other.ranks_),
      global_points_(other.global_points_),
      variable_names_(std::move(other.variable_names_)) {}

ExodusInput::~ExodusInput() {
  if (exoid_ >= 0) ex_close(exoid_);
}

void ExodusInput::check(int status, const char* what) const {
  if (status < 0) throw std::runtime_error(fmt::format("Exodus file '{}': {} failed: {}", path_, what, library_message()));
}

int ExodusInput::steps() const { return static_cast<int>(ex_inquire_int(exoid_, EX_INQ_TIME)); }

double ExodusInput::time(int step) const {
  double t = 0;
  check(ex_get_time(exoid_, step, &t), "ex_get_time");
  return t;
}

void ExodusInput::read_variable(int step, std::size_t variable, std::vector<double>& values) const {
  values.resize(num_points_);
  if (num_points_ == 0) return;
  check(ex_get_var(exoid_, step, EX_NODAL, static_cast<int>(variable + 1), 1, static_cast<int64_t>(num_points_), values.data()),
        "ex_get_var");
}

std::vector<std::uint32_t> ExodusInput::point_index() const {
  std::vector<std::uint32_t> index(num_points_);
  if (ranks_ == 1 && global_points_ == num_points_ && ex_inquire_int(exoid_, EX_INQ_NODE_MAP) == 0) {
    for (std::size_t i = 0; i < num_points_; ++i) index[i] = static_cast<std::uint32_t>(i);
    return index;
  }
  std::vector<int> map(num_points_);
  if (num_points_ > 0) check(ex_get_num_map(exoid_, EX_NODE_MAP, 1, map.data()), "ex_get_num_map (point_index)");
  for (std::size_t i = 0; i < num_points_; ++i) {
    if (map[i] < 1 || static_cast<std::uint64_t>(map[i]) > global_points_)
      throw std::runtime_error(fmt::format("Exodus file '{}': point_index {} outside 1 … {}", path_, map[i], global_points_));
    index[i] = static_cast<std::uint32_t>(map[i] - 1);
  }
  return index;
}

ExodusMesh ExodusInput::mesh() const {
  ExodusMesh mesh;
  const std::size_t n = num_points_;
  ex_init_params params{};
  check(ex_get_init_ext(exoid_, &params), "ex_get_init_ext");
  mesh.dimension = dimension_;
  mesh.title = params.title;
  for (int d = 0; d < dimension_; ++d) mesh.coord[d].resize(n);
  if (n > 0) {
    check(ex_get_coord(exoid_, mesh.coord[0].data(), dimension_ >= 2 ? mesh.coord[1].data() : nullptr,
                       dimension_ == 3 ? mesh.coord[2].data() : nullptr),
          "ex_get_coord");
    mesh.node_id.resize(n);
    check(ex_get_id_map(exoid_, EX_NODE_MAP, mesh.node_id.data()), "ex_get_id_map");
  }
  mesh.block.assign(n, -1);
  mesh.radius.assign(n, 0.0);
  std::vector<int> block_ids(static_cast<std::size_t>(params.num_elem_blk));
  if (!block_ids.empty()) check(ex_get_ids(exoid_, EX_ELEM_BLOCK, block_ids.data()), "ex_get_ids (blocks)");
  for (int id : block_ids) {
    char type[MAX_STR_LENGTH + 1] = {};
    int count = 0, per_entry = 0, edges = 0, faces = 0, attributes = 0;
    check(ex_get_block(exoid_, EX_ELEM_BLOCK, id, type, &count, &per_entry, &edges, &faces, &attributes), "ex_get_block");
    if (id < 1 || (count > 0 && (per_entry != 1 || attributes != 1)))  // an empty block (of a piece) keeps neither
      throw std::runtime_error(fmt::format("Exodus file '{}': block {} is not a block of Peridot's points", path_, id));
    const auto b = static_cast<std::size_t>(id - 1);
    if (mesh.block_names.size() <= b) mesh.block_names.resize(b + 1);
    mesh.block_names[b] = read_name(exoid_, EX_ELEM_BLOCK, id);
    if (count == 0) continue;
    std::vector<int> conn(static_cast<std::size_t>(count));
    std::vector<double> radius(static_cast<std::size_t>(count));
    check(ex_get_conn(exoid_, EX_ELEM_BLOCK, id, conn.data(), nullptr, nullptr), "ex_get_conn");
    check(ex_get_attr(exoid_, EX_ELEM_BLOCK, id, radius.data()), "ex_get_attr");
    for (std::size_t e = 0; e < conn.size(); ++e) {
      const auto p = static_cast<std::size_t>(conn[e] - 1);
      if (conn[e] < 1 || p >= n || mesh.block[p] >= 0)
        throw std::runtime_error(fmt::format("Exodus file '{}': element of block {} on node {}", path_, id, conn[e]));
      mesh.block[p] = static_cast<std::int32_t>(b);
      mesh.radius[p] = radius[e];
    }
  }
  if (std::find(mesh.block.begin(), mesh.block.end(), -1) != mesh.block.end())
    throw std::runtime_error(fmt::format("Exodus file '{}': a node without its element", path_));
  std::vector<int> set_ids(static_cast<std::size_t>(params.num_node_sets));
  if (!set_ids.empty()) check(ex_get_ids(exoid_, EX_NODE_SET, set_ids.data()), "ex_get_ids (node sets)");
  for (int id : set_ids) {
    int count = 0, factors = 0;
    check(ex_get_set_param(exoid_, EX_NODE_SET, id, &count, &factors), "ex_get_set_param");
    std::vector<int> nodes(static_cast<std::size_t>(count));
    if (count > 0) check(ex_get_set(exoid_, EX_NODE_SET, id, nodes.data(), nullptr), "ex_get_set");
    NodeSetOutput set{read_name(exoid_, EX_NODE_SET, id), {}};
    for (int node : nodes) set.points.push_back(static_cast<std::uint32_t>(node - 1));
    mesh.node_sets.push_back(std::move(set));
  }
  return mesh;
}

bool is_piece_suffix(const std::string& suffix) {
  const auto dot = suffix.find('.');
  if (dot == std::string::npos || dot == 0 || dot > 9 || suffix.size() != 2 * dot + 1) return false;
  const std::string count = suffix.substr(0, dot), rank = suffix.substr(dot + 1);
  auto digits = [](const std::string& s) { return std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; }); };
  return digits(count) && digits(rank) && std::stoi(rank) < std::stoi(count);
}

std::vector<std::string> piece_paths(const std::string& path) {
  const fs::path whole(path);
  const fs::path dir = whole.has_parent_path() ? whole.parent_path() : fs::path(".");
  const std::string stem = whole.filename().string() + ".";
  std::map<int, std::map<int, std::string>> sets;  // N → rank → path
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem, 0) != 0) continue;
    const std::string rest = name.substr(stem.size());  // "N.r"
    if (!is_piece_suffix(rest)) continue;
    const auto dot = rest.find('.');
    const int N = std::stoi(rest.substr(0, dot)), r = std::stoi(rest.substr(dot + 1));
    sets[N][r] = (whole.has_parent_path() ? (dir / name) : fs::path(name)).string();
  }
  if (sets.empty()) return {};
  if (sets.size() > 1) {
    std::vector<std::string> counts;
    for (const auto& [N, pieces] : sets) counts.push_back(fmt::format("{}.{}.*", path, N));
    throw std::runtime_error(fmt::format("pieces of several runs lie beside each other: {}", fmt::join(counts, ", ")));
  }
  const auto& [N, pieces] = *sets.begin();
  std::vector<std::string> paths;
  for (int r = 0; r < N; ++r) {
    const auto it = pieces.find(r);
    if (it == pieces.end())
      throw std::runtime_error(fmt::format("{} is missing: {} pieces expected", ExodusWriter::piece_path(path, r, N), N));
    paths.push_back(it->second);
  }
  return paths;
}

std::vector<std::string> exodus_result_files(const std::string& path) {
  std::vector<std::string> files;
  if (fs::exists(path)) files.push_back(path);
  const fs::path whole(path);
  const fs::path dir = whole.has_parent_path() ? whole.parent_path() : fs::path(".");
  const std::string stem = whole.filename().string() + ".";
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(stem, 0) != 0) continue;
    if (is_piece_suffix(name.substr(stem.size()))) files.push_back((dir / name).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

int join_exodus(const std::string& path, const std::string& out) {
  const std::vector<std::string> paths = piece_paths(path);
  if (paths.empty()) throw std::runtime_error(fmt::format("no pieces {}.N.r to join", path));
  std::vector<ExodusInput> pieces;
  for (const std::string& p : paths) pieces.emplace_back(p);
  // The fields: those of any piece with points (a piece without points has none).
  const ExodusInput& first = *std::max_element(pieces.begin(), pieces.end(), [](const ExodusInput& a, const ExodusInput& b) {
    return a.num_points() < b.num_points();
  });
  const std::size_t N = first.global_points();
  for (const ExodusInput& piece : pieces)
    if (piece.ranks() != static_cast<int>(pieces.size()) || piece.global_points() != N ||
        (piece.num_points() > 0 && piece.variable_names() != first.variable_names()) || piece.dimension() != first.dimension())
      throw std::runtime_error(fmt::format("'{}' does not belong with '{}' (rank count, points or fields differ)",
                                           piece.path(), first.path()));

  // The whole mesh in the serial order.
  ExodusMesh whole;
  whole.dimension = first.dimension();
  for (int d = 0; d < whole.dimension; ++d) whole.coord[d].assign(N, 0.0);
  whole.node_id.assign(N, 0);
  whole.block.assign(N, -1);
  whole.radius.assign(N, 0.0);
  std::vector<std::vector<std::uint32_t>> index(pieces.size());
  std::vector<std::uint8_t> seen(N, 0);
  for (std::size_t r = 0; r < pieces.size(); ++r) {
    const ExodusMesh mesh = pieces[r].mesh();
    index[r] = pieces[r].point_index();
    if (r == 0) {
      whole.title = mesh.title;
      whole.block_names = mesh.block_names;
      for (const NodeSetOutput& set : mesh.node_sets) whole.node_sets.push_back({set.name, {}});
    }
    if (mesh.node_sets.size() != whole.node_sets.size())
      throw std::runtime_error(fmt::format("'{}' has other node sets than '{}'", pieces[r].path(), first.path()));
    for (std::size_t i = 0; i < index[r].size(); ++i) {
      const std::uint32_t g = index[r][i];
      if (seen[g]) throw std::runtime_error(fmt::format("point {} is in two pieces (the second: '{}')", g, pieces[r].path()));
      seen[g] = 1;
      for (int d = 0; d < whole.dimension; ++d) whole.coord[d][g] = mesh.coord[d][i];
      whole.node_id[g] = mesh.node_id[i];
      whole.block[g] = mesh.block[i];
      whole.radius[g] = mesh.radius[i];
    }
    for (std::size_t s = 0; s < mesh.node_sets.size(); ++s)
      for (std::uint32_t p : mesh.node_sets[s].points) whole.node_sets[s].points.push_back(index[r][p]);
  }
  if (std::find(seen.begin(), seen.end(), std::uint8_t{0}) != seen.end())
    throw std::runtime_error(fmt::format("the pieces of '{}' miss points of the whole problem", path));
  std::vector<std::uint8_t>().swap(seen);
  for (NodeSetOutput& set : whole.node_sets) std::sort(set.points.begin(), set.points.end());

  // The fields after those every file has are the optional ones, in the order written.
  const std::vector<std::string>& names = first.variable_names();
  std::size_t always = 0;
  for (const PointField& field : point_fields())
    if (field.scope == FieldScope::always) always += variable_names(field, whole.dimension).size();
  if (names.size() < always) throw std::runtime_error(fmt::format("'{}' lacks fields every Peridot file has", first.path()));
  const std::vector<std::string> extra(names.begin() + static_cast<std::ptrdiff_t>(always), names.end());

  const std::string joining = out + ".joining";
  int frames = 0;
  try {
    ExodusWriter writer(joining, whole, extra);
    if (writer.variable_names() != names)
      throw std::runtime_error(fmt::format("'{}' holds fields this Peridot does not write", first.path()));
    int steps = first.steps();
    for (const ExodusInput& piece : pieces) steps = std::min(steps, piece.steps());  // a stopped run's pieces
    std::vector<double> column(N), values;
    for (int step = 1; step <= steps; ++step) {
      const double time = first.time(step);
      for (const ExodusInput& piece : pieces)
        if (piece.time(step) != time)
          throw std::runtime_error(fmt::format("'{}' has another time at frame {} than '{}'", piece.path(), step, first.path()));
      writer.write_frame(time, [&](std::size_t variable) {
        for (std::size_t r = 0; r < pieces.size(); ++r) {
          if (pieces[r].num_points() == 0) continue;
          pieces[r].read_variable(step, variable, values);
          for (std::size_t i = 0; i < values.size(); ++i) column[index[r][i]] = values[i];
        }
        return column.data();
      });
    }
    writer.close();
    frames = writer.frames_written();
  } catch (...) {
    std::error_code ignored;
    fs::remove(joining, ignored);
    throw;
  }
  fs::rename(joining, out);
  return frames;
}

}  // namespace peridot
