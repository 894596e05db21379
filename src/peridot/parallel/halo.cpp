#include "peridot/parallel/halo.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "peridot/core/error.hpp"

namespace peridot {

Halo::Halo(const Communicator& comm, const std::vector<std::uint32_t>& owned_global,
           const std::vector<std::uint32_t>& ghost_global, const std::vector<int>& ghost_owner)
    : comm_(comm), owned_(owned_global.size()), ghosts_(ghost_global.size()) {
  if (comm.serial()) {
    PERIDOT_REQUIRE(ghost_global.empty(), "a serial run has no ghosts");
    return;
  }
  const int size = comm.size();
  // Ask every owner for the points this rank holds as its ghosts.
  std::vector<int> request_count(size, 0), asked_count;
  for (int owner : ghost_owner) ++request_count[owner];
  const std::vector<std::uint32_t> asked = comm.all_to_all(ghost_global, request_count, asked_count);
  const std::vector<int> request_displ = Communicator::offsets(request_count), asked_displ = Communicator::offsets(asked_count);

  for (int r = 0; r < size; ++r) {
    if (request_count[r] == 0 && asked_count[r] == 0) continue;
    Peer peer;
    peer.rank = r;
    peer.receive_begin = static_cast<std::size_t>(request_displ[r]);
    peer.receive_count = static_cast<std::size_t>(request_count[r]);
    for (int k = asked_displ[r]; k < asked_displ[r] + asked_count[r]; ++k) {
      const auto found = std::lower_bound(owned_global.begin(), owned_global.end(), asked[k]);
      PERIDOT_REQUIRE(found != owned_global.end() && *found == asked[k], "a ghost was asked of a rank that does not own it");
      peer.send.push_back(static_cast<std::uint32_t>(found - owned_global.begin()));
    }
    peers_.push_back(std::move(peer));
  }
}

std::size_t Halo::sent_points() const {
  std::size_t n = 0;
  for (const Peer& p : peers_) n += p.send.size();
  return n;
}

void Halo::exchange_bytes(unsigned char* field, std::size_t bytes_per_point) const {
  constexpr int tag = 7301;
  const double start = MPI_Wtime();
  PERIDOT_REQUIRE(std::max(sent_points(), ghosts_) * bytes_per_point <= static_cast<std::size_t>(INT32_MAX),
                  "a halo message over 2 GiB: use more ranks");
  std::vector<MPI_Request> requests;
  requests.reserve(2 * peers_.size());
  for (const Peer& p : peers_) {
    if (p.receive_count == 0) continue;
    requests.emplace_back();
    MPI_Irecv(field + (owned_ + p.receive_begin) * bytes_per_point, static_cast<int>(p.receive_count * bytes_per_point),
              MPI_BYTE, p.rank, tag, comm_.mpi(), &requests.back());
  }
  send_buffer_.resize(sent_points() * bytes_per_point);
  unsigned char* out = send_buffer_.data();
  for (const Peer& p : peers_) {
    unsigned char* begin = out;
    for (std::uint32_t i : p.send) {
      std::memcpy(out, field + i * bytes_per_point, bytes_per_point);
      out += bytes_per_point;
    }
    if (p.send.empty()) continue;
    requests.emplace_back();
    MPI_Isend(begin, static_cast<int>(out - begin), MPI_BYTE, p.rank, tag, comm_.mpi(), &requests.back());
    traffic_.messages += 1;
    traffic_.bytes += static_cast<std::uint64_t>(out - begin);
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  traffic_.seconds += MPI_Wtime() - start;
}

}  // namespace peridot
