#pragma once
// The one registry of point fields: what a point carries that a user can see (Exodus variables, history
// probes), with its unit, which problems have it and where it lives in State. The Exodus writer, the
// probes' choices in the deck schema, the runner's field list and the distributed gathers all read this
// table; a new output field is one entry here (and the code that fills it).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "peridot/state/fields.hpp"

namespace peridot {

/// Which problems carry a field (and write it to Exodus).
enum class FieldScope : std::uint8_t {
  always,          ///< every problem
  inelastic,       ///< a model with history (lps_plastic, lps_viscoelastic) or a correspondence block
  correspondence,  ///< a correspondence block (State::point_outputs)
  thermal,         ///< a temperature field, or a correspondence J2 law with thermal softening (State::point_outputs)
  damage,          ///< some material can break bonds
  material_damage,  ///< a correspondence law with johnson_cook_damage (State::point_outputs)
};

/// Where a field's values are in a State: a vector field (3 per point), a scalar array, or neither (the
/// discretization's volume, or State::point_outputs under the field's name).
struct FieldStorage {
  VectorField* vector = nullptr;
  std::vector<double>* scalar = nullptr;
};
struct ConstFieldStorage {
  const VectorField* vector = nullptr;
  const std::vector<double>* scalar = nullptr;
};

struct PointField {
  std::string_view name;  ///< a scalar's name; a vector's stem (its components are name_x, _y, _z)
  bool vector = false;
  std::string_view unit;
  std::string_view description;
  FieldScope scope = FieldScope::always;
  bool probe = false;     ///< a history probe may sample it (current at every history row)
  bool constant = false;  ///< set once at set-up (distributed runs gather it once)
  FieldStorage (*storage)(State&) = nullptr;  ///< null: the volume, or State::point_outputs[name]

  FieldStorage in(State& state) const { return storage ? storage(state) : FieldStorage{}; }
  ConstFieldStorage in(const State& state) const {
    const FieldStorage where = in(const_cast<State&>(state));  // storage only locates the arrays
    return {where.vector, where.scalar};
  }
  /// The field's values at point i, component d (0 for scalars) in a State; not for point_outputs fields
  /// or the volume.
  double value(const State& state, std::size_t i, int d = 0) const;
};

/// Every point field, in the order the Exodus file lists them.
const std::vector<PointField>& point_fields();
/// The entry of a scalar field or of a vector component (displacement_x → displacement), null when none.
const PointField* find_point_field(std::string_view name, int* component = nullptr);
/// The names a probe may sample: every component of the probe fields (displacement_x, …, damage, …).
const std::vector<std::string>& probe_field_names();
/// The names of a field's Exodus variables: name_x, name_y (, name_z in 3D) for a vector, else name.
std::vector<std::string> variable_names(const PointField& field, int dimension);

}  // namespace peridot
