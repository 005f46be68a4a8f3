// The particles and memory a scene asks for, counted as it is read and before each set of
// particles is made (dentsph/limits.hpp): a scene of ten large blocks, or of thousands of
// increments, is refused at the field that crosses a limit instead of growing until the machine
// runs out of memory.
#pragma once

#include <cstdint>
#include <string_view>

#include "dentsph/limits.hpp"
#include "dentsph/scene_reader.hpp"

namespace dentsph::scene {

class ParticleBudget {
 public:
  // For a model of `max_bonds` bonds per particle, with neighbour lists kept between steps when
  // `skin`; `memory_limit` in bytes.
  ParticleBudget(int max_bonds, bool skin, std::uint64_t memory_limit = limits::memory_limit_bytes());

  // Counts `held` more particles made now, of which `simulated` join the simulation (an
  // increment's candidate sites are held, its count simulated). Refuses, at field `key` of `at`
  // ("" for `at` itself), what brings the scene over limits::max_particles simulated,
  // limits::max_held_particles held, or the memory limit; `fix` completes the message.
  void add(const Reader& at, std::string_view key, double held, double simulated, std::string_view fix);

  std::uint64_t held() const { return held_; }
  std::uint64_t simulated() const { return simulated_; }

 private:
  int max_bonds_;
  bool skin_;
  std::uint64_t memory_limit_;
  std::uint64_t held_ = 0, simulated_ = 0;
};

// Refuses `events` (the array field "events" of `owner`) longer than limits::max_events.
void check_event_count(const Reader& owner, std::size_t events);

}  // namespace dentsph::scene
