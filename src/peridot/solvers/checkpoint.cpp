#include "peridot/solvers/checkpoint.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <sstream>

#include <fmt/format.h>

#include "peridot/core/bounding_box.hpp"
#include "peridot/deck/deck.hpp"
#include "peridot/output/exodus_pieces.hpp"
#include "peridot/version.hpp"

namespace peridot {

namespace {

const char* layout_name(ArrayLayout layout) {
  return layout == ArrayLayout::point ? "point" : layout == ArrayLayout::bond ? "bond" : "global";
}

/// Throws on every rank the first failing rank's message about the checkpoint at path (none: no failure).
void agree(const Communicator& comm, const std::string& path, const std::string& failure) {
  const int failing = comm.first_rank_with(!failure.empty());
  if (failing < 0) return;
  throw InputError(SourcePos{path, 0, 0}, "restart: " + comm.broadcast(failure, failing));
}

/// The first line where a and b differ, for the message.
std::string first_difference(const std::string& written, const std::string& now) {
  std::istringstream a(written), b(now);
  std::string x, y;
  for (int line = 1;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(a, x)), more_b = static_cast<bool>(std::getline(b, y));
    if (!more_a && !more_b) return "";
    if (!more_a) x = "(end)";
    if (!more_b) y = "(end)";
    if (x != y)
      return fmt::format("line {} of the resolved deck (peridot check prints it; the end and output settings aside) "
                         "was '{}' and is now '{}'", line, x, y);
  }
}

/// The box of the first n points' reference positions: lo x, y, z, hi x, y, z (no point: lo above hi).
std::vector<double> reference_box(const Discretization& disc, std::size_t n) { return bounding_box(disc.x.data(), 3, n).six(); }

std::uint32_t global_of(const Simulation& sim, std::size_t i) {
  return sim.communicator().serial() ? static_cast<std::uint32_t>(i) : sim.global_index()[i];
}

}  // namespace

std::string code_version() { return PERIDOT_VERSION; }

std::string checkpoint_fingerprint(const Problem& problem) {
  Problem p = problem;
  p.deck_path = "the deck";  // the deck may be renamed or moved
  p.output = OutputSpec{};
  p.solver.parameters.erase("end_time");
  p.solver.parameters.erase("num_steps");
  return resolved_deck_yaml(p);
}

CheckpointData collect_checkpoint(Simulation& sim) {
  const Communicator& comm = sim.communicator();
  const StateArrays arrays = sim.state_arrays();
  const BondList& bonds = sim.bonds();
  const std::size_t owned = sim.num_owned();
  CheckpointData data;
  data.code_version = code_version();
  data.deck = checkpoint_fingerprint(sim.problem());
  data.time_step = sim.time_step();
  data.step = sim.state().step;
  data.time = sim.state().time;
  data.global_points = sim.global_point_count();
  data.family_size.resize(owned);
  for (std::size_t i = 0; i < owned; ++i) data.family_size[i] = static_cast<std::uint32_t>(bonds.offsets[i + 1] - bonds.offsets[i]);
  if (!comm.serial()) {  // this rank's piece: its owned points, in its own order, with their global indices
    data.pieces = comm.size();
    data.point_index.resize(owned);
    for (std::size_t i = 0; i < owned; ++i) data.point_index[i] = global_of(sim, i);
    data.piece_boxes = comm.gather(reference_box(sim.discretization(), owned));  // on rank 0, which writes piece 0
  }
  const std::size_t owned_bonds = bonds.offsets[owned];
  for (const StateArray& entry : arrays.entries()) {
    if (entry.layout == ArrayLayout::global) {  // the same on every rank
      data.arrays.push_back({entry.name, "global", entry.width, {reinterpret_cast<const unsigned char*>(entry.data),
                                                                 reinterpret_cast<const unsigned char*>(entry.data) + entry.width}});
      continue;
    }
    if (!comm.any(entry.count > 0)) continue;  // an array this problem does not use
    const bool point = entry.layout == ArrayLayout::point;
    CheckpointArray array{entry.name, layout_name(entry.layout), entry.width, {}};
    array.bytes.assign((point ? owned : owned_bonds) * entry.width, 0);
    if (point) {
      for (std::size_t i = entry.first; i < std::min(entry.first + entry.count, owned); ++i)
        std::memcpy(array.bytes.data() + i * entry.width, entry.data + (i - entry.first) * entry.width, entry.width);
    } else {
      PERIDOT_REQUIRE(entry.count >= owned_bonds, "a bond array shorter than this rank's bonds");
      if (!array.bytes.empty()) std::memcpy(array.bytes.data(), entry.data, array.bytes.size());
    }
    data.arrays.push_back(std::move(array));
  }
  return data;
}

