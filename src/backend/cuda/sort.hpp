// Stage 2a on the GPU: after the radix sort of (key, index) pairs (CUB on the device, a stable
// sort in the emulation; both stable, so both give the CPU's counting-sort order), each sorted
// index marks where its bucket begins and ends. The bucket arrays are zeroed before (empty: [0, 0)).
#pragma once

#include "backend/cuda/view.hpp"

namespace dentsph::gpu {

// Number of key bits the radix sort needs for keys below `buckets`.
DENTSPH_HD inline int key_bits(std::uint32_t buckets) {
  int bits = 1;
  while (bits < 32 && (std::uint64_t(1) << bits) < buckets) ++bits;
  return bits;
}

DENTSPH_HD inline void cell_range_body(const StepView& v, std::uint32_t k) {
  const std::uint32_t key = v.key_sorted[k];
  if (k == 0 || v.key_sorted[k - 1] != key) v.bucket_begin[key] = k;
  if (k + 1 == v.n || v.key_sorted[k + 1] != key) v.bucket_end[key] = k + 1;
}

}  // namespace dentsph::gpu
