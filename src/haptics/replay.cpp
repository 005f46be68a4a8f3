// Deterministic replay: the recorded tool pose of every step, keyed by step, not wall time, into a
// Simulation on any backend.
#include "dentsph/haptics/replay.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dentsph/dispense.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/tools.hpp"

namespace dentsph {

EventSample tool_switch_event(std::uint64_t step, const std::string& name) {
  const std::vector<std::string>& names = instrument_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw std::invalid_argument(fmt::format("unknown tool \"{}\"; known: {}", name, fmt::join(names, ", ")));
  return {step, kToolSwitch + std::uint32_t(it - names.begin())};
}

std::vector<Vec3> replay_steps(const Scene& scene, const Recording& r, int threads, Backend backend, State* final_state,
                               const std::function<void(const State&, const EventSample&)>& on_event,
                               RunSummary* summary) {
  // The recorded session ran whatever its time step; a replay repeats it, diverging or not.
  Simulation sim(scene, {backend, threads, true});
  const State& state = sim.state();
  std::vector<Vec3> forces;
  forces.reserve(r.steps.size());
  std::size_t next_event = 0;
  const real volume = increment_volume_or_default(scene, r.dispense_volume);
  const IncrementPaste paste = scene_paste(scene);
  for (const StepSample& s : r.steps) {
    if (s.step != state.steps)
      throw std::runtime_error(fmt::format("recording: step {} follows step {}: the steps must be consecutive from 0",
                                           s.step, state.steps));
    for (; next_event < r.events.size() && r.events[next_event].step == s.step; ++next_event) {
      const std::uint32_t i = r.events[next_event].index;
      if (i == kButtonIncrement) {
        sim.dispense(volume, paste);
        if (on_event) on_event(sim.synced(), r.events[next_event]);
        continue;
      }
      if (i == kLightToggle) {
        sim.toggle_light();
        if (on_event) on_event(sim.synced(), r.events[next_event]);
        continue;
      }
      if (i >= kToolSwitch) {
        const std::vector<std::string>& names = instrument_names();
        if (i - kToolSwitch >= names.size())
          throw std::runtime_error(fmt::format("recording: event {} switches to instrument {}, but there are {}: "
                                               "replay with the version that recorded it", i, i - kToolSwitch, names.size()));
        sim.switch_instrument(names[i - kToolSwitch]);
        if (on_event) on_event(sim.synced(), r.events[next_event]);
        continue;
      }
      if (i >= scene.events.size())
        throw std::runtime_error(fmt::format("recording: event {} does not exist in scene '{}' ({} events): "
                                             "replay into the scene that was recorded", i, scene.name, scene.events.size()));
      sim.apply_event(i);
      if (on_event) on_event(sim.synced(), r.events[next_event]);
    }
    sim.step(s.tool_pose);
    forces.push_back(state.tool_wrench.force);
  }
  if (final_state) *final_state = sim.synced();
  if (summary) *summary = sim.summary();
  return forces;
}

ReplayComparison compare_replay(const std::vector<Vec3>& f, const Recording& r, double rel) {
  if (f.size() != r.steps.size())
    throw std::invalid_argument(fmt::format("compare_replay: {} replayed steps against {} recorded", f.size(), r.steps.size()));
  ReplayComparison c;
  for (const StepSample& s : r.steps) c.peak = std::max(c.peak, double(norm(s.tool_force)));
  const double bound = rel * std::max(c.peak, double(kBackendParityForceFloor));
  for (std::size_t k = 0; k < f.size(); ++k) {
    const Vec3 d = f[k] - r.steps[k].tool_force;
    c.largest = std::max(c.largest, double(norm(d)));
    c.differ += !(f[k] == r.steps[k].tool_force);
    c.outside += !(std::abs(d.x) <= bound && std::abs(d.y) <= bound && std::abs(d.z) <= bound);
  }
  return c;
}

}  // namespace dentsph
