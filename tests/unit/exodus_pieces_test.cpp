// Exodus pieces of distributed runs (NAME.N.r): written by ExodusWriter with an ExodusPiece, merged by
// join_exodus into the file a serial run writes, byte for byte, and carried over by copy_frames between any
// rank counts (a restart).
#include "peridot/output/exodus_pieces.hpp"
#include "peridot/output/exodus_writer.hpp"

#include <gtest/gtest.h>

#include "support/scratch_dir.hpp"
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using peridot::Discretization;
using peridot::ExodusInput;
using peridot::ExodusPiece;
using peridot::ExodusWriter;
using peridot::NodeSetOutput;
using peridot::State;
using peridot::testing::scratch_dir;

namespace {


std::string bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// 3×3×3 lattice; block 1 for the first column of each row, block 0 elsewhere; input ids reversed.
Discretization lattice() {
  Discretization disc;
  disc.dimension = 3;
  const double h = 0.1;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int l = 0; l < 3; ++l) {
        const std::size_t i = disc.volume.size();
        disc.x.resize(i + 1);
        disc.x(i, 0) = l * h;
        disc.x(i, 1) = j * h;
        disc.x(i, 2) = k * h;
        disc.volume.push_back(h * h * h * (1 + 0.01 * static_cast<double>(i)));
        disc.block.push_back(l == 0 ? 1 : 0);
      }
  for (std::size_t i = 0; i < disc.volume.size(); ++i) disc.input_id.push_back(static_cast<std::uint32_t>(26 - i));
  disc.block_names = {"plate", "column"};
  return disc;
}

/// The points of `whole` listed in `points`, in that order (a rank's owned points).
Discretization subset(const Discretization& whole, const std::vector<std::uint32_t>& points) {
  Discretization part;
  part.dimension = whole.dimension;
  part.block_names = whole.block_names;
  part.x.resize(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    for (int d = 0; d < 3; ++d) part.x(k, d) = whole.x(points[k], d);
    part.volume.push_back(whole.volume[points[k]]);
    part.block.push_back(whole.block[points[k]]);
    part.input_id.push_back(whole.input_id[points[k]]);
  }
  return part;
}

/// Frame f's state of the points listed (global indices), and `ghosts` more entries of garbage after them.
State state_of(const std::vector<std::uint32_t>& points, int f, std::size_t ghosts = 0) {
  State s;
  s.resize(points.size() + ghosts);
  for (std::size_t k = 0; k < points.size() + ghosts; ++k) {
    const double i = k < points.size() ? points[k] : 1e9;
    for (int d = 0; d < 3; ++d) {
      s.u(k, d) = 0.001 * i + d + 10.0 * f;
      s.v(k, d) = -0.5 * i + 0.25 * d + f;
      s.force(k, d) = 1e6 * (i + 1) * (d + 1) + f;
    }
    s.damage[k] = 0.01 * i * f;
    s.dilatation[k] = 0.001 * i - f;
    s.weighted_volume[k] = 1e-9 * (i + 1);
  }
  return s;
}

std::vector<std::uint32_t> all_points() {
  std::vector<std::uint32_t> all(27);
  for (std::uint32_t i = 0; i < 27; ++i) all[i] = i;
  return all;
}

const std::vector<NodeSetOutput> kSets = {{"bottom", {0, 1, 2, 3, 4, 5, 6, 7, 8}}, {"none", {}}, {"corner", {26}}};
constexpr double kTimes[] = {0.0, 0.5, 1.25};

void write_serial(const fs::path& path, int frames = 3) {
  const Discretization disc = lattice();
  ExodusWriter writer(path.string(), disc, kSets, "peridot: pieces test");
  for (int f = 0; f < frames; ++f) writer.write_frame(kTimes[f], state_of(all_points(), f));
}

