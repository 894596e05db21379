#include "peridot/parallel/global_order.hpp"

#include <algorithm>
#include <numeric>

#include "peridot/core/error.hpp"

namespace peridot {

std::vector<std::uint64_t> global_ranks(const Communicator& comm, const std::vector<OrderKey>& keys) {
  const std::size_t n = keys.size();
  std::vector<std::uint32_t> sorted(n);
  std::iota(sorted.begin(), sorted.end(), 0u);
  std::sort(sorted.begin(), sorted.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  std::vector<std::uint64_t> rank(n);
  if (comm.serial()) {
    for (std::size_t k = 0; k < n; ++k) rank[sorted[k]] = k;
    return rank;
  }
  const int ranks = comm.size();
  // Splitters: `ranks` evenly spaced samples of every rank's sorted keys, sorted, every ranks-th taken.
  std::vector<std::uint64_t> samples;
  for (int s = 0; s < ranks && n > 0; ++s) {
    const OrderKey& key = keys[sorted[(static_cast<std::size_t>(s) * n) / static_cast<std::size_t>(ranks)]];
    samples.insert(samples.end(), key.begin(), key.end());
  }
  const std::vector<std::uint64_t> all_samples = comm.all_gather(samples);
  std::vector<OrderKey> pool(all_samples.size() / 3);
  for (std::size_t k = 0; k < pool.size(); ++k) pool[k] = {all_samples[3 * k], all_samples[3 * k + 1], all_samples[3 * k + 2]};
  std::sort(pool.begin(), pool.end());
  std::vector<OrderKey> splitter;  // rank r takes the keys in [splitter[r − 1], splitter[r])
  for (int r = 1; r < ranks && !pool.empty(); ++r) splitter.push_back(pool[(static_cast<std::size_t>(r) * pool.size()) / ranks]);

  // To each bucket's rank, this rank's keys of that bucket in increasing order.
  std::vector<int> count(static_cast<std::size_t>(ranks), 0);
  std::vector<std::uint64_t> out;
  out.reserve(3 * n);
  for (std::uint32_t k : sorted) {
    const int bucket = static_cast<int>(std::upper_bound(splitter.begin(), splitter.end(), keys[k]) - splitter.begin());
    count[static_cast<std::size_t>(bucket)] += 3;
    out.insert(out.end(), keys[k].begin(), keys[k].end());
  }
  std::vector<int> received;
  const std::vector<std::uint64_t> in = comm.all_to_all(out, count, received);
  out.clear();
  out.shrink_to_fit();
  const std::size_t m = in.size() / 3;
  std::vector<std::uint32_t> order(m);
  std::iota(order.begin(), order.end(), 0u);
  auto key_of = [&](std::uint32_t k) { return OrderKey{in[3 * k], in[3 * k + 1], in[3 * k + 2]}; };
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key_of(a) < key_of(b); });
  for (std::size_t k = 1; k < m; ++k)
    PERIDOT_REQUIRE(key_of(order[k - 1]) < key_of(order[k]), "global_ranks: two ranks hold the same key");
  // The buckets are in rank order: this bucket starts after the lower ranks' buckets.
  const std::vector<std::uint64_t> sizes = comm.all_gather(std::vector<std::uint64_t>{m});
  const std::uint64_t first = std::accumulate(sizes.begin(), sizes.begin() + comm.rank(), std::uint64_t{0});
  std::vector<std::uint64_t> position(m);
  for (std::size_t k = 0; k < m; ++k) position[order[k]] = first + k;
  // Back to the senders, in the order they sent (source after source, as received).
  std::vector<int> back_count(received.size());
  for (std::size_t r = 0; r < received.size(); ++r) back_count[r] = received[r] / 3;
  std::vector<int> returned;
  const std::vector<std::uint64_t> mine = comm.all_to_all(position, back_count, returned);
  PERIDOT_REQUIRE(mine.size() == n, "global_ranks: a key was lost");
  for (std::size_t k = 0; k < n; ++k) rank[sorted[k]] = mine[k];
  return rank;
}

}  // namespace peridot
