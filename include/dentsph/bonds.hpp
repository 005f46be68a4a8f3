// Adhesion bonds: per-pair hysteresis (docs/model.md, "Adhesion hysteresis"), kept by stable particle id so that the bonds
// survive the reordering of every step. Each particle has a fixed-capacity list of partners; an
// insertion into a full list is refused and counted, never silent.
#pragma once

#include <cstdint>
#include <vector>

namespace dentsph {

struct BondCounters {
  std::uint64_t formed = 0;      // pairs bonded since the start (each pair once)
  std::uint64_t broken = 0;      // pairs unbonded since the start (each pair once)
  std::uint64_t overflowed = 0;  // insertions refused because a list was full (per side)
};

class BondStore {
 public:
  void resize(std::uint32_t particles, int capacity);
  int capacity() const { return capacity_; }
  std::uint32_t particles() const { return std::uint32_t(count_.size()); }

  int count(std::uint32_t id) const { return count_[id]; }
  std::uint32_t partner(std::uint32_t id, int k) const { return partner_[std::size_t(id) * capacity_ + k]; }
  bool has(std::uint32_t id, std::uint32_t other) const;
  // Where the list of `id` starts (for prefetching it ahead of its use).
  const std::uint32_t* list(std::uint32_t id) const { return partner_.data() + std::size_t(id) * capacity_; }

  // Adds `other` to the list of `id`; false when the list is full (the caller counts the
  // overflow: the step per thread, then into `counters`).
  bool try_add(std::uint32_t id, std::uint32_t other) {
    if (count_[id] >= capacity_) return false;
    partner_[std::size_t(id) * capacity_ + count_[id]++] = other;
    return true;
  }
  // Removes the k-th partner of `id` (the last one takes its place).
  void remove_at(std::uint32_t id, int k);

  std::size_t bytes() const { return count_.capacity() * sizeof(std::uint16_t) + partner_.capacity() * sizeof(std::uint32_t); }
  BondCounters counters;

 private:
  int capacity_ = 0;
  std::vector<std::uint16_t> count_;    // [id]
  std::vector<std::uint32_t> partner_;  // [id * capacity + k], partner ids
};

}  // namespace dentsph
