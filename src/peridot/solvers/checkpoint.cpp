#include "peridot/solvers/checkpoint.hpp"

#include <cstring>
#include <sstream>

#include <fmt/format.h>

#include "peridot/deck/deck.hpp"
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
  std::vector<std::uint32_t> index(owned), family(owned);
  for (std::size_t i = 0; i < owned; ++i) {
    index[i] = global_of(sim, i);
    family[i] = static_cast<std::uint32_t>(bonds.offsets[i + 1] - bonds.offsets[i]);
  }
  const std::size_t owned_bonds = bonds.offsets[owned];
  // Rank 0 receives every rank's owned points rank after rank; pieces below arrive in the same order.
  const std::vector<std::uint32_t> all_index = comm.gather(index), all_family = comm.gather(family);

  CheckpointData data;
  std::vector<std::uint64_t> bond_offset;  // rank 0: where each global point's family starts
  if (comm.is_root()) {
    const std::size_t n = sim.global_point_count();
    data.code_version = code_version();
    data.deck = checkpoint_fingerprint(sim.problem());
    data.time_step = sim.time_step();
    data.step = sim.state().step;
    data.time = sim.state().time;
    data.family_size.assign(n, 0);
    for (std::size_t k = 0; k < all_index.size(); ++k) data.family_size[all_index[k]] = all_family[k];
    bond_offset.assign(n + 1, 0);
    for (std::size_t g = 0; g < n; ++g) bond_offset[g + 1] = bond_offset[g] + data.family_size[g];
  }
  for (const StateArray& entry : arrays.entries()) {
    if (entry.layout == ArrayLayout::global) {
      if (comm.is_root())
        data.arrays.push_back({entry.name, "global", entry.width, {reinterpret_cast<const unsigned char*>(entry.data),
                                                                   reinterpret_cast<const unsigned char*>(entry.data) + entry.width}});
      continue;
    }
    if (!comm.any(entry.count > 0)) continue;  // an array this problem does not use
    const bool point = entry.layout == ArrayLayout::point;
    std::vector<unsigned char> mine((point ? owned : owned_bonds) * entry.width, 0);
    if (point) {
      for (std::size_t i = entry.first; i < std::min(entry.first + entry.count, owned); ++i)
        std::memcpy(mine.data() + i * entry.width, entry.data + (i - entry.first) * entry.width, entry.width);
    } else {
      PERIDOT_REQUIRE(entry.count >= owned_bonds, "a bond array shorter than this rank's bonds");
      if (!mine.empty()) std::memcpy(mine.data(), entry.data, mine.size());
    }
    const std::vector<unsigned char> all = comm.gather(mine);
    if (!comm.is_root()) continue;
    CheckpointArray array{entry.name, layout_name(entry.layout), entry.width, {}};
    const std::size_t w = entry.width;
    array.bytes.assign((point ? data.family_size.size() : bond_offset.back()) * w, 0);
    std::size_t from = 0;
    for (std::size_t k = 0; k < all_index.size(); ++k) {
      const std::uint32_t g = all_index[k];
      const std::size_t length = point ? w : all_family[k] * w;
      std::memcpy(array.bytes.data() + (point ? g * w : bond_offset[g] * w), all.data() + from, length);
      from += length;
    }
    data.arrays.push_back(std::move(array));
  }
  return data;
}

CheckpointData read_checkpoint(const std::string& path, const Simulation& sim) {
  const Communicator& comm = sim.communicator();
  CheckpointData data;
  std::string failure;
  try {
    data = read_checkpoint_file(path);
  } catch (const CheckpointFileError& e) {
    failure = e.what();
  }
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
  return data;
}

void restore_checkpoint(Simulation& sim, const CheckpointData& data, const std::string& path) {
  const Communicator& comm = sim.communicator();
  const BondList& bonds = sim.bonds();
  const std::size_t owned = sim.num_owned();
  const std::size_t n = data.family_size.size();
  std::string failure;
  if (n != sim.global_point_count())
    failure = fmt::format("'{}' holds {} points and this problem has {}", path, n, sim.global_point_count());
  std::vector<std::uint64_t> bond_offset(n + 1, 0);
  for (std::size_t g = 0; g < n; ++g) bond_offset[g + 1] = bond_offset[g] + data.family_size[g];
  for (std::size_t i = 0; i < owned && failure.empty(); ++i)
    if (data.family_size[global_of(sim, i)] != bonds.offsets[i + 1] - bonds.offsets[i])
      failure = fmt::format("'{}' has other bonds than this problem (point {})", path, global_of(sim, i));
  agree(comm, path, failure);

  StateArrays arrays = sim.state_arrays();
  std::vector<bool> used(data.arrays.size(), false);
  for (const StateArray& entry : arrays.entries()) {
    std::size_t k = 0;
    while (k < data.arrays.size() && data.arrays[k].name != entry.name) ++k;
    if (k == data.arrays.size()) {
      if (entry.count > 0) failure = fmt::format("'{}' has no array {}, which this problem needs", path, entry.name);
      continue;
    }
    used[k] = true;
    const CheckpointArray& array = data.arrays[k];
    const std::size_t w = entry.width;
    const std::size_t expected = entry.layout == ArrayLayout::point  ? n * w
                                 : entry.layout == ArrayLayout::bond ? bond_offset.back() * w
                                                                     : w;
    if (array.layout != layout_name(entry.layout) || array.width != w || array.bytes.size() != expected) {
      failure = fmt::format("'{}' holds array {} in another form ({} of {} bytes, {} in all) than this problem's", path,
                            entry.name, array.layout, array.width, array.bytes.size());
      continue;
    }
    switch (entry.layout) {
      case ArrayLayout::global: std::memcpy(entry.data, array.bytes.data(), w); break;
      case ArrayLayout::point:  // owned points and ghosts alike, from their owners' values
        for (std::size_t i = entry.first; i < entry.first + entry.count; ++i)
          std::memcpy(entry.data + (i - entry.first) * w, array.bytes.data() + global_of(sim, i) * w, w);
        break;
      case ArrayLayout::bond:
        for (std::size_t i = 0; i < owned && entry.count > 0; ++i) {
          const std::size_t length = (bonds.offsets[i + 1] - bonds.offsets[i]) * w;
          if (length > 0)
            std::memcpy(entry.data + bonds.offsets[i] * w, array.bytes.data() + bond_offset[global_of(sim, i)] * w, length);
        }
        break;
    }
  }
  for (std::size_t k = 0; k < used.size() && failure.empty(); ++k)
    if (!used[k]) failure = fmt::format("'{}' holds array {}, which this problem does not have", path, data.arrays[k].name);
  agree(comm, path, failure);
  sim.restored();
}

}  // namespace peridot
