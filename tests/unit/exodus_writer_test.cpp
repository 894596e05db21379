// ExodusWriter: write small point clouds, read them back through the Exodus C API, compare exactly.
// Set PERIDOT_EXODUS_FIXTURE=/some/file.e to keep the 3D file of ExodusWriter.RoundTrip3D; the regression
// script tests/regression/test_exodus_readback.py --file /some/file.e --fixture then checks it from Python.
#include "peridot/output/csv_writer.hpp"
#include "peridot/output/exodus_writer.hpp"

#include <gtest/gtest.h>

#include "support/scratch_dir.hpp"
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <exodusII.h>

namespace fs = std::filesystem;
using peridot::CsvWriter;
using peridot::Discretization;
using peridot::ExodusWriter;
using peridot::NodeSetOutput;
using peridot::State;
using peridot::testing::scratch_dir;

namespace {


/// n×n×n (or n×n) lattice of spacing h; block 1 for x < middle, block 0 otherwise, so that blocks interleave
/// in point order; input_id reversed so that the node map is not the identity.
Discretization lattice(int dimension, int n, double h) {
  Discretization disc;
  disc.dimension = dimension;
  const int nz = dimension == 3 ? n : 1;
  const std::size_t count = static_cast<std::size_t>(n) * n * nz;
  disc.x.resize(count);
  std::size_t i = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n; ++j)
      for (int l = 0; l < n; ++l, ++i) {
        disc.x(i, 0) = l * h;
        disc.x(i, 1) = j * h;
        disc.x(i, 2) = dimension == 3 ? k * h : 0.0;
        disc.volume.push_back(dimension == 3 ? h * h * h : h * h * 0.01);  // 2D: thickness 0.01
        disc.block.push_back(l < n / 2 ? 1 : 0);
        disc.input_id.push_back(static_cast<std::uint32_t>(count - 1 - i));
      }
  disc.block_names = {"right", "left"};
  return disc;
}

// The field values of point i, component d, frame f; test_exodus_readback.py --fixture computes the same
// expressions in the same order, so both compare exactly.
double u_of(std::size_t i, int d, int f) { return 0.001 * i + d + 10.0 * f; }
double v_of(std::size_t i, int d, int f) { return -0.5 * i + 0.25 * d + f; }
double force_of(std::size_t i, int d, int f) { return 1.0e6 * (i + 1) * (d + 1) + f; }
double damage_of(std::size_t i, int f) { return (i % 4) / 4.0 * (f / 2.0); }
double dilatation_of(std::size_t i, int f) { return 0.001 * i - f; }
double weighted_volume_of(std::size_t i, int f) { return 1.0e-9 * (i + 1) + 1.0e-12 * f; }

State make_state(std::size_t n, int f) {
  State s;
  s.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      s.u(i, d) = u_of(i, d, f);
      s.v(i, d) = v_of(i, d, f);
      s.force(i, d) = force_of(i, d, f);
    }
    s.damage[i] = damage_of(i, f);
    s.dilatation[i] = dilatation_of(i, f);
    s.weighted_volume[i] = weighted_volume_of(i, f);
  }
  return s;
}

/// Read-only Exodus handle that closes itself.
class Reader {
 public:
  explicit Reader(const fs::path& path) {
    int comp_ws = sizeof(double), io_ws = 0;
    float version = 0;
    id = ex_open(path.c_str(), EX_READ, &comp_ws, &io_ws, &version);
  }
  ~Reader() {
    if (id >= 0) ex_close(id);
  }
  std::vector<std::string> names(ex_entity_type type, std::size_t count) const {
    std::vector<std::vector<char>> storage(count, std::vector<char>(MAX_STR_LENGTH + 1, '\0'));
    std::vector<char*> ptrs;
    for (auto& s : storage) ptrs.push_back(s.data());
    EXPECT_GE(ex_get_names(id, type, ptrs.data()), 0);
    return {ptrs.begin(), ptrs.end()};
  }
  std::vector<std::string> variable_names() const {
    int count = 0;
    EXPECT_GE(ex_get_variable_param(id, EX_NODAL, &count), 0);
    std::vector<std::vector<char>> storage(count, std::vector<char>(MAX_STR_LENGTH + 1, '\0'));
    std::vector<char*> ptrs;
    for (auto& s : storage) ptrs.push_back(s.data());
    EXPECT_GE(ex_get_variable_names(id, EX_NODAL, count, ptrs.data()), 0);
    return {ptrs.begin(), ptrs.end()};
  }
  std::vector<double> nodal(int step, int var, std::size_t n) const {
    std::vector<double> values(n, -1.0);
    EXPECT_GE(ex_get_var(id, step, EX_NODAL, var, 1, static_cast<int64_t>(n), values.data()), 0);
    return values;
  }
  int id = -1;
};

