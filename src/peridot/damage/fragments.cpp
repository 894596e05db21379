#include "peridot/damage/fragments.hpp"

#include <algorithm>
#include <functional>
#include <map>
#include <numeric>

namespace peridot {

namespace {

/// Union–find over the intact bonds of `bonds`, each pair once (both directions break together).
class Components {
 public:
  explicit Components(const BondList& bonds) {
    const std::size_t n = bonds.offsets.empty() ? 0 : bonds.offsets.size() - 1;
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0u);
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        // Each pair once; a ghost (no family of its own) is always reached from its owned partner.
        if (bonds.broken[b] || (j < i && bonds.offsets[j + 1] > bonds.offsets[j])) continue;
        const std::uint32_t a = root(static_cast<std::uint32_t>(i)), c = root(j);
        if (a != c) parent_[std::max(a, c)] = std::min(a, c);
      }
  }
  std::uint32_t root(std::uint32_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];  // path halving
    return i;
  }
  std::size_t size() const { return parent_.size(); }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace

std::size_t label_fragments(const BondList& bonds, const std::vector<std::uint32_t>& input_id,
                            std::vector<double>& label) {
  Components sets(bonds);
  const std::size_t n = sets.size();
  auto id = [&](std::size_t i) { return input_id.empty() ? static_cast<std::uint32_t>(i) : input_id[i]; };
  // The smallest input id of each root's set.
  std::vector<std::uint32_t> smallest(n, UINT32_MAX);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t& s = smallest[sets.root(static_cast<std::uint32_t>(i))];
    s = std::min(s, id(i));
  }
  label.resize(n);
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t r = sets.root(static_cast<std::uint32_t>(i));
    label[i] = smallest[r];
    if (r == i) ++count;
  }
  return count;
}

void label_fragments(const BondList& bonds, const std::vector<std::uint32_t>& input_id, std::vector<double>& label,
                     std::size_t owned, const std::function<void(std::vector<double>&)>& exchange,
                     const std::function<bool(bool)>& any) {
  Components sets(bonds);
  const std::size_t n = sets.size();
  std::vector<double> smallest(n, static_cast<double>(UINT32_MAX));
  for (std::size_t i = 0; i < n; ++i) {
    double& s = smallest[sets.root(static_cast<std::uint32_t>(i))];
    s = std::min(s, static_cast<double>(input_id[i]));
  }
  label.resize(n);
  for (bool changed = true; changed;) {
    for (std::size_t i = 0; i < n; ++i) label[i] = smallest[sets.root(static_cast<std::uint32_t>(i))];
    exchange(label);  // each ghost now carries its owner's label
    bool lowered = false;
    for (std::size_t g = owned; g < n; ++g) {
      double& s = smallest[sets.root(static_cast<std::uint32_t>(g))];
      if (label[g] < s) s = label[g], lowered = true;
    }
    changed = any(lowered);
  }
  for (std::size_t i = 0; i < n; ++i) label[i] = smallest[sets.root(static_cast<std::uint32_t>(i))];
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
