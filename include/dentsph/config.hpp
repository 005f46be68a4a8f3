// Build-wide conventions shared by host and device code.
#pragma once

#if defined(__CUDACC__)
#define DENTSPH_HD __host__ __device__
#else
#define DENTSPH_HD
#endif

namespace dentsph {

// Floating-point type of every physical quantity. Double keeps the grid step and the
// all-pairs reference within 1e-5 relative of each other over long runs, where summation
// order is the only difference between them.
using real = double;

}  // namespace dentsph
