#pragma once
// What a trajectory depends on, declared by whoever holds it (the state, the models' histories, the
// correspondence blocks, the energy criterion, the rigid bodies, the solver), so that a checkpoint saves all
// of it without a list of its own (solvers/checkpoint.hpp). Each entry names one array in place:
//  - point: `width` bytes for each of `count` consecutive local points from `first` (owned points; an array
//    that also holds ghosts declares its owned part, and the checkpoint fills the ghosts from their owners);
//  - bond: `width` bytes for each of this rank's bonds (BondList order; partner-bond slots excluded);
//  - global: `width` bytes in all, the same on every rank (a rigid body's velocity, a solver's scalars).
// A checkpoint stores point and bond arrays in the global point order (each family in its own order, which
// is the serial one on every rank), so that it restarts on any number of ranks. Every rank declares the same
// entries in the same order, with a count of 0 where it holds none (an array the problem does not use has
// count 0 everywhere and is not stored).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "peridot/state/fields.hpp"

namespace peridot {

enum class ArrayLayout : std::uint8_t { point, bond, global };

struct StateArray {
  std::string name;
  ArrayLayout layout = ArrayLayout::global;
  std::size_t width = 0;  ///< bytes per point or bond; global: bytes in all
  std::size_t first = 0;  ///< point: the local index of the first point covered
  std::size_t count = 0;  ///< point: points covered; bond: bonds; global: 1
  std::byte* data = nullptr;
};

class StateArrays {
 public:
  /// `per_point` values of T for each of `count` points from local point `first`, point i's at
  /// values + i × per_point.
  template <class T>
  void points(std::string name, T* values, std::size_t count, std::size_t per_point, std::size_t first) {
    static_assert(std::is_trivially_copyable_v<T>);
    entries_.push_back({std::move(name), ArrayLayout::point, sizeof(T) * per_point, first, count,
                        reinterpret_cast<std::byte*>(values)});
  }
  /// The first `count` points' values (fewer when `values` is shorter: an array the problem does not use is
  /// empty).
  template <class T>
  void points(std::string name, std::vector<T>& values, std::size_t count, std::size_t per_point = 1) {
    points(std::move(name), values.data(), std::min(count, values.size() / per_point), per_point, 0);
  }
  void points(std::string name, VectorField& field, std::size_t count) {
    points(std::move(name), field.data(), std::min(count, field.size()), 3, 0);
  }
  /// One T per bond (`values` may be longer: partner-bond slots follow the bonds; empty: an array this problem
  /// does not use).
  template <class T>
  void bonds(std::string name, std::vector<T>& values, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>);
    entries_.push_back({std::move(name), ArrayLayout::bond, sizeof(T), 0, values.empty() ? 0 : count,
                        reinterpret_cast<std::byte*>(values.data())});
  }
  /// `n` values of T at `values`, the same on every rank.
  template <class T>
  void global(std::string name, T* values, std::size_t n = 1) {
    static_assert(std::is_trivially_copyable_v<T>);
    entries_.push_back({std::move(name), ArrayLayout::global, sizeof(T) * n, 0, 1, reinterpret_cast<std::byte*>(values)});
  }
  const std::vector<StateArray>& entries() const { return entries_; }

 private:
  std::vector<StateArray> entries_;
};

}  // namespace peridot
