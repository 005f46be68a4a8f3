// The Model's material table (include/dentsph/material.hpp).
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/material.hpp"

namespace dentsph {

MaterialIndex MaterialTable::add(const std::string& name, const Material& material) {
  if (name.empty()) throw std::invalid_argument("material table: a material needs a name");
  if (find(std::string_view(name)))
    throw std::invalid_argument(fmt::format("material table: \"{}\" is already there; give each material its own name", name));
  if (entries_.size() >= kCapacity)
    throw std::invalid_argument(fmt::format("material table: at most {} materials; \"{}\" is one too many", kCapacity, name));
  entries_.push_back({name, material});
  return MaterialIndex(entries_.size() - 1);
}

std::optional<MaterialIndex> MaterialTable::find(std::string_view name) const {
  for (std::size_t i = 0; i < entries_.size(); ++i)
    if (entries_[i].name == name) return MaterialIndex(i);
  return std::nullopt;
}

std::optional<MaterialIndex> MaterialTable::find(const Material& material) const {
  for (std::size_t i = 0; i < entries_.size(); ++i)
    if (entries_[i].material == material) return MaterialIndex(i);
  return std::nullopt;
}

MaterialIndex MaterialTable::at(std::string_view name, std::string_view where) const {
  if (auto i = find(name)) return *i;
  throw std::invalid_argument(fmt::format("{}: unknown material \"{}\"; the materials are: {}", where, name,
                                          entries_.empty() ? std::string("(none)") : names()));
}

MaterialIndex MaterialTable::intern(const Material& material) {
  if (auto i = find(material)) return *i;
  std::string name = fmt::format("material {}", entries_.size());
  while (find(std::string_view(name))) name += "'";
  return add(name, material);
}

std::string MaterialTable::names() const {
  std::string s;
  for (const NamedMaterial& e : entries_) s += (s.empty() ? "" : ", ") + e.name;
  return s;
}

}  // namespace dentsph
