#include "scene/budget.hpp"

#include <fmt/format.h>

#include <string>

namespace dentsph::scene {

ParticleBudget::ParticleBudget(int max_bonds, bool skin, std::uint64_t memory_limit)
    : max_bonds_(max_bonds), skin_(skin), memory_limit_(memory_limit) {}

void ParticleBudget::add(const Reader& at, std::string_view key, double held, double simulated, std::string_view fix) {
  auto refuse = [&](const std::string& problem) {
    if (key.empty()) at.fail_here(problem, fix);
    at.fail(key, problem, fix);
  };
  const double sim_total = double(simulated_) + simulated, held_total = double(held_) + held;
  if (!(sim_total <= double(limits::max_particles)))
    refuse(fmt::format("brings the scene to {:.3g} particles in the simulation, over the limit of {} (README, "
                       "\"Resource limits\")",
                       sim_total, limits::max_particles));
  if (!(held_total <= double(limits::max_held_particles)))
    refuse(fmt::format("brings the particles held as the scene is read (its increments' candidate sites included) "
                       "to {:.3g}, over the limit of {} (README, \"Resource limits\")",
                       held_total, limits::max_held_particles));
  const std::string memory = limits::memory_problem(std::uint64_t(held_total), std::uint64_t(sim_total), max_bonds_,
                                                    skin_, memory_limit_);
  if (!memory.empty()) refuse(fmt::format("the scene {}", memory));
  held_ = std::uint64_t(held_total);
  simulated_ = std::uint64_t(sim_total);
}

void check_event_count(const Reader& owner, std::size_t events) {
  if (events > limits::max_events)
    owner.fail("events", fmt::format("{} events, over the limit of {} per file (README, \"Resource limits\")", events,
                                     limits::max_events),
               "split the procedure into files of fewer events; a filling takes a few increments");
}

}  // namespace dentsph::scene
