#include "peridot/parallel/contact_candidates.hpp"

#include <algorithm>
#include <numeric>

#include "peridot/core/bounding_box.hpp"
#include "peridot/parallel/box_search.hpp"

namespace peridot {

ContactCandidates gather_contact_candidates(const Communicator& comm, ContactCandidates mine, double reach) {
  if (comm.serial()) return mine;
  const std::size_t owned = mine.size();
  // Empty (and meeting nothing) on a rank without owned points.
  const std::vector<double> boxes = comm.all_gather(bounding_box(mine.y.data(), 3, owned).widened(reach).six());

  // Rank after rank, the owned points inside its box: index, positions and volume, block.
  std::vector<std::uint32_t> send_index;
  std::vector<double> send_reals;
  std::vector<std::int32_t> send_block;
  std::vector<int> count(static_cast<std::size_t>(comm.size()), 0), real_count(count.size(), 0);
  const std::vector<std::vector<std::uint32_t>> inside = points_in_boxes(mine.y.data(), 3, owned, boxes, comm.rank());
  for (int r = 0; r < comm.size(); ++r) {
    for (const std::uint32_t i : inside[static_cast<std::size_t>(r)]) {
      const double* y = mine.y.data() + 3 * i;
      send_index.push_back(mine.global[i]);
      send_reals.insert(send_reals.end(), y, y + 3);
      send_reals.insert(send_reals.end(), mine.x.data() + 3 * i, mine.x.data() + 3 * i + 3);
      send_reals.push_back(mine.volume[i]);
      send_block.push_back(mine.block[i]);
    }
    count[static_cast<std::size_t>(r)] = static_cast<int>(inside[static_cast<std::size_t>(r)].size());
    real_count[static_cast<std::size_t>(r)] = 7 * count[static_cast<std::size_t>(r)];
  }
  std::vector<int> received, received_reals;
  const std::vector<std::uint32_t> index = comm.all_to_all(send_index, count, received);
  const std::vector<double> reals = comm.all_to_all(send_reals, real_count, received_reals);
  const std::vector<std::int32_t> block = comm.all_to_all(send_block, count, received);

  std::vector<int> source(index.size());
  for (std::size_t r = 0, k = 0; r < received.size(); ++r)
    for (int c = 0; c < received[r]; ++c) source[k++] = static_cast<int>(r);
  std::vector<std::uint32_t> order(index.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return index[a] < index[b]; });
  for (std::uint32_t k : order)
    mine.add(index[k], source[k], reals.data() + 7 * k, reals.data() + 7 * k + 3, reals[7 * k + 6], block[k]);
  return mine;
}

}  // namespace peridot
