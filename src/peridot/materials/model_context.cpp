#include "peridot/materials/model_context.hpp"

#include <algorithm>
#include <cmath>

#include "peridot/materials/dispatch.hpp"

namespace peridot {

bool ModelContext::any_dilatation() const {
  return std::any_of(params.begin(), params.end(),
                     [](const MaterialParams& p) { return with_model(p.model, [](auto m) { return m.uses_dilatation; }); });
}

bool ModelContext::any_damage() const {
  return std::any_of(params.begin(), params.end(), [](const MaterialParams& p) { return std::isfinite(p.critical_stretch); });
}

int ModelContext::bond_history_arrays() const {
  int arrays = 0;
  for (const MaterialParams& p : params)
    arrays = std::max(arrays, with_model(p.model, [](auto m) { return decltype(m)::bond_history_arrays; }));
  return arrays;
}

std::vector<std::vector<double> MaterialHistory::*> ModelContext::partner_point_scratch() const {
  std::vector<std::vector<double> MaterialHistory::*> fields;
  for (const MaterialParams& p : params)
    with_model(p.model, [&](auto model) {
      for (auto field : decltype(model)::partner_point_scratch)
        if (std::find(fields.begin(), fields.end(), field) == fields.end()) fields.push_back(field);
    });
  return fields;
}

}  // namespace peridot
