#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

const char* role_name(Role r) {
  switch (r) {
    case Role::material: return "material";
    case Role::boundary: return "boundary";
    case Role::tool: return "tool";
  }
  return "unknown";
}

std::uint64_t new_state_stamp() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

std::uint32_t State::count(Role r) const {
  return std::uint32_t(std::count(role.begin(), role.end(), r));
}

namespace {

template <class T>
std::size_t bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace

std::uint64_t State::bonded_pairs() const {
  std::uint64_t both_sides = 0, to_boundary = 0;
  for (std::uint32_t i = 0; i < size(); ++i) {
    for (int b = 0; b < bonds.count(id[i]); ++b)
      (role[index_of_id[bonds.partner(id[i], b)]] == Role::boundary ? to_boundary : both_sides) += 1;
  }
  return both_sides / 2 + to_boundary;
}

void State::remove_particles(const Model& model, const std::vector<std::uint8_t>& remove) {
  const std::uint32_t n = size();
  if (remove.size() != n) throw std::invalid_argument("remove_particles: one flag per particle");
  // New ids: the kept particles in the order of their old ids.
  constexpr std::uint32_t gone = ~0u;
  std::vector<std::uint32_t> new_id(n, gone);
  std::uint32_t kept = 0;
  for (std::uint32_t old = 0; old < n; ++old)
    if (!remove[index_of_id[old]]) new_id[old] = kept++;
  // Bonds, re-keyed.
  BondStore rebuilt;
  rebuilt.resize(kept, model.max_bonds_per_particle);
  rebuilt.counters = bonds.counters;
  for (std::uint32_t old = 0; old < n; ++old) {
    if (new_id[old] == gone) continue;
    for (int b = 0; b < bonds.count(old); ++b)
      if (const std::uint32_t other = new_id[bonds.partner(old, b)]; other != gone) rebuilt.try_add(new_id[old], other);
  }
  bonds = std::move(rebuilt);
  cure.compact(new_id, kept);
  if (!viscous_pressure.empty()) {  // one by id (add_particles keeps it so)
    std::vector<real> kept_pressure(kept, 0);
    for (std::uint32_t old = 0; old < n; ++old)
      if (new_id[old] != gone) kept_pressure[new_id[old]] = viscous_pressure[old];
    viscous_pressure = std::move(kept_pressure);
  }
  // Compact every per-particle array in index order.
  auto compact = [&](auto& v) {
    std::size_t k = 0;
    for (std::uint32_t i = 0; i < n; ++i)
      if (!remove[i]) v[k++] = v[i];
    v.resize(kept);
  };
  compact(id);
  for (std::uint32_t& x : id) x = new_id[x];
  compact(role);
  for (auto* v : {&pos, &vel, &anchor, &force}) compact(*v);
  compact(material);
  for (auto* v : {&mass, &mu, &Kp, &rho0, &Ka, &rho, &pressure, &volume}) compact(*v);
  size_by_id_and_scratch(model, kept);
}

void State::size_by_id_and_scratch(const Model& model, std::uint32_t n) {
  // Ids are dense: index_of_id covers [0, n).
  index_of_id.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) index_of_id[id[i]] = i;
  bonds.resize(n, model.max_bonds_per_particle);
  rho_static.assign(n, 0);
  rho_static_valid = false;  // the walls may have changed
  grid.key.resize(n);
  grid.order.resize(n);
  grid.bucket_start.assign(2 * std::size_t(model.grid.cell_count()) + 1, 0);
  grid.bucket_fill.assign(2 * std::size_t(model.grid.cell_count()), 0);
  grid.x.resize(n);
  grid.y.resize(n);
  grid.z.resize(n);
  grid.neighbours.resize(std::size_t(n) * GridIndex::kNeighbourStride);
  grid.neighbour_count.resize(n);
  // The within-h part of the lists, and the positions at the last build, serve the steps that keep
  // their lists (a skin) alone: without one every list is rebuilt and is itself within h.
  grid.keep_lists = model.neighbour_skin > 0;
  const std::size_t kept = grid.keep_lists ? n : 0;
  grid.within.resize(kept * GridIndex::kNeighbourStride);
  grid.within.shrink_to_fit();
  grid.within_count.resize(kept);
  grid.within_count.shrink_to_fit();
  grid.pos_at_build.resize(kept);
  grid.pos_at_build.shrink_to_fit();
  grid.lists_valid = false;
  grid.pair_data.resize(n);
  scratch_vec.resize(n);
  scratch_real.resize(n);
  scratch_u32.resize(n);
  scratch_role.resize(n);
  scratch_material.resize(n);
  layout_stamp = order_stamp = new_state_stamp();
}

