// Stage 2b: gather every per-particle array into cell order, so that the neighbour loops read
// memory in sequence; then refresh the id -> index map that bonds and callers use, the coordinate
// arrays the neighbour searches read, and the material cache (mu, Kp, rho0, Ka) from the Model's
// table by each particle's one-byte material index (the cure's parameters by id for paste it has
// changed): four arrays written in sequence instead of gathered. One parallel region for all of it: the arrays
// that share a scratch buffer take turns, separated by the barrier at the end of each loop.
#include "step/stages.hpp"

namespace dentsph::stages {

namespace {

// Inside a parallel region: every thread gathers its share, then one swaps the buffers (no
// allocation) while the others wait at the barrier that ends `single`.
template <class T>
void gather(std::vector<T>& a, std::vector<T>& scratch, const std::vector<std::uint32_t>& order) {
  const std::int64_t n = std::int64_t(a.size());
#pragma omp for schedule(static)
  for (std::int64_t k = 0; k < n; ++k) scratch[k] = a[order[k]];
#pragma omp single
  a.swap(scratch);
}

}  // namespace

void reorder(const Model& model, State& s, int threads, bool keep_pressure) {
  const auto& order = s.grid.order;
  const std::int64_t n = s.size();
  const MaterialTable& table = model.materials;
#pragma omp parallel num_threads(threads)
  {
    gather(s.id, s.scratch_u32, order);
    gather(s.role, s.scratch_role, order);
    gather(s.pos, s.scratch_vec, order);
    gather(s.vel, s.scratch_vec, order);
    gather(s.anchor, s.scratch_vec, order);
    gather(s.mass, s.scratch_real, order);
    gather(s.material, s.scratch_material, order);
    // A solver that starts each pressure solve from the last one keeps the pressure (the paper's step
    // recomputes its pressure before reading it). rho and force are recomputed before they are read again.
    if (keep_pressure) gather(s.pressure, s.scratch_real, order);
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      s.index_of_id[s.id[i]] = std::uint32_t(i);
      s.grid.x[i] = s.pos[i].x;
      s.grid.y[i] = s.pos[i].y;
      s.grid.z[i] = s.pos[i].z;
      const MaterialIndex mi = s.material[i];
      const Material& m = (mi & kCuredMaterial) ? s.cure.cured[s.id[i]] : table[mi];
      s.mu[i] = m.mu;
      s.Kp[i] = m.Kp;
      s.rho0[i] = m.rho0;
      s.Ka[i] = m.Ka;
    }
  }
  s.order_stamp = new_state_stamp();  // what a solver listed in the old order is stale
}

}  // namespace dentsph::stages
