#include "peridot/deck/problem.hpp"

namespace peridot {

const MaterialSpec& Problem::material_of(const BodySpec& body) const {
  for (const MaterialSpec& material : materials)
    if (material.name == body.material) return material;
  PERIDOT_REQUIRE(false, "body '" + body.name + "' refers to undefined material '" + body.material + "'");
}

}  // namespace peridot

namespace peridot {

ModelParameters::Entry& ModelParameters::slot(std::string key) {
  for (Entry& e : entries_)
    if (e.key == key) return e;
  entries_.push_back({});
  entries_.back().key = std::move(key);
  return entries_.back();
}

void ModelParameters::set_number(std::string key, double value, SourcePos pos) {
  Entry& e = slot(std::move(key));
  e.pos = std::move(pos);
  e.number = value;
  e.is_text = false;
}

void ModelParameters::set_text(std::string key, std::string value, SourcePos pos) {
  Entry& e = slot(std::move(key));
  e.pos = std::move(pos);
  e.text = std::move(value);
  e.is_text = true;
}

const ModelParameters::Entry* ModelParameters::find(std::string_view key) const {
  for (const Entry& e : entries_)
    if (e.key == key) return &e;
  return nullptr;
}

bool ModelParameters::has(std::string_view key) const { return find(key) != nullptr; }

double ModelParameters::number(std::string_view key) const {
  const Entry* e = find(key);
  PERIDOT_REQUIRE(e && !e->is_text, "model parameter '" + std::string(key) + "' is not a number of this material");
  return e->number;
}

double ModelParameters::number_or(std::string_view key, double fallback) const {
  const Entry* e = find(key);
  return e && !e->is_text ? e->number : fallback;
}

const std::string& ModelParameters::text(std::string_view key) const {
  const Entry* e = find(key);
  PERIDOT_REQUIRE(e && e->is_text, "model parameter '" + std::string(key) + "' is not a text of this material");
  return e->text;
}

}  // namespace peridot
