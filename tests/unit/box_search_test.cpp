// points_in_boxes (parallel/box_search.hpp) against testing every point in every box: random clouds in 3D, flat
// (2D) and on a line, boxes that miss, cover everything, are empty or touch points exactly on their faces.
#include "peridot/parallel/box_search.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

namespace {

std::vector<std::vector<std::uint32_t>> brute_force(const std::vector<double>& xyz, const std::vector<double>& boxes, int self) {
  std::vector<std::vector<std::uint32_t>> inside(boxes.size() / 6);
  for (std::size_t r = 0; r < inside.size(); ++r) {
    if (static_cast<int>(r) == self) continue;
    const double* b = boxes.data() + 6 * r;
    for (std::size_t k = 0; k < xyz.size() / 3; ++k) {
      const double* x = xyz.data() + 3 * k;
      if (x[0] >= b[0] && x[1] >= b[1] && x[2] >= b[2] && x[0] <= b[3] && x[1] <= b[4] && x[2] <= b[5])
        inside[r].push_back(static_cast<std::uint32_t>(k));
    }
  }
  return inside;
}

}  // namespace

TEST(BoxSearch, FindsWhatTestingEveryPointFinds) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int shape : {3, 2, 1}) {  // spanned axes
    for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{57}, std::size_t{5000}}) {
      std::vector<double> xyz(3 * n, 0.0);
      for (std::size_t k = 0; k < n; ++k)
        for (int d = 0; d < shape; ++d) xyz[3 * k + d] = d == 0 ? 10 * unit(random) : unit(random);
      std::vector<double> boxes;
      for (int r = 0; r < 40; ++r) {
        double lo[3], hi[3];
        for (int d = 0; d < 3; ++d) {
          const double a = 12 * unit(random) - 1, b = a + (r % 5) * unit(random);
          lo[d] = a, hi[d] = b;
        }
        if (r == 3) lo[0] = 1e300, hi[0] = -1e300;                    // an empty box
        if (r == 4) for (int d = 0; d < 3; ++d) lo[d] = -1e300, hi[d] = 1e300;  // everything
        if (r == 5 && n > 0) for (int d = 0; d < 3; ++d) lo[d] = hi[d] = xyz[d];  // one point, on every face
        boxes.insert(boxes.end(), lo, lo + 3);
        boxes.insert(boxes.end(), hi, hi + 3);
      }
      for (int self : {-1, 0, 7}) {
        const auto found = peridot::points_in_boxes(xyz.data(), 3, n, boxes, self);
        EXPECT_EQ(found, brute_force(xyz, boxes, self)) << shape << " axes, " << n << " points";
      }
      if (n > 0) {
        const auto all = peridot::points_in_boxes(xyz.data(), 3, n, boxes, -1);
        EXPECT_EQ(all[4].size(), n);
        EXPECT_FALSE(all[5].empty());
        EXPECT_TRUE(all[3].empty());
      }
    }
  }
}
