// Stage 2b: gather every per-particle array into cell order, so that the neighbour loops read
// memory in sequence; then refresh the id -> index map that bonds and callers use, and the
// coordinate arrays the neighbour searches read.
#include "step/stages.hpp"

namespace dentsph::stages {

namespace {

template <class T>
void gather(std::vector<T>& a, std::vector<T>& scratch, const std::vector<std::uint32_t>& order, int threads) {
  const std::int64_t n = std::int64_t(a.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t k = 0; k < n; ++k) scratch[k] = a[order[k]];
  a.swap(scratch);  // swaps buffers, no allocation
}

}  // namespace

void reorder(State& s, int threads) {
  const auto& order = s.grid.order;
  gather(s.id, s.scratch_u32, order, threads);
  gather(s.role, s.scratch_role, order, threads);
  gather(s.pos, s.scratch_vec, order, threads);
  gather(s.vel, s.scratch_vec, order, threads);
  gather(s.anchor, s.scratch_vec, order, threads);
  gather(s.mass, s.scratch_real, order, threads);
  gather(s.mu, s.scratch_real, order, threads);
  gather(s.Kp, s.scratch_real, order, threads);
  gather(s.rho0, s.scratch_real, order, threads);
  gather(s.Ka, s.scratch_real, order, threads);
  // rho, pressure and force are recomputed before they are read again.
  const std::int64_t n = s.size();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    s.index_of_id[s.id[i]] = std::uint32_t(i);
    s.grid.x[i] = s.pos[i].x;
    s.grid.y[i] = s.pos[i].y;
    s.grid.z[i] = s.pos[i].z;
  }
}

}  // namespace dentsph::stages