/// The pieces of `owners` (the points of each rank, in the rank's order) for `path`, each with a writer
/// made as Run makes one; returns the writers, open, with no frame.
std::vector<ExodusWriter> piece_writers(const fs::path& path, const std::vector<std::vector<std::uint32_t>>& owners) {
  const Discretization whole = lattice();
  std::vector<ExodusWriter> writers;
  const int ranks = static_cast<int>(owners.size());
  for (int r = 0; r < ranks; ++r) {
    const std::vector<std::uint32_t>& mine = owners[static_cast<std::size_t>(r)];
    ExodusPiece piece;
    piece.rank = r;
    piece.ranks = ranks;
    piece.point_index = mine;
    piece.global_points = 27;
    piece.blocks = {0, 1};
    piece.block_sizes = {18, 9};
    std::vector<NodeSetOutput> sets;
    for (const NodeSetOutput& set : kSets) {
      NodeSetOutput local{set.name, {}};
      for (std::size_t k = 0; k < mine.size(); ++k)
        if (std::find(set.points.begin(), set.points.end(), mine[k]) != set.points.end())
          local.points.push_back(static_cast<std::uint32_t>(k));
      sets.push_back(local);
      piece.node_set_sizes.push_back(set.points.size());
    }
    // The rank's discretization holds two ghosts after its owned points.
    std::vector<std::uint32_t> with_ghosts = mine;
    with_ghosts.push_back(0);
    with_ghosts.push_back(26);
    writers.emplace_back(ExodusWriter::piece_path(path.string(), r, ranks), subset(whole, with_ghosts), sets,
                         "peridot: pieces test", 1.0, std::vector<std::string>{}, &piece);
  }
  return writers;
}

/// Four ranks: two share block 0 (scrambled order), one holds block 1, one holds nothing.
std::vector<std::vector<std::uint32_t>> four_owners() {
  std::vector<std::vector<std::uint32_t>> owners(4);
  const Discretization whole = lattice();
  for (std::uint32_t i = 27; i-- > 0;) owners[whole.block[i] == 1 ? 2 : i % 2].push_back(i);
  return owners;
}

}  // namespace

TEST(ExodusPieces, PiecePathsFollowTheNemesisConvention) {
  EXPECT_EQ(ExodusWriter::piece_path("out/a.e", 0, 4), "out/a.e.4.0");
  EXPECT_EQ(ExodusWriter::piece_path("a.e", 3, 16), "a.e.16.03");
  EXPECT_EQ(ExodusWriter::piece_path("a.e", 999, 1000), "a.e.1000.0999");
  EXPECT_TRUE(peridot::is_piece_suffix("16.03"));
  EXPECT_FALSE(peridot::is_piece_suffix("16.3"));
  EXPECT_FALSE(peridot::is_piece_suffix("4.4"));
  EXPECT_FALSE(peridot::is_piece_suffix("4.0.partial"));
}

TEST(ExodusPieces, JoinedPiecesAreTheSerialFileByteForByte) {
  const fs::path dir = scratch_dir();
  write_serial(dir / "serial.e");
  const auto owners = four_owners();
  {
    std::vector<ExodusWriter> writers = piece_writers(dir / "out.e", owners);
    for (int f = 0; f < 3; ++f)
      for (std::size_t r = 0; r < writers.size(); ++r) writers[r].write_frame(kTimes[f], state_of(owners[r], f, 2));
  }
  const ExodusInput piece((dir / "out.e.4.2").string());
  EXPECT_EQ(piece.ranks(), 4);
  EXPECT_EQ(piece.global_points(), 27u);
  EXPECT_EQ(piece.num_points(), 9u);
  EXPECT_EQ(piece.point_index(), owners[2]);
  EXPECT_EQ(ExodusInput((dir / "out.e.4.3").string()).num_points(), 0u);  // the rank without points
  EXPECT_EQ(peridot::piece_paths((dir / "out.e").string()).size(), 4u);
  EXPECT_EQ(peridot::join_exodus((dir / "out.e").string(), (dir / "out.e").string()), 3);
  EXPECT_EQ(bytes(dir / "out.e"), bytes(dir / "serial.e"));
  fs::remove_all(dir);
}

