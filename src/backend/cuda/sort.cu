// Stage 2a on the device: CUB's radix sort of (bucket, index) pairs over the key bits the grid
// needs (stable, so the CPU's counting-sort order), then each bucket's range of sorted indices.
#include <cub/device/device_radix_sort.cuh>

#include "backend/cuda/kernel.cuh"
#include "backend/cuda/launch.hpp"
#include "backend/cuda/sort.hpp"

namespace dentsph::gpu {

std::size_t sort_scratch_bytes(const StepView& v) {
  std::size_t bytes = 0;
  cub::DeviceRadixSort::SortPairs(nullptr, bytes, v.key, v.key_sorted, v.iota, v.order, int(v.n), 0,
                                  key_bits(v.buckets));
  return bytes;
}

cudaError_t launch_sort(const StepView& v, const SortScratch& scratch, cudaStream_t s) {
  std::size_t bytes = scratch.bytes;
  cudaError_t e = cub::DeviceRadixSort::SortPairs(scratch.ptr, bytes, v.key, v.key_sorted, v.iota, v.order, int(v.n),
                                                  0, key_bits(v.buckets), s);
  if (e != cudaSuccess) return e;
  if ((e = cudaMemsetAsync(v.bucket_begin, 0, 2 * sizeof(std::uint32_t) * v.buckets, s)) != cudaSuccess) return e;
  return launch_each<cell_range_body>(v, kBlock, s);
}

}  // namespace dentsph::gpu
