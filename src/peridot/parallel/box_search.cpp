#include "peridot/parallel/box_search.hpp"

#include <algorithm>
#include <cmath>

#include "peridot/core/bounding_box.hpp"

namespace peridot {

std::vector<std::vector<std::uint32_t>> points_in_boxes(const double* coords, std::size_t stride, std::size_t n,
                                                        const std::vector<double>& boxes, int self) {
  const std::size_t ranks = boxes.size() / 6;
  std::vector<std::vector<std::uint32_t>> inside(ranks);
  if (n == 0) return inside;
  const BoundingBox all = bounding_box(coords, stride, n);
  const Vec3 lo = all.lo, hi = all.hi;
  // About eight points per cell over the axes the points span (a flat or thin set gets one cell across).
  double extent[3], volume = 1;
  int spanned = 0;
  for (std::size_t d = 0; d < 3; ++d) {
    extent[d] = hi[d] - lo[d];
    if (extent[d] > 0) volume *= extent[d], ++spanned;
  }
  const double side = spanned == 0 ? 1.0 : std::pow(volume * 8.0 / static_cast<double>(n), 1.0 / spanned);
  long cells[3];
  for (std::size_t d = 0; d < 3; ++d)
    cells[d] = extent[d] > 0 ? std::clamp(static_cast<long>(extent[d] / side) + 1, 1L, 1L << 20) : 1;
  while (static_cast<double>(cells[0]) * static_cast<double>(cells[1]) * static_cast<double>(cells[2]) > 2.0 * static_cast<double>(n) + 8)
    for (long& c : cells) c = std::max(1L, c / 2);  // a nearly flat set: never many more cells than points
  auto cell_of = [&](double x, std::size_t d) {
    if (cells[d] == 1) return 0L;
    return std::clamp(static_cast<long>((x - lo[d]) / extent[d] * static_cast<double>(cells[d])), 0L, cells[d] - 1);
  };
  // Counting sort of the points by cell, increasing index within a cell.
  const std::size_t total = static_cast<std::size_t>(cells[0] * cells[1] * cells[2]);
  std::vector<std::uint32_t> first(total + 1, 0), order(n);
  std::vector<std::uint32_t> cell(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double* x = coords + stride * k;
    cell[k] = static_cast<std::uint32_t>((cell_of(x[2], 2) * cells[1] + cell_of(x[1], 1)) * cells[0] + cell_of(x[0], 0));
    ++first[cell[k] + 1];
  }
  for (std::size_t c = 0; c < total; ++c) first[c + 1] += first[c];
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t k = 0; k < n; ++k) order[fill[cell[k]]++] = static_cast<std::uint32_t>(k);

  for (std::size_t r = 0; r < ranks; ++r) {
    if (static_cast<int>(r) == self) continue;
    const double* b = boxes.data() + 6 * r;
    bool meets = true;
    for (std::size_t d = 0; d < 3; ++d) meets = meets && b[d] <= hi[d] && b[3 + d] >= lo[d];
    if (!meets) continue;
    long from[3], to[3];
    for (std::size_t d = 0; d < 3; ++d) from[d] = cell_of(std::max(b[d], lo[d]), d), to[d] = cell_of(std::min(b[3 + d], hi[d]), d);
    std::vector<std::uint32_t>& found = inside[r];
    for (long k = from[2]; k <= to[2]; ++k)
      for (long j = from[1]; j <= to[1]; ++j)
        for (long i = from[0]; i <= to[0]; ++i) {
          const std::size_t c = static_cast<std::size_t>((k * cells[1] + j) * cells[0] + i);
          for (std::uint32_t e = first[c]; e < first[c + 1]; ++e) {
            const double* x = coords + stride * order[e];
            if (x[0] >= b[0] && x[1] >= b[1] && x[2] >= b[2] && x[0] <= b[3] && x[1] <= b[4] && x[2] <= b[5])
              found.push_back(order[e]);
          }
        }
    std::sort(found.begin(), found.end());
  }
  return inside;
}

}  // namespace peridot
