// The per-particle cure state kept by id (include/dentsph/cure_state.hpp).
#include "dentsph/cure_state.hpp"

#include <limits>

#include "dentsph/state.hpp"

namespace dentsph {

namespace {

template <class T>
std::size_t capacity_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace

void CureState::append(const ParticleInit& p, real time) {
  alpha.push_back(0);
  dose.push_back(0);
  irradiance.push_back(0);
  increment.push_back(0);
  curable.push_back(p.role == Role::material ? 1 : 0);
  rigid.push_back(0);
  mixed_at.push_back(time);
  mu0.push_back(p.material.mu);
  Kp0.push_back(p.material.Kp);
  rho00.push_back(p.material.rho0);
  Ka0.push_back(p.material.Ka);
  gel_pos.push_back({});
  if (!cured.empty()) cured.push_back(p.material);
}

void CureState::set_cured(std::uint32_t id, const Material& m) {
  if (cured.size() != alpha.size()) cured.resize(alpha.size());
  cured[id] = m;
}

void CureState::compact(const std::vector<std::uint32_t>& new_id, std::uint32_t kept) {
  auto rekey = [&](auto& v) {
    auto old = v;
    v.resize(kept);
    for (std::size_t id = 0; id < new_id.size(); ++id)
      if (new_id[id] != ~0u) v[new_id[id]] = old[id];
  };
  rekey(alpha), rekey(dose), rekey(irradiance), rekey(increment), rekey(curable), rekey(rigid);
  rekey(mixed_at), rekey(mu0), rekey(Kp0), rekey(rho00), rekey(Ka0), rekey(gel_pos);
  if (!cured.empty()) rekey(cured);
  // The lit list names old ids: the next cure call makes a pass, which lists the lit paste anew.
  lit_ids.clear();
  lit_irradiance.clear();
  next_pass = -std::numeric_limits<real>::infinity();
}

std::uint16_t CureState::begin_increment(std::uint32_t first_id, std::uint32_t count) {
  const std::uint16_t k = ++increments;
  for (std::uint32_t id = first_id; id < first_id + count && id < particles(); ++id)
    if (curable[id]) increment[id] = k;
  return k;
}

std::size_t CureState::bytes() const {
  if (particles() == 0) return 0;
  const std::size_t total = capacity_bytes(alpha) + capacity_bytes(dose) + capacity_bytes(irradiance) +
                            capacity_bytes(increment) + capacity_bytes(curable) + capacity_bytes(rigid) +
                            capacity_bytes(mixed_at) + capacity_bytes(mu0) + capacity_bytes(Kp0) +
                            capacity_bytes(rho00) + capacity_bytes(Ka0) + capacity_bytes(cured) + capacity_bytes(gel_pos) + capacity_bytes(beam_x) + capacity_bytes(beam_y) +
                            capacity_bytes(beam_z);
  return total / particles();
}

}  // namespace dentsph
