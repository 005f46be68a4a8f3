#include "dentsph/bonds.hpp"

namespace dentsph {

void BondStore::resize(std::uint32_t particles, int capacity) {
  if (capacity != capacity_ && !count_.empty()) {
    // Re-layout existing lists for the new capacity.
    std::vector<std::uint32_t> old = std::move(partner_);
    const int old_cap = capacity_;
    partner_.assign(std::size_t(count_.size()) * capacity, 0);
    for (std::size_t id = 0; id < count_.size(); ++id) {
      if (count_[id] > capacity) count_[id] = std::uint16_t(capacity);
      for (int k = 0; k < count_[id]; ++k) partner_[id * capacity + k] = old[id * old_cap + k];
    }
  }
  capacity_ = capacity;
  count_.resize(particles, 0);
  partner_.resize(std::size_t(particles) * capacity, 0);
}

bool BondStore::has(std::uint32_t id, std::uint32_t other) const {
  const std::uint32_t* p = &partner_[std::size_t(id) * capacity_];
  for (int k = 0; k < count_[id]; ++k)
    if (p[k] == other) return true;
  return false;
}

void BondStore::remove_at(std::uint32_t id, int k) {
  std::uint32_t* p = &partner_[std::size_t(id) * capacity_];
  p[k] = p[--count_[id]];
}


}  // namespace dentsph
