#include "peridot/damage/fragments.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <numeric>

namespace peridot {

std::size_t label_fragments(const BondList& bonds, const std::vector<std::uint32_t>& input_id,
                            std::vector<double>& label) {
  const std::size_t n = bonds.offsets.empty() ? 0 : bonds.offsets.size() - 1;
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  auto root = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];  // path halving
    return i;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      if (bonds.broken[b] || j < i) continue;  // each pair once; both directions break together
      const std::uint32_t a = root(static_cast<std::uint32_t>(i)), c = root(j);
      if (a != c) parent[std::max(a, c)] = std::min(a, c);
    }
  auto id = [&](std::size_t i) { return input_id.empty() ? static_cast<std::uint32_t>(i) : input_id[i]; };
  // The smallest input id of each root's set.
  std::vector<std::uint32_t> smallest(n, UINT32_MAX);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t& s = smallest[root(static_cast<std::uint32_t>(i))];
    s = std::min(s, id(i));
  }
  label.resize(n);
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t r = root(static_cast<std::uint32_t>(i));
    label[i] = smallest[r];
    if (r == i) ++count;
  }
  return count;
}

std::vector<std::size_t> fragment_sizes(const std::vector<double>& label) {
  std::map<double, std::size_t> sizes;
  for (double l : label) ++sizes[l];
  std::vector<std::size_t> out;
  for (const auto& [l, size] : sizes) out.push_back(size);
  std::sort(out.begin(), out.end(), std::greater<>());
  return out;
}

}  // namespace peridot