std::vector<std::string> expected_names(int dimension) {
  std::vector<std::string> names;
  for (std::string f : {"displacement", "velocity", "force_density"})
    for (int d = 0; d < dimension; ++d) names.push_back(f + "_" + "xyz"[d]);
  for (std::string s : {"damage", "dilatation", "weighted_volume", "volume"}) names.push_back(s);
  return names;
}

/// Checks mesh, blocks, maps, node sets, variable names, times and every value of a file written by
/// write_fixture().
void check_file(const fs::path& path, const Discretization& disc, const std::vector<NodeSetOutput>& sets,
                const std::vector<double>& times, const std::vector<std::uint32_t>& element_points,
                double thickness) {
  const std::size_t n = disc.num_points();
  const int dim = disc.dimension;
  Reader r(path);
  ASSERT_GE(r.id, 0) << path;

  char title[MAX_LINE_LENGTH + 1] = {};
  int num_dim = 0, num_nodes = 0, num_elem = 0, num_blk = 0, num_nsets = 0, num_ssets = 0;
  ASSERT_GE(ex_get_init(r.id, title, &num_dim, &num_nodes, &num_elem, &num_blk, &num_nsets, &num_ssets), 0);
  EXPECT_STREQ(title, "peridot exodus writer test");
  EXPECT_EQ(num_dim, dim);
  EXPECT_EQ(num_nodes, static_cast<int>(n));
  EXPECT_EQ(num_elem, static_cast<int>(n));
  EXPECT_EQ(num_nsets, static_cast<int>(sets.size()));
  EXPECT_EQ(num_ssets, 0);

  // Coordinates, exactly.
  std::vector<double> c[3] = {std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)};
  ASSERT_GE(ex_get_coord(r.id, c[0].data(), c[1].data(), dim == 3 ? c[2].data() : nullptr), 0);
  for (std::size_t i = 0; i < n; ++i)
    for (int d = 0; d < dim; ++d) EXPECT_EQ(c[d][i], disc.x(i, d)) << "point " << i << " axis " << d;

  // Node ids: input_id + 1.
  std::vector<int> node_map(n);
  ASSERT_GE(ex_get_id_map(r.id, EX_NODE_MAP, node_map.data()), 0);
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(node_map[i], static_cast<int>(disc.input_id[i]) + 1);

  // Blocks: ids = block index + 1, ascending; elements grouped by block, ascending point index within.
  std::vector<int> block_ids(num_blk);
  ASSERT_GE(ex_get_ids(r.id, EX_ELEM_BLOCK, block_ids.data()), 0);
  std::vector<std::int32_t> distinct(disc.block.begin(), disc.block.end());
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  ASSERT_EQ(block_ids.size(), distinct.size());
  const auto block_names = r.names(EX_ELEM_BLOCK, block_ids.size());
  std::vector<std::uint32_t> order;  // element order as read back from the connectivity
  for (std::size_t b = 0; b < distinct.size(); ++b) {
    EXPECT_EQ(block_ids[b], distinct[b] + 1);
    EXPECT_EQ(block_names[b], disc.block_names[distinct[b]]);
    char type[MAX_STR_LENGTH + 1] = {};
    int count = 0, nodes_per = 0, edges = 0, faces = 0, attrs = 0;
    ASSERT_GE(ex_get_block(r.id, EX_ELEM_BLOCK, block_ids[b], type, &count, &nodes_per, &edges, &faces, &attrs),
              0);
    EXPECT_STREQ(type, "SPHERE");
    EXPECT_EQ(nodes_per, 1);
    EXPECT_EQ(attrs, 1);
    EXPECT_EQ(count, std::count(disc.block.begin(), disc.block.end(), distinct[b]));
    std::vector<int> conn(count);
    std::vector<double> radius(count);
    ASSERT_GE(ex_get_conn(r.id, EX_ELEM_BLOCK, block_ids[b], conn.data(), nullptr, nullptr), 0);
    ASSERT_GE(ex_get_attr(r.id, EX_ELEM_BLOCK, block_ids[b], radius.data()), 0);
    char attr_name[MAX_STR_LENGTH + 1] = {};
    char* attr_names[] = {attr_name};
    ASSERT_GE(ex_get_attr_names(r.id, EX_ELEM_BLOCK, block_ids[b], attr_names), 0);
    EXPECT_STREQ(attr_name, "radius");
    for (int e = 0; e < count; ++e) {
      const std::uint32_t p = static_cast<std::uint32_t>(conn[e] - 1);
      EXPECT_EQ(disc.block[p], distinct[b]);
      if (!order.empty() && disc.block[order.back()] == distinct[b]) {
        EXPECT_GT(p, order.back());
      }
      EXPECT_EQ(radius[e], ExodusWriter::equivalent_radius(disc.volume[p], dim, thickness));
      order.push_back(p);
    }
  }
  EXPECT_EQ(order, element_points);
  std::vector<int> elem_map(n);
  ASSERT_GE(ex_get_id_map(r.id, EX_ELEM_MAP, elem_map.data()), 0);
  for (std::size_t e = 0; e < n; ++e) EXPECT_EQ(elem_map[e], node_map[element_points[e]]);

  // Node sets: ids 1…, names, members (1-based on disk).
  if (!sets.empty()) {
    const auto set_names = r.names(EX_NODE_SET, sets.size());
    for (std::size_t s = 0; s < sets.size(); ++s) {
      EXPECT_EQ(set_names[s], sets[s].name);
      int count = -1, df = -1;
      ASSERT_GE(ex_get_set_param(r.id, EX_NODE_SET, static_cast<ex_entity_id>(s + 1), &count, &df), 0);
      EXPECT_EQ(count, static_cast<int>(sets[s].points.size()));
      EXPECT_EQ(df, 0);
      if (count > 0) {
        std::vector<int> members(count);
        ASSERT_GE(ex_get_set(r.id, EX_NODE_SET, static_cast<ex_entity_id>(s + 1), members.data(), nullptr), 0);
        for (int k = 0; k < count; ++k) EXPECT_EQ(members[k], static_cast<int>(sets[s].points[k]) + 1);
      }
    }
  }

  // Variables and times.
  EXPECT_EQ(r.variable_names(), expected_names(dim));
  ASSERT_EQ(ex_inquire_int(r.id, EX_INQ_TIME), static_cast<int64_t>(times.size()));
  std::vector<double> read_times(times.size());
  if (!times.empty()) {
    ASSERT_GE(ex_get_all_times(r.id, read_times.data()), 0);
  }
  EXPECT_EQ(read_times, times);

  for (int f = 0; f < static_cast<int>(times.size()); ++f) {
    const int step = f + 1;
    int var = 1;
    for (auto fn : {u_of, v_of, force_of}) {
      for (int d = 0; d < dim; ++d, ++var) {
        const auto values = r.nodal(step, var, n);
        for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(values[i], fn(i, d, f)) << "var " << var << " point " << i;
      }
    }
    for (auto fn : {damage_of, dilatation_of, weighted_volume_of}) {
      const auto values = r.nodal(step, var++, n);
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(values[i], fn(i, f)) << "var " << var - 1 << " point " << i;
    }
    EXPECT_EQ(r.nodal(step, var, n), disc.volume);
  }
}

