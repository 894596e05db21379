#pragma once
// Which of a rank's points lie in the other ranks' boxes: the ghost candidates of the decomposition (boxes of
// the owners' points widened by the reach) and the contact candidates (boxes of the deformed positions
// widened by the search reach). The points are binned once on a grid over their bounding box, and each box
// visits only the cells it overlaps, so a rank's cost is about its points plus the candidates it finds, not
// its points times the rank count.
#include <cstdint>
#include <vector>

namespace peridot {

/// For each rank r other than `self`, the indices of the n points (x, y, z at coords[stride·k + 0, 1, 2])
/// inside the closed box boxes[6r … 6r + 5] (lo x, y, z, hi x, y, z; an empty box has a lo above its hi), in
/// increasing order.
std::vector<std::vector<std::uint32_t>> points_in_boxes(const double* coords, std::size_t stride, std::size_t n,
                                                        const std::vector<double>& boxes, int self);

}  // namespace peridot
