// Fragments (damage/fragments.hpp): connected sets of points through intact bonds, each labelled by the
// smallest input id among its points.
#include <gtest/gtest.h>

#include "peridot/damage/fragments.hpp"

namespace peridot {
namespace {

/// A chain 0 – 1 – 2 – 3 – 4 (symmetric CSR), bonds between neighbours only.
BondList chain(std::size_t n) {
  BondList bonds;
  bonds.offsets.push_back(0);
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) bonds.neighbors.push_back(static_cast<std::uint32_t>(i - 1));
    if (i + 1 < n) bonds.neighbors.push_back(static_cast<std::uint32_t>(i + 1));
    bonds.offsets.push_back(bonds.neighbors.size());
  }
  bonds.broken.assign(bonds.neighbors.size(), 0);
  return bonds;
}

void break_pair(BondList& bonds, std::uint32_t i, std::uint32_t j) {
  for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b)
    if (bonds.neighbors[b] == j) bonds.broken[b] = 1;
  for (std::uint64_t b = bonds.offsets[j]; b < bonds.offsets[j + 1]; ++b)
    if (bonds.neighbors[b] == i) bonds.broken[b] = 1;
}

TEST(Fragments, IntactChainIsOneFragmentLabelledBySmallestInputId) {
  const BondList bonds = chain(5);
  const std::vector<std::uint32_t> input_id = {7, 3, 9, 4, 8};  // the space-filling-curve order scrambles ids
  std::vector<double> label;
  EXPECT_EQ(label_fragments(bonds, input_id, label), 1u);
  for (double l : label) EXPECT_EQ(l, 3.0);
}

TEST(Fragments, BrokenBondsSplitTheChainAndIsolatedPointsCount) {
  BondList bonds = chain(6);
  break_pair(bonds, 1, 2);  // {0, 1} | {2, 3} | ...
  break_pair(bonds, 3, 4);
  break_pair(bonds, 4, 5);  // ... {4} alone | {5} alone
  std::vector<double> label;
  EXPECT_EQ(label_fragments(bonds, {}, label), 4u);
  EXPECT_EQ(label, (std::vector<double>{0, 0, 2, 2, 4, 5}));
  EXPECT_EQ(fragment_sizes(label), (std::vector<std::size_t>{2, 2, 1, 1}));
}

}  // namespace
}  // namespace peridot