constexpr double kTimes[] = {0.0, 0.5, 1.25};

}  // namespace

TEST(ExodusWriter, RoundTrip3D) {
  const fs::path dir = scratch_dir();
  const char* keep = std::getenv("PERIDOT_EXODUS_FIXTURE");
  const fs::path path = keep && *keep ? fs::path(keep) : dir / "lattice3d.e";
  const Discretization disc = lattice(3, 2, 0.1);
  const std::vector<NodeSetOutput> sets = {{"bottom", {0, 1, 2, 3}}, {"corner", {7}}};
  std::vector<std::uint32_t> element_points;
  {
    ExodusWriter writer(path.string(), disc, sets, "peridot exodus writer test");
    EXPECT_EQ(writer.frames_written(), 0);
    element_points = writer.element_points();
    // Block 0 ("right", x = h) holds the odd points, block 1 ("left", x = 0) the even ones.
    EXPECT_EQ(element_points, (std::vector<std::uint32_t>{1, 3, 5, 7, 0, 2, 4, 6}));
    for (int f = 0; f < 3; ++f) {
      writer.write_frame(kTimes[f], make_state(disc.num_points(), f));
      EXPECT_EQ(writer.frames_written(), f + 1);
      // Readable, with exactly the frames written so far, while the writer still has it open.
      Reader r(path);
      ASSERT_GE(r.id, 0);
      EXPECT_EQ(ex_inquire_int(r.id, EX_INQ_TIME), f + 1);
    }
    writer.close();
  }
  check_file(path, disc, sets, {kTimes, kTimes + 3}, element_points, 1.0);
  fs::remove_all(dir);
}

