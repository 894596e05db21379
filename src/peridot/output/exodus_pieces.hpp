#pragma once
// Reading Peridot's Exodus files back: one file, or the pieces of a distributed run (NAME.N.r, see
// exodus_writer.hpp), for a restart's continuation and for `peridot join`, which merges the pieces into the
// file a serial run writes, byte for byte.
#include <cstdint>
#include <string>
#include <vector>

#include "peridot/output/exodus_writer.hpp"

namespace peridot {

/// An Exodus file open for reading (closed by the destructor). Every failure throws std::runtime_error naming
/// the file and the library's message.
class ExodusInput {
 public:
  explicit ExodusInput(const std::string& path);
  ExodusInput(const ExodusInput&) = delete;
  ExodusInput& operator=(const ExodusInput&) = delete;
  ExodusInput(ExodusInput&& other) noexcept;
  ExodusInput& operator=(ExodusInput&&) = delete;
  ~ExodusInput();

  const std::string& path() const { return path_; }
  std::size_t num_points() const { return num_points_; }
  int dimension() const { return dimension_; }
  int steps() const;
  double time(int step) const;  ///< step is 1-based
  const std::vector<std::string>& variable_names() const { return variable_names_; }
  /// Variable `variable` (0-based) of time step `step` (1-based), num_points() values.
  void read_variable(int step, std::size_t variable, std::vector<double>& values) const;
  /// Each point's index in the whole problem: a piece's "point_index" map, else 0, 1, 2, … (a whole file).
  std::vector<std::uint32_t> point_index() const;
  /// Nemesis: the pieces of the set (1 for a whole file) and the whole problem's point count.
  int ranks() const { return ranks_; }
  std::uint64_t global_points() const { return global_points_; }
  /// The mesh as written (node sets by this file's points).
  ExodusMesh mesh() const;

 private:
  void check(int status, const char* what) const;
  std::string path_;
  int exoid_ = -1;
  std::size_t num_points_ = 0;
  int dimension_ = 3;
  int ranks_ = 1;
  std::uint64_t global_points_ = 0;
  std::vector<std::string> variable_names_;
};

/// Whether `suffix` is a piece's "N.r": digits, r of the width of N (zero-padded) and below N.
bool is_piece_suffix(const std::string& suffix);

/// The pieces of the distributed output `path` (path.N.0 … path.N.N−1: Exodus frames, checkpoints), in rank
/// order; empty when there are none. Throws std::runtime_error when pieces of several rank counts lie there, or one of the N is missing.
std::vector<std::string> piece_paths(const std::string& path);

/// Every piece set (any N) and the whole file of `path` that exist: what a new run's results replace.
std::vector<std::string> exodus_result_files(const std::string& path);

/// `peridot join`: merges the pieces of `path` into `out` (written as out.joining and renamed when complete),
/// the file a serial run of the same deck writes. Holds the whole mesh and one variable of one frame in
/// memory. Returns the number of frames. Throws std::runtime_error (unreadable or inconsistent pieces).
int join_exodus(const std::string& path, const std::string& out);

}  // namespace peridot