CheckpointSource read_checkpoint(const std::string& path, const Simulation& sim) {
  const Communicator& comm = sim.communicator();
  CheckpointSource source;
  std::string failure;
  try {
    // The checkpoint of a distributed run is one piece per rank: `path` names the set (checkpoint_400.nc for
    // checkpoint_400.nc.4.*), or any one of its pieces.
    std::string set = path;
    const std::size_t last = path.rfind('.'), before = last == std::string::npos || last == 0 ? std::string::npos : path.rfind('.', last - 1);
    if (std::filesystem::exists(path) && before != std::string::npos && is_piece_suffix(path.substr(before + 1)))
      set = path.substr(0, before);
    source.files = std::filesystem::exists(set) ? std::vector<std::string>{set} : piece_paths(set);
    if (source.files.empty()) source.files.push_back(path);  // reading it says why it cannot be read
    source.first = read_checkpoint_file(source.files.front(), true);
    if (source.first.pieces != static_cast<int>(source.files.size()))
      failure = fmt::format("'{}' is one of {} pieces, and {} lie beside it", source.files.front(), source.first.pieces,
                            source.files.size());
  } catch (const CheckpointFileError& e) {
    failure = e.what();
  } catch (const std::runtime_error& e) {
    failure = fmt::format("cannot read checkpoint '{}': {}", path, e.what());
  }
  const CheckpointData& data = source.first;
  if (failure.empty() && data.code_version != code_version())
    failure = fmt::format("'{}' was written by peridot {}, and this is peridot {}; restart it with the version that "
                          "wrote it", path, data.code_version, code_version());
  if (failure.empty() && data.deck != checkpoint_fingerprint(sim.problem()))
    failure = fmt::format("'{}' was written for another deck: {}. Only the end time, the step count and the output "
                          "settings may change on a restart", path, first_difference(data.deck, checkpoint_fingerprint(sim.problem())));
  if (failure.empty() && data.time_step != sim.time_step())
    failure = fmt::format("'{}' stepped with Δt = {:.17g} s and this deck now gives Δt = {:.17g} s (an end time that "
                          "is not a whole number of the old steps changes it); give solver.num_steps, or an end time "
                          "on the old steps", path, data.time_step, sim.time_step());
  agree(comm, path, failure);
  return source;
}

