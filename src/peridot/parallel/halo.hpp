#pragma once
// Ghost (halo) entries of one rank and their exchange. A rank's local points are its owned points
// (local indices 0 … owned−1) followed by its ghosts: the partners of owned points that another rank
// owns, grouped by owner rank (ascending) and in increasing global index within a group, so that the
// ghosts of one owner are one contiguous range and are received in place. exchange() copies the owners'
// values of a per-point field into every rank's ghost entries with non-blocking point-to-point messages;
// the owned entries are only read. The partner-bond slots of a per-bond array work the same way
// (parallel/domain.hpp). Families are symmetric, so the ranks a rank receives from are the ranks it
// sends to.
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
  /// The exchange that keeps copies of other ranks' entries (points, or bonds: parallel/domain.hpp).
  /// `requests` names, `width` values each, the entries this rank copies, grouped by owner rank: count[r]
  /// entries of rank r, ascending r. Their copies sit at local entries base, base + 1, … in request order.
  /// Every owner resolves each request it receives, resolve(pointer to its `width` values), to the local
  /// entry it will send. Collective.
  template <class Resolve>
  static Halo serve(const Communicator& comm, std::size_t base, const std::vector<std::uint32_t>& requests,
                    const std::vector<int>& count, int width, Resolve&& resolve);

  /// Refreshes the ghost entries of a field with `components` values per point (point i at
  /// field[components·i + c]). Collective over the ranks that share ghosts; a no-op without ghosts.
  template <class T>
  void exchange(T* field, int components) const;
  template <class T>
  void exchange(std::vector<T>& field, int components = 1) const { exchange(field.data(), components); }

  /// Entries this rank holds copies of.
  std::size_t ghosts() const { return ghosts_; }

  /// What the exchanges have cost since set-up, for the benchmarks: wall time inside exchange() (packing,
  /// sending and waiting), messages sent and bytes sent.
  struct Traffic {
    double seconds = 0;
    std::uint64_t messages = 0, bytes = 0;
  };
  const Traffic& traffic() const { return traffic_; }

 private:
  struct Peer {
    int rank = 0;
    std::vector<std::uint32_t> send;  ///< local entries whose values this peer copies
    std::size_t receive_begin = 0, receive_count = 0;  ///< its entries here: base + [begin, begin + count)
  };
  std::size_t sent_entries() const;
  void exchange_bytes(unsigned char* field, std::size_t bytes_per_point) const;

  Communicator comm_;
  std::size_t base_ = 0, ghosts_ = 0;  ///< the copies are entries base_ … base_ + ghosts_ − 1
  std::vector<Peer> peers_;
  mutable std::vector<unsigned char> send_buffer_;
  mutable Traffic traffic_;
};

template <class Resolve>
Halo Halo::serve(const Communicator& comm, std::size_t base, const std::vector<std::uint32_t>& requests,
                 const std::vector<int>& count, int width, Resolve&& resolve) {
  Halo halo;
  halo.comm_ = comm;
  halo.base_ = base;
  halo.ghosts_ = requests.size() / static_cast<std::size_t>(width);
  if (comm.serial()) return halo;
  std::vector<int> values(count.size()), asked_values;
  for (std::size_t r = 0; r < count.size(); ++r) values[r] = width * count[r];
  const std::vector<std::uint32_t> asked = comm.all_to_all(requests, values, asked_values);
  const std::vector<int> request_displ = Communicator::offsets(values), asked_displ = Communicator::offsets(asked_values);
  for (int r = 0; r < comm.size(); ++r) {
    if (values[r] == 0 && asked_values[r] == 0) continue;
    Peer peer;
    peer.rank = r;
    peer.receive_begin = static_cast<std::size_t>(request_displ[r] / width);
    peer.receive_count = static_cast<std::size_t>(count[r]);
    for (int k = asked_displ[r]; k < asked_displ[r] + asked_values[r]; k += width) peer.send.push_back(resolve(&asked[k]));
    halo.peers_.push_back(std::move(peer));
  }
  return halo;
}

template <class T>
void Halo::exchange(T* field, int components) const {
  if (peers_.empty()) return;
  exchange_bytes(reinterpret_cast<unsigned char*>(field), sizeof(T) * static_cast<std::size_t>(components));
}

}  // namespace peridot
