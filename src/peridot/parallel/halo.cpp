#include "peridot/parallel/halo.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>

#include "peridot/core/error.hpp"

namespace peridot {

std::size_t Halo::sent_entries() const {
  std::size_t n = 0;
  for (const Peer& p : peers_) n += p.send.size();
  return n;
}

void Halo::exchange_bytes(unsigned char* field, std::size_t bytes_per_point) const {
  constexpr int tag = 7301;
  const double start = MPI_Wtime();
  PERIDOT_REQUIRE(std::max(sent_entries(), ghosts_) * bytes_per_point <= static_cast<std::size_t>(INT32_MAX),
                  "a halo message over 2 GiB: use more ranks");
  std::vector<MPI_Request> requests;
  requests.reserve(2 * peers_.size());
  for (const Peer& p : peers_) {
    if (p.receive_count == 0) continue;
    requests.emplace_back();
    MPI_Irecv(field + (base_ + p.receive_begin) * bytes_per_point, static_cast<int>(p.receive_count * bytes_per_point),
              MPI_BYTE, p.rank, tag, comm_.mpi(), &requests.back());
  }
  send_buffer_.resize(sent_entries() * bytes_per_point);
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
