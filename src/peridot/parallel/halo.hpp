#pragma once
// Ghost (halo) points of one rank and their exchange. A rank's local points are its owned points
// (local indices 0 … owned−1) followed by its ghosts: the partners of owned points that another rank
// owns, grouped by owner rank (ascending) and in increasing global index within a group, so that the
// ghosts of one owner are one contiguous range and are received in place. exchange() copies the owners'
// values of a per-point field into every rank's ghost entries with non-blocking point-to-point messages;
// the owned entries are only read. Families are symmetric, so the ranks a rank receives from are the
// ranks it sends to.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "peridot/parallel/communicator.hpp"

namespace peridot {

class Halo {
 public:
  /// No ghosts (one rank).
  Halo() = default;
  /// ghost_global: the ghosts' global indices in local order; ghost_owner: their owner ranks (non-decreasing);
  /// owned_global: the global index of every owned point (increasing). Collective.
  Halo(const Communicator& comm, const std::vector<std::uint32_t>& owned_global,
       const std::vector<std::uint32_t>& ghost_global, const std::vector<int>& ghost_owner);

  /// The same exchange for entries other than points (per-bond arrays, parallel/domain.hpp): what each peer
  /// receives is `receive_count` entries written at base + receive_begin, what it sends the entries `send`.
  struct Peer {
    int rank = 0;
    std::vector<std::uint32_t> send;  ///< local entries whose values this peer holds as ghosts
    std::size_t receive_begin = 0, receive_count = 0;  ///< this peer's ghosts: base + [begin, begin + count)
  };
  Halo(const Communicator& comm, std::size_t base, std::size_t ghosts, std::vector<Peer> peers)
      : comm_(comm), owned_(base), ghosts_(ghosts), peers_(std::move(peers)) {}

  /// Refreshes the ghost entries of a field with `components` values per point (point i at
  /// field[components·i + c]). Collective over the ranks that share ghosts; a no-op without ghosts.
  template <class T>
  void exchange(T* field, int components) const;
  template <class T>
  void exchange(std::vector<T>& field, int components = 1) const { exchange(field.data(), components); }

  std::size_t owned() const { return owned_; }
  std::size_t ghosts() const { return ghosts_; }
  /// Ranks this rank exchanges with, and the point values it sends per exchange (sum over them).
  std::size_t peers() const { return peers_.size(); }
  std::size_t sent_points() const;

  /// What the exchanges have cost since set-up, for the benchmarks: wall time inside exchange() (packing,
  /// sending and waiting), messages sent and bytes sent.
  struct Traffic {
    double seconds = 0;
    std::uint64_t messages = 0, bytes = 0;
  };
  const Traffic& traffic() const { return traffic_; }

 private:
  void exchange_bytes(unsigned char* field, std::size_t bytes_per_point) const;

  Communicator comm_;
  std::size_t owned_ = 0, ghosts_ = 0;  ///< owned_: where the ghost entries begin
  std::vector<Peer> peers_;
  mutable std::vector<unsigned char> send_buffer_;
  mutable Traffic traffic_;
};

template <class T>
void Halo::exchange(T* field, int components) const {
  if (peers_.empty()) return;
  exchange_bytes(reinterpret_cast<unsigned char*>(field), sizeof(T) * static_cast<std::size_t>(components));
}

}  // namespace peridot