TEST(ExodusWriter, RoundTrip2D) {
  const fs::path dir = scratch_dir();
  const fs::path path = dir / "lattice2d.e";
  const Discretization disc = lattice(2, 3, 0.5);
  const std::vector<NodeSetOutput> sets = {{"empty_set", {}}, {"left_edge", {0, 3, 6}}};
  std::vector<std::uint32_t> element_points;
  {
    ExodusWriter writer(path.string(), disc, sets, "peridot exodus writer test", 0.01);
    EXPECT_EQ(writer.variable_names(), expected_names(2));
    element_points = writer.element_points();
    for (int f = 0; f < 3; ++f) writer.write_frame(kTimes[f], make_state(disc.num_points(), f));
  }  // the destructor closes
  check_file(path, disc, sets, {kTimes, kTimes + 3}, element_points, 0.01);
  // 2D radius: the disc of area V / thickness = h².
  EXPECT_DOUBLE_EQ(ExodusWriter::equivalent_radius(0.5 * 0.5 * 0.01, 2, 0.01), 0.5 / std::sqrt(M_PI));
  EXPECT_DOUBLE_EQ(ExodusWriter::equivalent_radius(4.0 / 3.0 * M_PI, 3, 1.0), 1.0);
  fs::remove_all(dir);
}

TEST(ExodusWriter, MeshOnlyFileHasNoTimeSteps) {
  const fs::path dir = scratch_dir();
  const Discretization disc = lattice(3, 2, 0.1);
  ExodusWriter writer((dir / "mesh.e").string(), disc, {}, "peridot exodus writer test");
  Reader r(dir / "mesh.e");
  ASSERT_GE(r.id, 0);
  EXPECT_EQ(ex_inquire_int(r.id, EX_INQ_TIME), 0);
  EXPECT_EQ(ex_inquire_int(r.id, EX_INQ_NODE_SETS), 0);
  fs::remove_all(dir);
}

TEST(ExodusWriter, CloseTwiceIsFineAndWritingAfterCloseThrows) {
  const fs::path dir = scratch_dir();
  const Discretization disc = lattice(3, 2, 0.1);
  ExodusWriter writer((dir / "close.e").string(), disc, {}, "t");
  writer.write_frame(0.0, make_state(disc.num_points(), 0));
  writer.close();
  EXPECT_NO_THROW(writer.close());
  EXPECT_THROW(writer.write_frame(1.0, make_state(disc.num_points(), 1)), std::logic_error);
  EXPECT_EQ(writer.frames_written(), 1);
  fs::remove_all(dir);
}