std::size_t State::bytes_per_particle() const {
  if (size() == 0) return 0;
  const std::size_t total = bytes(id) + bytes(role) + bytes(pos) + bytes(vel) + bytes(mass) + bytes(material) + bytes(mu) + bytes(Kp) +
                            bytes(rho0) + bytes(Ka) + bytes(anchor) + bytes(rho) + bytes(pressure) + bytes(volume) +
                            bytes(force) + bytes(index_of_id) + bytes(rho_static) + bytes(viscous_pressure) + bonds.bytes() + cure.bytes() * size() + bytes(grid.key) +
                            bytes(grid.order) + bytes(grid.x) + bytes(grid.y) + bytes(grid.z) + bytes(grid.neighbours) + bytes(grid.neighbour_count) + bytes(grid.within) + bytes(grid.within_count) + bytes(grid.pos_at_build) + bytes(grid.pair_data) + bytes(scratch_vec) +
                            bytes(scratch_real) + bytes(scratch_u32) + bytes(scratch_role) + bytes(scratch_material);
  return total / size();
}

void State::refresh_materials(const Model& model) {
  const MaterialTable& table = model.materials;
  for (std::uint32_t i = 0; i < size(); ++i) {
    const Material& m = (material[i] & kCuredMaterial) ? cure.cured[id[i]] : table[material[i]];
    mu[i] = m.mu;
    Kp[i] = m.Kp;
    rho0[i] = m.rho0;
    Ka[i] = m.Ka;
  }
}

void State::add_particles(Model& model, const std::vector<ParticleInit>& particles) {
  for (const ParticleInit& p : particles)
    if (p.material_index == kNoMaterial && p.mass > 0 && p.material.rho0 > 0) model.materials.intern(p.material);
  add_particles(std::as_const(model), particles);
}

void State::add_particles(const Model& model, const std::vector<ParticleInit>& particles) {
  // Checked before anything is added, so that a refused call leaves the state as it was.
  const MaterialTable& table = model.materials;
  std::vector<MaterialIndex> index(particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const ParticleInit& p = particles[k];
    if (p.material_index != kNoMaterial) {
      if (p.material_index >= table.size())
        throw std::invalid_argument(fmt::format("add_particles: particle {} names material {}, but the Model has {} materials",
                                                k, int(p.material_index), table.size()));
      index[k] = p.material_index;
    } else if (const auto found = table.find(p.material)) {
      index[k] = *found;
    } else {
      throw std::invalid_argument(fmt::format(
          "add_particles: particle {}'s material (mu {}, Kp {}, rho0 {}, Ka {}) is not in the Model's material table; "
          "add it (Model::materials.add) or name its entry (ParticleInit::material_index)",
          k, p.material.mu, p.material.Kp, p.material.rho0, p.material.Ka));
    }
    if (!(p.mass > 0) || !(table[index[k]].rho0 > 0))
      throw std::invalid_argument("add_particles: a particle needs a positive mass and rest density");
  }
  const std::uint32_t n = size() + std::uint32_t(particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k) {
    ParticleInit p = particles[k];
    p.material = table[index[k]];  // the table's values (what the cure starts from)
    material.push_back(index[k]);
    const std::uint32_t i = std::uint32_t(pos.size());
    id.push_back(i);
    role.push_back(p.role);
    anchor.push_back(p.role == Role::tool ? p.pos : Vec3{});
    pos.push_back(p.role == Role::tool ? tool_pose_applied.apply(p.pos) : p.pos);
    vel.push_back(p.role == Role::material ? p.vel : Vec3{});
    mass.push_back(p.mass);
    mu.push_back(p.material.mu);
    Kp.push_back(p.material.Kp);
    rho0.push_back(p.material.rho0);
    Ka.push_back(p.material.Ka);
    rho.push_back(p.material.rho0);
    pressure.push_back(0);
    volume.push_back(p.mass / p.material.rho0);
    force.push_back({});
    cure.append(p, time);
    if (!viscous_pressure.empty()) viscous_pressure.push_back(0);  // a new particle has none yet
  }
  size_by_id_and_scratch(model, n);
}

}  // namespace dentsph
