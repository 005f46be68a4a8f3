// A parallel loop over rows that also sums a value of each row, in fixed blocks of
// IisphScratch::kSumBlock rows: each block's sum is taken in order by whichever thread runs it,
// then the blocks' sums in order. Every thread count gives the same result bit for bit, and the sum
// costs no serial pass of its own (the solver's iterations each need one or two such sums).
#pragma once

#include <algorithm>
#include <cstdint>

#include "solver/scratch.hpp"

namespace dentsph::iisph {

// fn(k) for k in [0, n), in parallel; returns the sum of what it returns (a T with += and a zero
// default: a Vec3 holds three sums side by side). `partial` holds n / kSumBlock + 1 entries.
template <class T, class Fn>
T for_rows_summed(std::int64_t n, int threads, T* partial, Fn&& fn) {
  constexpr std::int64_t B = IisphScratch::kSumBlock;
  const std::int64_t blocks = (n + B - 1) / B;
#pragma omp parallel for num_threads(threads) schedule(static) if (threads > 1)
  for (std::int64_t b = 0; b < blocks; ++b) {
    T s{};
    const std::int64_t end = std::min(n, (b + 1) * B);
    for (std::int64_t k = b * B; k < end; ++k) s += fn(k);
    partial[b] = s;
  }
  T total{};
  for (std::int64_t b = 0; b < blocks; ++b) total += partial[b];
  return total;
}

}  // namespace dentsph::iisph
