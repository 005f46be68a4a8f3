// Stage 3: rho_i = sum_j m_j W_poly6(r_ij) over all roles, self included (MODEL.md; the paper's
// eq. 6 has a stray minus sign).
#include "physics/kernels.hpp"
#include "step/grid.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

void compute_density(const Model& model, State& s) {
  const std::uint32_t n = s.size();
  for (std::uint32_t i = 0; i < n; ++i) {
    const Vec3 pi = s.pos[i];
    real rho = 0;
    grid::for_each_in_neighbourhood(model.grid, s.grid, pi, [&](std::uint32_t j) {
      rho += s.mass[j] * kernels::poly6(norm2(pi - s.pos[j]), model.kernel);
    });
    s.rho[i] = rho;
  }
}

}  // namespace dentsph::stages