std::size_t restore_checkpoint(Simulation& sim, CheckpointSource& source, const std::string& path) {
  const Communicator& comm = sim.communicator();
  const BondList& bonds = sim.bonds();
  const std::size_t owned = sim.num_owned(), local = sim.discretization().num_points();
  std::string failure;
  if (source.first.global_points != sim.global_point_count())
    failure = fmt::format("'{}' holds {} points and this problem has {}", path, source.first.global_points, sim.global_point_count());
  // This rank's points (owned and ghosts) by global index; each is looked for in every piece.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> mine(local);
  for (std::size_t i = 0; i < local; ++i) mine[i] = {global_of(sim, i), static_cast<std::uint32_t>(i)};
  std::sort(mine.begin(), mine.end());
  std::vector<std::uint8_t> found(local, 0);
  StateArrays arrays = sim.state_arrays();

  // One piece at a time (a whole checkpoint is one piece of every point): memory for one piece only. Where the
  // first piece lists every piece's box, only the pieces whose box meets this rank's points' box are read.
  const CheckpointData header = std::move(source.first);
  const std::vector<double>& boxes = header.piece_boxes;
  const std::vector<double> here = reference_box(sim.discretization(), local);
  auto near = [&](std::size_t f) {
    if (boxes.size() != 6 * source.files.size()) return true;
    const double* b = boxes.data() + 6 * f;
    for (std::size_t d = 0; d < 3; ++d)
      if (b[d] > here[3 + d] || b[3 + d] < here[d]) return false;
    return true;
  };
  std::size_t read = 0;
  for (std::size_t f = 0; f < source.files.size() && failure.empty(); ++f) {
    // A rank without points reads the last piece all the same, for the arrays every rank holds (layout global).
    if (!near(f) && !(read == 0 && f + 1 == source.files.size())) continue;
    CheckpointData piece;
    try {
      piece = read_checkpoint_file(source.files[f]);
    } catch (const CheckpointFileError& e) {
      failure = e.what();
      break;
    }
    if (piece.deck != header.deck || piece.step != header.step || piece.time != header.time ||
        piece.pieces != header.pieces || piece.global_points != header.global_points) {
      failure = fmt::format("'{}' is not of the same checkpoint as '{}'", source.files[f], source.files.front());
      break;
    }
    const bool first_read = read++ == 0;
    const std::size_t m = piece.family_size.size();
    std::vector<std::uint64_t> bond_offset(m + 1, 0);  // where each of the piece's points' family starts
    for (std::size_t k = 0; k < m; ++k) bond_offset[k + 1] = bond_offset[k] + piece.family_size[k];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> moves;  // (point in the piece, point here)
    for (std::size_t k = 0; k < m; ++k) {
      const std::uint32_t g = piece.point_index.empty() ? static_cast<std::uint32_t>(k) : piece.point_index[k];
      const auto it = std::lower_bound(mine.begin(), mine.end(), std::make_pair(g, std::uint32_t{0}));
      if (it == mine.end() || it->first != g) continue;
      const std::uint32_t i = it->second;
      if (found[i]++) {
        failure = fmt::format("'{}' holds point {} twice", path, g);
        break;
      }
      if (i < owned && piece.family_size[k] != bonds.offsets[i + 1] - bonds.offsets[i]) {
        failure = fmt::format("'{}' has other bonds than this problem (point {})", path, g);
        break;
      }
      moves.emplace_back(static_cast<std::uint32_t>(k), i);
    }
    std::vector<std::string> names;
    for (const StateArray& entry : arrays.entries()) {
      if (!failure.empty()) break;
      const auto array = std::find_if(piece.arrays.begin(), piece.arrays.end(), [&](const CheckpointArray& a) { return a.name == entry.name; });
      if (array == piece.arrays.end()) {
        if (entry.count > 0) failure = fmt::format("'{}' has no array {}, which this problem needs", source.files[f], entry.name);
        continue;
      }
      names.push_back(array->name);
      const std::size_t w = entry.width;
      const std::size_t expected = entry.layout == ArrayLayout::point  ? m * w
                                   : entry.layout == ArrayLayout::bond ? bond_offset.back() * w
                                                                       : w;
      if (array->layout != layout_name(entry.layout) || array->width != w || array->bytes.size() != expected) {
        failure = fmt::format("'{}' holds array {} in another form ({} of {} bytes, {} in all) than this problem's",
                              source.files[f], entry.name, array->layout, array->width, array->bytes.size());
        continue;
      }
      switch (entry.layout) {
        case ArrayLayout::global:  // the same in every piece
          if (first_read) std::memcpy(entry.data, array->bytes.data(), w);
          break;
        case ArrayLayout::point:  // owned points and ghosts alike, from their owners' values
          for (const auto& [k, i] : moves)
            if (i >= entry.first && i < entry.first + entry.count)
              std::memcpy(entry.data + (i - entry.first) * w, array->bytes.data() + k * w, w);
          break;
        case ArrayLayout::bond:
          for (const auto& [k, i] : moves) {
            const std::size_t length = (bonds.offsets[i + 1] - bonds.offsets[i]) * w;
            if (i < owned && entry.count > 0 && length > 0)
              std::memcpy(entry.data + bonds.offsets[i] * w, array->bytes.data() + bond_offset[k] * w, length);
          }
          break;
      }
    }
    for (const CheckpointArray& array : piece.arrays)
      if (failure.empty() && std::find(names.begin(), names.end(), array.name) == names.end())
        failure = fmt::format("'{}' holds array {}, which this problem does not have", source.files[f], array.name);
  }
  if (failure.empty() && std::find(found.begin(), found.end(), std::uint8_t{0}) != found.end())
    failure = fmt::format("'{}' lacks points of this problem", path);
  agree(comm, path, failure);
  source.first = header;  // what the caller still reads (the step, the time); the arrays are in sim now
  sim.restored();
  return read;
}

}  // namespace peridot