TEST(ExodusPieces, FramesCarryOverBetweenAnyRankCounts) {
  const fs::path dir = scratch_dir();
  write_serial(dir / "serial.e");
  write_serial(dir / "first_two.e", 2);
  // Serial → 2 pieces: frames 1 and 2 carried over, the third written; joined, the serial file.
  const std::vector<std::vector<std::uint32_t>> two = {{26, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25},
                                                       {0, 1, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24}};
  {
    std::vector<ExodusWriter> writers = piece_writers(dir / "two.e", two);
    for (std::size_t r = 0; r < 2; ++r) {
      EXPECT_EQ(writers[r].copy_frames({(dir / "first_two.e").string()}, 0.25, 5, 1), 2);
      writers[r].write_frame(kTimes[2], state_of(two[r], 2));
    }
  }
  EXPECT_EQ(peridot::join_exodus((dir / "two.e").string(), (dir / "two_joined.e").string()), 3);
  EXPECT_EQ(bytes(dir / "two_joined.e"), bytes(dir / "serial.e"));
  // 2 pieces → 4 pieces, every frame; up to step 2 only (times 0, 0.5): two frames.
  const auto four = four_owners();
  {
    std::vector<ExodusWriter> writers = piece_writers(dir / "four.e", four);
    std::vector<std::string> earlier = peridot::piece_paths((dir / "two.e").string());
    for (ExodusWriter& writer : writers) EXPECT_EQ(writer.copy_frames(earlier, 0.25, 5, 1), 3);
  }
  peridot::join_exodus((dir / "four.e").string(), (dir / "four_joined.e").string());
  EXPECT_EQ(bytes(dir / "four_joined.e"), bytes(dir / "serial.e"));
  {
    std::vector<ExodusWriter> writers = piece_writers(dir / "early.e", four);
    for (ExodusWriter& writer : writers)
      EXPECT_EQ(writer.copy_frames(peridot::piece_paths((dir / "two.e").string()), 0.25, 2, 1), 2);
  }
  // 4 pieces → one serial file.
  {
    ExodusWriter writer((dir / "back.e").string(), lattice(), kSets, "peridot: pieces test");
    EXPECT_EQ(writer.copy_frames(peridot::piece_paths((dir / "four.e").string()), 0.25, 5, 1), 3);
  }
  EXPECT_EQ(bytes(dir / "back.e"), bytes(dir / "serial.e"));
  // Other points: refused.
  {
    std::vector<ExodusWriter> writers = piece_writers(dir / "bad.e", two);
    write_serial(dir / "ok.e");
    EXPECT_NO_THROW(writers[0].copy_frames({(dir / "ok.e").string()}, 0.25, 5, 1));
    EXPECT_THROW(writers[1].copy_frames({(dir / "four.e.4.0").string()}, 0.25, 5, 1), std::runtime_error);  // a part only
  }
  fs::remove_all(dir);
}

TEST(ExodusPieces, IncompleteOrMixedPieceSetsAreRefused) {
  const fs::path dir = scratch_dir();
  EXPECT_TRUE(peridot::piece_paths((dir / "none.e").string()).empty());
  EXPECT_THROW(peridot::join_exodus((dir / "none.e").string(), (dir / "none.e").string()), std::runtime_error);
  { std::vector<ExodusWriter> writers = piece_writers(dir / "out.e", four_owners()); }
  fs::remove(dir / "out.e.4.1");
  try {
    peridot::join_exodus((dir / "out.e").string(), (dir / "out.e").string());
    FAIL() << "a missing piece was not noticed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("out.e.4.1 is missing"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "out.e"));
  fs::remove_all(dir);
  fs::create_directories(dir);
  { std::vector<ExodusWriter> writers = piece_writers(dir / "out.e", four_owners()); }
  write_serial(dir / "x.e");
  fs::copy_file(dir / "x.e", dir / "out.e.1.0");  // an earlier serial run's name… as a 1-piece set
  EXPECT_THROW(peridot::piece_paths((dir / "out.e").string()), std::runtime_error);
  EXPECT_EQ(peridot::exodus_result_files((dir / "out.e").string()).size(), 5u);
  fs::remove_all(dir);
}
