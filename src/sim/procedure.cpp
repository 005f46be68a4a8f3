// Procedure events applied between steps (include/dentsph/scene.hpp).
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "dentsph/scene.hpp"
#include "dentsph/tools.hpp"

namespace dentsph {

namespace {

// The first event.count candidate sites that keep event.clearance from the material there. The
// material is hashed into cells of edge clearance, so each site looks at the 27 cells around its
// own: linear in the material and the sites instead of their product.
std::vector<ParticleInit> free_sites(const State& state, const ProcedureEvent& event) {
  const real c = event.clearance;
  std::vector<ParticleInit> ps;
  if (!(c > 0)) {
    for (const ParticleInit& site : event.particles)
      if (ps.size() < event.count) ps.push_back(site);
    return ps;
  }
  using Cell = std::array<std::int64_t, 3>;
  struct CellHash {
    std::size_t operator()(const Cell& k) const {
      return std::size_t(std::uint64_t(k[0]) * 73856093u ^ std::uint64_t(k[1]) * 19349663u ^
                         std::uint64_t(k[2]) * 83492791u);
    }
  };
  auto cell = [c](const Vec3& p) {
    return Cell{std::int64_t(std::floor(p.x / c)), std::int64_t(std::floor(p.y / c)), std::int64_t(std::floor(p.z / c))};
  };
  std::unordered_map<Cell, std::vector<Vec3>, CellHash> material;
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.role[i] == Role::material && is_finite(state.pos[i])) material[cell(state.pos[i])].push_back(state.pos[i]);
  auto free = [&](const Vec3& p) {
    const Cell k = cell(p);
    for (std::int64_t di = -1; di <= 1; ++di)
      for (std::int64_t dj = -1; dj <= 1; ++dj)
        for (std::int64_t dk = -1; dk <= 1; ++dk) {
          const auto it = material.find({k[0] + di, k[1] + dj, k[2] + dk});
          if (it == material.end()) continue;
          for (const Vec3& m : it->second)
            if (norm2(p - m) < c * c) return false;
        }
    return true;
  };
  for (const ParticleInit& site : event.particles) {
    if (ps.size() == event.count) break;
    if (free(site.pos)) ps.push_back(site);
  }
  return ps;
}

}  // namespace

void apply_event(const Scene& scene, State& state, const ProcedureEvent& event) {
  switch (event.kind) {
    case ProcedureEvent::Kind::dispense:
      state.add_particles(scene.model, event.count > 0 ? free_sites(state, event) : event.particles);
      return;
    case ProcedureEvent::Kind::switch_tool:
      replace_tool_particles(state, scene.model, event.particles);
      return;
  }
  throw std::logic_error("apply_event: unknown event kind");
}

}  // namespace dentsph