TEST(ExodusWriter, BadPathThrowsWithPath) {
  const Discretization disc = lattice(3, 2, 0.1);
  const std::string path = "/nonexistent_peridot_dir/sub/out.e";
  try {
    ExodusWriter writer(path, disc, {}, "t");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(ExodusWriter, BadInputThrows) {
  const fs::path dir = scratch_dir();
  const Discretization disc = lattice(3, 2, 0.1);
  EXPECT_THROW(ExodusWriter((dir / "a.e").string(), disc, {{"bad", {8}}}, "t"), std::logic_error);
  ExodusWriter writer((dir / "b.e").string(), disc, {}, "t");
  EXPECT_THROW(writer.write_frame(0.0, make_state(3, 0)), std::logic_error);
  EXPECT_EQ(writer.frames_written(), 0);
  fs::remove_all(dir);
}

// A process that dies in the middle of a frame leaves the frames before it readable and nothing of the
// unfinished one. The child writes two frames, then lowers its file-size limit so that the kernel kills it
// (SIGXFSZ) while netCDF writes out the third frame, with nothing closed or flushed.
TEST(ExodusWriter, DeathMidFrameLeavesCompleteFrames) {
  const fs::path dir = scratch_dir();
  const fs::path path = dir / "killed.e";
  // 4096 points, 32 KiB per variable and frame: far more than netCDF's buffer, so part of the unfinished
  // frame reaches the file before the process dies.
  const Discretization disc = lattice(3, 16, 0.1);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      ExodusWriter writer(path.string(), disc, {}, "peridot exodus writer test");
      writer.write_frame(kTimes[0], make_state(disc.num_points(), 0));
      writer.write_frame(kTimes[1], make_state(disc.num_points(), 1));
      const State third = make_state(disc.num_points(), 2);
      const rlim_t limit = fs::file_size(path) + 100000;  // a quarter of a frame
      const rlimit rl{limit, limit};
      const rlimit no_core{0, 0};  // SIGXFSZ dumps core by default
      if (::setrlimit(RLIMIT_CORE, &no_core) != 0 || ::setrlimit(RLIMIT_FSIZE, &rl) != 0) ::_exit(2);
      writer.write_frame(kTimes[2], third);
    } catch (...) {
      ::_exit(0);  // netCDF reported the short write instead: equally a death mid-frame (no ex_close)
    }
    ::_exit(1);  // the third frame went through: the limit did not bite
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE((WIFSIGNALED(status) && WTERMSIG(status) == SIGXFSZ) || (WIFEXITED(status) && WEXITSTATUS(status) == 0))
      << "child status " << status;
  // The same two frames written and closed normally: the killed file is longer, so values of the third
  // frame did reach it, and yet a reader sees exactly two frames with their values.
  ExodusWriter complete((dir / "complete.e").string(), disc, {}, "peridot exodus writer test");
  complete.write_frame(kTimes[0], make_state(disc.num_points(), 0));
  complete.write_frame(kTimes[1], make_state(disc.num_points(), 1));
  complete.close();
  EXPECT_GT(fs::file_size(path), fs::file_size(dir / "complete.e"));
  check_file(path, disc, {}, {kTimes, kTimes + 2}, complete.element_points(), 1.0);
  fs::remove_all(dir);
}

TEST(CsvWriter, HeaderAndFullPrecisionRows) {
  const fs::path dir = scratch_dir();
  const fs::path path = dir / "history.csv";
  {
    CsvWriter csv(path.string(), {"time", "force, total", "energy"});
    csv.write_row({0.0, 0.1, -1.0 / 3.0});
    // Every row is on disk as soon as write_row returns.
    std::ifstream partial(path);
    std::stringstream so_far;
    so_far << partial.rdbuf();
    EXPECT_EQ(so_far.str(), "time,\"force, total\",energy\n0,0.10000000000000001,-0.33333333333333331\n");
    csv.write_row({1e300, 2.5, 1e-300});
    EXPECT_THROW(csv.write_row({1.0}), std::logic_error);
    csv.close();
    EXPECT_NO_THROW(csv.close());
  }
  std::ifstream in(path);
  std::string header, row1, row2, extra;
  std::getline(in, header);
  std::getline(in, row1);
  std::getline(in, row2);
  EXPECT_FALSE(std::getline(in, extra));
  EXPECT_EQ(row2, "1.0000000000000001e+300,2.5,1e-300");
  EXPECT_EQ(std::stod("-0.33333333333333331"), -1.0 / 3.0);
  EXPECT_THROW(CsvWriter((dir / "no/such/dir.csv").string(), {"a"}), std::runtime_error);
  fs::remove_all(dir);
}
