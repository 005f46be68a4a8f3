// Stage 3: rho_i = sum_j m_j W_poly6(r_ij) over all roles, self included (docs/model.md, "One step"; the paper's
// eq. 6 has a stray minus sign). Boundary particles never move, so the part of a boundary
// particle's density that comes from other boundary particles is computed once
// (compute_static_density) and each step adds only its moving neighbours, from its list.
#include <algorithm>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "physics/kernels.hpp"
#include "physics/pair_terms.hpp"
#include "step/grid.hpp"
#include "step/pressure_stage.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

namespace {

// What the density loops read: the coordinate arrays of the grid (valid after a reorder only) and
// the masses, and particle i's position.
struct Arrays {
  const real *x, *y, *z, *m;
  real xi, yi, zi, h2;
  Arrays(const Model& model, const State& s, std::int64_t i)
      : x(s.grid.x.data()), y(s.grid.y.data()), z(s.grid.z.data()), m(s.mass.data()), xi(s.pos[i].x),
        yi(s.pos[i].y), zi(s.pos[i].z), h2(model.kernel.h2) {}
};

// Whether this step sorted the particles, so that the grid's coordinate arrays hold the current
// positions (a step that keeps its lists reads the positions themselves).
enum class Coords { sorted, moved };

// max(0, t) without a branch (0 for NaN, as std::max(0, t)). Where its result also decides which
// entries to keep, g++ turned std::max into a branch, mispredicted for every pair in the skin.
inline real clamp_at_zero(real t) {
#if defined(__SSE2__)
  return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(t), _mm_setzero_pd()));
#else
  return std::max<real>(0, t);
#endif
}

// Sum of m_j W(r_ij) over the particles of the 27 cells around i of the kind `visit` asks for.
real density_sum(const Model& model, const State& s, std::int64_t i, grid::Visit visit, Coords coords) {
  const Arrays a(model, s, i);
  const Vec3* pos = s.pos.data();
  real sum = 0;  // of m_j (h^2 - r^2)^3 over r < h; the kernel's constant is applied once
  grid::for_each_neighbour_range(model.grid, s.grid, s.pos[i], visit, [&](std::uint32_t b, std::uint32_t e) {
    // Branch-free so that the compiler vectorises it: pairs beyond h contribute max(0, .) = 0.
    if (coords == Coords::sorted) {
      for (std::uint32_t j = b; j < e; ++j) {
        const real dx = a.xi - a.x[j], dy = a.yi - a.y[j], dz = a.zi - a.z[j];
        const real w = std::max<real>(0, a.h2 - (dx * dx + dy * dy + dz * dz));
        sum += kernels::poly6_mass_term(a.m[j], w);
      }
    } else {
      for (std::uint32_t j = b; j < e; ++j) {
        const real dx = a.xi - pos[j].x, dy = a.yi - pos[j].y, dz = a.zi - pos[j].z;
        const real w = std::max<real>(0, a.h2 - (dx * dx + dy * dy + dz * dz));
        sum += kernels::poly6_mass_term(a.m[j], w);
      }
    }
  });
  return model.kernel.poly6 * sum;
}

// Which neighbours particle i lists: a moving particle all within reach, a boundary particle the
// moving ones (its boundary part is static, rho_static).
grid::Visit listed(const State& s, std::int64_t i) {
  return s.role[i] == Role::boundary ? grid::Visit::moving : grid::Visit::all;
}

// The density of particle i from a search of its cells: where its list overflowed, and for a
// boundary particle without a skin (its list would serve one step only).
real density_by_search(const Model& model, const State& s, std::int64_t i, Coords coords) {
  const real own = s.role[i] == Role::boundary ? s.rho_static[s.id[i]] : 0;
  return own + density_sum(model, s, i, listed(s, i), coords);
}

// Sum of m_j w_q^3 over the entries q of a list, w_q = max(0, h^2 - r^2) from `w_at(q, j)`, in
// four running sums (entry q into sum q mod 4) so that successive additions do not wait for one
// another; the same order whichever thread takes the particle. `keep(j, w)` sees every entry.
template <class W, class Keep>
real list_sum(const std::uint32_t* list, std::uint32_t count, const real* m, W&& w_at, Keep&& keep) {
  real part[4] = {0, 0, 0, 0};
  std::uint32_t q = 0;
  for (; q + 4 <= count; q += 4)
    for (std::uint32_t l = 0; l < 4; ++l) {
      const std::uint32_t j = list[q + l];
      const real w = w_at(q + l, j);
      part[l] += kernels::poly6_mass_term(m[j], w);
      keep(j, w);
    }
  for (; q < count; ++q) {
    const std::uint32_t j = list[q];
    const real w = w_at(q, j);
    part[0] += kernels::poly6_mass_term(m[j], w);
    keep(j, w);
  }
  return (part[0] + part[1]) + (part[2] + part[3]);
}

