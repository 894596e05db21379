#include "peridot/deck/problem.hpp"

#include <algorithm>

namespace peridot {

const MaterialSpec& Problem::material_of(const BodySpec& body) const {
  for (const MaterialSpec& material : materials)
    if (material.name == body.material) return material;
  PERIDOT_REQUIRE(false, "body '" + body.name + "' refers to undefined material '" + body.material + "'");
}

}  // namespace peridot

namespace peridot {

Parameters::Entry& Parameters::slot(std::string key, Kind kind, SourcePos pos) {
  auto it = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.key == key; });
  if (it == entries_.end()) {
    entries_.push_back({});
    it = entries_.end() - 1;
    it->key = std::move(key);
  }
  it->kind = kind;
  it->pos = std::move(pos);
  return *it;
}

void Parameters::set_number(std::string key, double value, SourcePos pos) {
  slot(std::move(key), Kind::number, std::move(pos)).number = value;
}

void Parameters::set_integer(std::string key, std::int64_t value, SourcePos pos) {
  slot(std::move(key), Kind::integer, std::move(pos)).number = static_cast<double>(value);
}

void Parameters::set_boolean(std::string key, bool value, SourcePos pos) {
  slot(std::move(key), Kind::boolean, std::move(pos)).number = value ? 1.0 : 0.0;
}

void Parameters::set_text(std::string key, std::string value, SourcePos pos) {
  slot(std::move(key), Kind::text, std::move(pos)).text = std::move(value);
}

const Parameters::Entry* Parameters::find(std::string_view key) const {
  for (const Entry& e : entries_)
    if (e.key == key) return &e;
  return nullptr;
}

bool Parameters::has(std::string_view key) const { return find(key) != nullptr; }

void Parameters::erase(std::string_view key) {
  std::erase_if(entries_, [&](const Entry& e) { return e.key == key; });
}

const Parameters::Entry& Parameters::get(std::string_view key, Kind kind) const {
  const Entry* e = find(key);
  static const char* const kinds[] = {"number", "integer", "boolean", "text"};
  PERIDOT_REQUIRE(e && e->kind == kind,
                  "parameter '" + std::string(key) + "' is not a " + kinds[static_cast<int>(kind)] + " here");
  return *e;
}

double Parameters::number(std::string_view key) const { return get(key, Kind::number).number; }
std::int64_t Parameters::integer(std::string_view key) const {
  return static_cast<std::int64_t>(get(key, Kind::integer).number);
}
bool Parameters::boolean(std::string_view key) const { return get(key, Kind::boolean).number != 0; }
const std::string& Parameters::text(std::string_view key) const { return get(key, Kind::text).text; }

double Parameters::number_or(std::string_view key, double fallback) const {
  const Entry* e = find(key);
  return e && e->kind == Kind::number ? e->number : fallback;
}

}  // namespace peridot
