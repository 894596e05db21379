#pragma once
// The checkpoint file: a netCDF file (CDF-5, readable with ncdump) holding named byte arrays and what a
// restart checks them against (solvers/checkpoint.hpp fills and reads it):
//  - attributes: the format version, the code version, the deck fingerprint (text), Δt, the step, the time,
//    the global point count and a 64-bit checksum (FNV-1a) over the fingerprint and every array's bytes;
//  - family_size: each point's bond count, in the global point order (a piece: in the piece's order);
//  - a distributed run's checkpoint is one file per rank, NAME.N.r (the Exodus pieces' convention,
//    output/exodus_writer.hpp), each with its owned points only: attributes pieces (N) and global_points, and a
//    variable point_index, each point's index in the whole problem; piece 0 also holds piece_boxes, every
//    piece's box of its points' reference positions, so that a restart reads only the pieces near its points;
//  - one NC_UBYTE variable per state array, with its layout ("point", "bond", "global") and its width in
//    bytes (per point or bond; in all for a global one) as attributes.
// It is written to NAME.tmp, flushed to disk (fsync), then renamed over NAME and the folder synced, so that a
// checkpoint is either absent, the previous one, or whole.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace peridot {

struct CheckpointArray {
  std::string name;
  std::string layout;  ///< "point", "bond" or "global"
  std::uint64_t width = 0;  ///< bytes per point or bond (global: bytes in all)
  std::vector<unsigned char> bytes;  ///< global point order; bonds family after family
};

struct CheckpointData {
  std::string code_version;
  std::string deck;  ///< the fingerprint of the deck it was written by (solvers/checkpoint.hpp)
  double time_step = 0;
  std::int64_t step = 0;
  double time = 0;
  std::vector<std::uint32_t> family_size;  ///< bonds of each point, global order (a piece: the piece's order)
  std::vector<CheckpointArray> arrays;
  /// A piece (one rank's file of a distributed run): its points' global indices, and how many pieces the
  /// checkpoint is. A whole checkpoint: point_index empty, pieces 1.
  std::vector<std::uint32_t> point_index;
  int pieces = 1;
  std::uint64_t global_points = 0;  ///< points of the whole problem (a whole file: family_size.size())
  /// Piece 0 of a distributed checkpoint: each piece's box of its points' reference positions (lo x, y, z,
  /// hi x, y, z; an empty piece's lo above its hi), piece after piece. Otherwise empty.
  std::vector<double> piece_boxes;
};

/// A checkpoint that cannot be read or fails its checksum; what() says which file and why.
class CheckpointFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// FNV-1a over the fingerprint, the family sizes, a piece's point indices, the piece boxes and every array
/// (name, layout, width and bytes).
std::uint64_t checkpoint_checksum(const CheckpointData& data);

/// Writes data to path atomically (path.tmp, fsync, rename). Throws std::runtime_error naming the path and
/// the reason (disk full, permission).
void write_checkpoint_file(const std::string& path, const CheckpointData& data);

/// Reads path and verifies its checksum. Throws CheckpointFileError for a file that is missing, not a
/// checkpoint, truncated or corrupt. `header_only`: the attributes and piece_boxes alone (no arrays, no
/// checksum: a restart checks them before it reads the pieces it needs).
CheckpointData read_checkpoint_file(const std::string& path, bool header_only = false);

}  // namespace peridot