// Density of particle i over its neighbour list (pairs beyond h add nothing), and its own part:
// itself for a moving particle, the static boundary around it for a boundary particle; w_at(q, j)
// gives entry q's max(0, h^2 - r^2). With a skin, a moving particle also keeps the entries within
// h, in list order, for the force pass (without one, every entry is within h and the force pass
// reads the list itself).
template <class W>
real density_over_list(const Model& model, State& s, std::int64_t i, W&& w_at) {
  GridIndex& g = s.grid;
  const bool boundary = s.role[i] == Role::boundary;
  const real h2 = model.kernel.h2;
  const std::uint32_t* list = g.neighbours.data() + std::size_t(i) * GridIndex::kNeighbourStride;
  const std::uint32_t count = g.neighbour_count[i];
  const real* m = s.mass.data();
  real sum = boundary ? 0 : m[i] * h2 * h2 * h2;
  if (boundary || !g.keep_lists) {
    sum += list_sum(list, count, m, w_at, [](std::uint32_t, real) {});
  } else {
    // Branch-free: every entry is written, the count advances for those within h.
    std::uint32_t* within = g.within.data() + std::size_t(i) * GridIndex::kNeighbourStride;
    std::uint32_t kept = 0;
    sum += list_sum(list, count, m, w_at, [&](std::uint32_t j, real w) {
      within[kept] = j;
      kept += w > 0 ? 1 : 0;
    });
    g.within_count[i] = std::uint16_t(kept);
  }
  return (boundary ? s.rho_static[s.id[i]] : 0) + model.kernel.poly6 * sum;
}

// The density of particle i over the list it keeps between rebuilds, at the current positions.
real density_from_list(const Model& model, State& s, std::int64_t i) {
  if (s.grid.neighbour_count[i] > GridIndex::kNeighbourCapacity) return density_by_search(model, s, i, Coords::moved);
  const Arrays a(model, s, i);
  const Vec3* pos = s.pos.data();
  return density_over_list(model, s, i, [&](std::uint32_t, std::uint32_t j) {
    const real dx = a.xi - pos[j].x, dy = a.yi - pos[j].y, dz = a.zi - pos[j].z;
    return clamp_at_zero(a.h2 - (dx * dx + dy * dy + dz * dz));
  });
}

// The density of particle i, over its cells, and its list of neighbours within h + skin (self
// excluded) for the force pass and the steps until the next rebuild. The search keeps each listed
// entry's r^2 for the density sum.
real density_and_neighbours(const Model& model, State& s, std::int64_t i) {
  GridIndex& g = s.grid;
  const Arrays a(model, s, i);
  const real reach = model.kernel.h + model.neighbour_skin, reach2 = reach * reach;
  constexpr std::uint32_t cap = GridIndex::kNeighbourCapacity;
  std::uint32_t* list = g.neighbours.data() + std::size_t(i) * GridIndex::kNeighbourStride;
  real r2_at[cap + 1];
  std::uint32_t count = 0;
  grid::for_each_neighbour_range(model.grid, g, s.pos[i], listed(s, i), [&](std::uint32_t b, std::uint32_t e) {
    // Branch-free filter: every candidate is written, at the count (at slot `cap`, scratch, once
    // the list is full), and the count advances for those within reach; past the capacity it
    // marks the overflow.
    for (std::uint32_t j = b; j < e; ++j) {
      const real dx = a.xi - a.x[j], dy = a.yi - a.y[j], dz = a.zi - a.z[j];
      const real r2 = dx * dx + dy * dy + dz * dz;
      const std::uint32_t within = (r2 < reach2) & (j != std::uint32_t(i));
      const std::uint32_t slot = count < cap ? count : cap;
      list[slot] = j;
      r2_at[slot] = r2;
      count += within;
    }
  });
  g.neighbour_count[i] = std::uint16_t(count > cap ? cap + 1 : count);
  if (count > cap) return density_by_search(model, s, i, Coords::sorted);
  return density_over_list(model, s, i, [&](std::uint32_t q, std::uint32_t) { return clamp_at_zero(a.h2 - r2_at[q]); });
}


// A boundary particle's density from the boundary alone with the cubic spline (the iisph solver's
// density_kernel "cubic"), self included as the solver's pair pass leaves it out.
real cubic_boundary_density(const Model& model, const State& s, std::int64_t i) {
  real sum = s.mass[i] * model.kernel.cubic;
  grid::for_each_neighbour_range(model.grid, s.grid, s.pos[i], grid::Visit::boundary, [&](std::uint32_t b, std::uint32_t e) {
    for (std::uint32_t j = b; j < e; ++j)
      if (j != std::uint32_t(i)) sum += s.mass[j] * kernels::cubic(norm(s.pos[i] - s.pos[j]), model.kernel);
  });
  return sum;
}

}  // namespace

void compute_static_density(const Model& model, State& s) {
  for (std::uint32_t i = 0; i < s.size(); ++i)
    s.rho_static[s.id[i]] = s.role[i] != Role::boundary ? 0
                            : model.kernel.cubic_density ? cubic_boundary_density(model, s, i)
                                                         : density_sum(model, s, i, grid::Visit::boundary, Coords::sorted);
  s.rho_static_valid = true;
}

void compute_density(const Model& model, State& s, int threads, bool build_lists) {
  if (!s.rho_static_valid) compute_static_density(model, s);  // after a reorder: added particles rebuild
  const std::int64_t n = s.size();
  constexpr std::int64_t kPrefetch = 8;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    // rho_static is kept by id, so in cell order it is read at scattered places: fetched ahead.
    if (i + kPrefetch < n) __builtin_prefetch(&s.rho_static[s.id[i + kPrefetch]]);
    // Without a skin a boundary particle's list would serve one step only: search directly.
    if (s.role[i] == Role::boundary && !s.grid.keep_lists)
      s.rho[i] = density_by_search(model, s, i, Coords::sorted);
    else
      s.rho[i] = build_lists ? density_and_neighbours(model, s, i) : density_from_list(model, s, i);
    pressure_of(s, i);  // 4. pressure: particle i's own density is all it needs
    s.grid.pair_data[i] = pair::side_of(s, std::uint32_t(i));
  }
}

}  // namespace dentsph::stages
