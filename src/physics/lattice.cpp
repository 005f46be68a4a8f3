// Particle mass for a lattice at rest density: m = rho0 / sum_j W(|r_ij|) over the lattice, W the
// density's kernel (poly6, or the cubic spline where KernelCoeffs::cubic_density).
#include "dentsph/lattice.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/limits.hpp"
#include "physics/kernels.hpp"

namespace dentsph {

real lattice_particle_mass(real rho0, real spacing, const KernelCoeffs& kernel) {
  // The sum visits (2 h / spacing + 1)^3 points: a spacing far under h would loop for hours.
  if (const std::string problem = limits::spacing_problem(spacing, kernel.h); !problem.empty())
    throw std::invalid_argument(
        fmt::format("lattice_particle_mass: spacing {}; {}", problem, limits::spacing_fix(kernel.h)));
  const int n = int(std::ceil(kernel.h / spacing));
  real sum = 0;
  if (kernel.cubic_density) {
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j)
        for (int k = -n; k <= n; ++k) sum += kernels::cubic(spacing * std::sqrt(real(i * i + j * j + k * k)), kernel);
    return rho0 / sum;
  }
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) sum += kernels::poly6(spacing * spacing * real(i * i + j * j + k * k), kernel);
  return rho0 / sum;
}

}  // namespace dentsph
