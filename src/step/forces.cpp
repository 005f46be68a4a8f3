// Stage 5: force densities over the neighbours within h that the density pass listed (pressure,
// viscosity) and over the particle's bond list (adhesion, which reaches partners up to B > h). Gravity is added in
// integration, so `force` is the internal force density the tool wrench is made of. Each moving
// particle also updates its own bond list here, from the distances this pass computes anyway.
#include <algorithm>

#include "bonds/hysteresis.hpp"
#include "step/grid.hpp"
#include "step/side.hpp"
#include "step/stages.hpp"

namespace dentsph::stages {

namespace {

// Neighbours of one particle found so far: candidates of the 27 cells are filtered without
// branches (every candidate is written, the count advances only for those within h), then the
// pair terms run over the short list. Flushed whenever it could overflow.
struct NeighbourBuffer {
  static constexpr std::uint32_t capacity = 256;
  std::uint32_t j[capacity];
  real r2[capacity];
  std::uint32_t n = 0;
};

// Adhesion on moving particle i from its bonded partners; breaks the bonds stretched past B.
Vec3 bonded_adhesion(const Model& model, State& s, std::uint32_t i, const pair::Side& si, const Sides& sides,
                     bonds::Events& ev) {
  const bond_rules::Thresholds t = bond_rules::thresholds(model.adhesion);
  const std::uint32_t id = s.id[i];
  Vec3 f;
  for (int b = s.bonds.count(id) - 1; b >= 0; --b) {
    const std::uint32_t other = s.bonds.partner(id, b);
    const std::uint32_t j = s.index_of_id[other];
    const Vec3 d = si.pos - sides.pos(j);
    const real r2 = norm2(d);
    if (bond_rules::stretched(r2, t)) {
      bonds::count_break(s, i, j, ev);
      s.bonds.remove_at(id, b);
    } else {
      f += pair::adhesion(si, sides[j], d, std::sqrt(r2), model.adhesion, model.kernel);
    }
  }
  return f;
}

// Force density on moving particle i; updates i's bonds (events into ev).
Vec3 force_on(const Model& model, State& s, std::uint32_t i, bonds::Events& ev) {
  const KernelCoeffs& k = model.kernel;
  const GridIndex& g = s.grid;
  const Sides sides(s);
  const pair::Side si = sides[i];
  const bond_rules::Thresholds t = bond_rules::thresholds(model.adhesion);
  // Bonds first: one pass breaks those stretched past B and adds the adhesion of the rest. Bonds
  // formed below (r < A) add nothing this step: W_adh is zero below A.
  Vec3 f = bonded_adhesion(model, s, i, si, sides, ev);
  // The density pass kept the neighbours within h (unless the list overflowed). Pairs close enough
  // to bond are noted and bonded after the pair terms (in the same order), so that the loop of
  // pair terms makes no call.
  if (g.neighbour_count[i] <= GridIndex::kNeighbourCapacity) {
    // Lists rebuilt every step hold exactly the pairs within h.
    const bool kept = g.keep_lists;
    const std::uint32_t* list = (kept ? g.within : g.neighbours).data() + std::size_t(i) * GridIndex::kNeighbourStride;
    const std::uint32_t count = kept ? g.within_count[i] : g.neighbour_count[i];
    std::uint32_t close[GridIndex::kNeighbourStride];
    std::uint32_t n_close = 0;
    for (std::uint32_t q = 0; q < count; ++q) {
      const std::uint32_t j = list[q];
      const Vec3 d = si.pos - sides.pos(j);
      const real r2 = norm2(d);
      f += pair::pressure_viscosity(si, sides[j], d, std::sqrt(r2), k);
      close[n_close] = j;
      n_close += bond_rules::close_enough(r2, t) ? 1 : 0;
    }
    bonds::form_bonds(s, i, close, n_close, ev);
    return f;
  }
  // Otherwise search the grid (over the positions themselves: the coordinate arrays are as old as
  // the lists): candidates filtered without branches into a short buffer, pairs closer than A
  // bonded after each buffer's pair terms (A < h: every pair to bond is here).
  NeighbourBuffer nb;
  auto flush = [&] {
    std::uint32_t close[NeighbourBuffer::capacity];
    std::uint32_t n_close = 0;
    for (std::uint32_t q = 0; q < nb.n; ++q) {
      const std::uint32_t j = nb.j[q];
      if (j == i) continue;
      const Vec3 d = si.pos - sides.pos(j);
      f += pair::pressure_viscosity(si, sides[j], d, std::sqrt(nb.r2[q]), k);
      close[n_close] = j;
      n_close += bond_rules::close_enough(nb.r2[q], t) ? 1 : 0;
    }
    bonds::form_bonds(s, i, close, n_close, ev);
    nb.n = 0;
  };
  grid::for_each_neighbour_range(model.grid, g, si.pos, grid::Visit::all, [&](std::uint32_t b, std::uint32_t e) {
    while (b < e) {
      const std::uint32_t end = std::min(e, b + (NeighbourBuffer::capacity - nb.n));
      for (std::uint32_t j = b; j < end; ++j) {
        const Vec3 d = si.pos - sides.pos(j);
        const real dx = d.x, dy = d.y, dz = d.z;
        const real r2 = dx * dx + dy * dy + dz * dz;
        nb.j[nb.n] = j;
        nb.r2[nb.n] = r2;
        nb.n += r2 < k.h2 ? 1 : 0;
      }
      b = end;
      if (nb.n == NeighbourBuffer::capacity) flush();
    }
  });
  flush();
  return f;
}

}  // namespace

void compute_forces(const Model& model, State& s, int threads) {
  constexpr std::int64_t kBondPrefetch = 8;
  const std::int64_t n = s.size();
  // Bond events summed by an integer reduction (exact in any order). Not a named critical
  // section: libomp 14 under ThreadSanitizer crashes in one entered from a thread it did not
  // create (the haptic runtime's and the viewer's simulation threads).
  // Static halves: each thread keeps the particles (and caches) it had in the density pass.
  // Chunks of 64 handed out dynamically balanced the work better but measured slower.
  std::uint64_t formed = 0, broken = 0, overflowed = 0;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : formed, broken, overflowed)
  for (std::int64_t i = 0; i < n; ++i) {
    // The bond lists are kept by id, so in cell order they are read at scattered places: fetched
    // a few particles ahead, they are in cache when their particle comes.
    if (i + kBondPrefetch < n) __builtin_prefetch(s.bonds.list(s.id[i + kBondPrefetch]));
    bonds::Events ev;
    s.force[i] = s.role[i] == Role::boundary ? Vec3{} : force_on(model, s, std::uint32_t(i), ev);  // static: unused
    formed += ev.formed;
    broken += ev.broken;
    overflowed += ev.overflowed;
  }
  bonds::Events total;
  total.formed = formed;
  total.broken = broken;
  total.overflowed = overflowed;
  bonds::record(s, total);
}

}  // namespace dentsph::stages
