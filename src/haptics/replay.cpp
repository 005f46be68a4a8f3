// Deterministic replay: the recorded tool pose of every step, keyed by step, not wall time.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dentsph/dispense.hpp"
#include "dentsph/haptics/recording.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/step.hpp"
#include "dentsph/tools.hpp"

namespace dentsph {

EventSample tool_switch_event(std::uint64_t step, const std::string& name) {
  const std::vector<std::string>& names = instrument_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end())
    throw std::invalid_argument(fmt::format("unknown tool \"{}\"; known: {}", name, fmt::join(names, ", ")));
  return {step, kToolSwitch + std::uint32_t(it - names.begin())};
}

std::vector<Vec3> replay_steps(const Scene& scene, const Recording& r, int threads, State* final_state,
                               const std::function<void(const State&, const EventSample&)>& on_event) {
  State state = make_state(scene);
  std::vector<Vec3> forces;
  forces.reserve(r.steps.size());
  std::size_t next_event = 0;
  const real volume = increment_volume_or_default(scene, r.dispense_volume);
  for (const StepSample& s : r.steps) {
    if (s.step != state.steps)
      throw std::runtime_error(fmt::format("recording: step {} follows step {}: the steps must be consecutive from 0",
                                           s.step, state.steps));
    for (; next_event < r.events.size() && r.events[next_event].step == s.step; ++next_event) {
      const std::uint32_t i = r.events[next_event].index;
      if (i == kButtonIncrement) {
        dispense_increment(scene, state, volume, increment_axis(scene), scene_paste(scene));
        if (on_event) on_event(state, r.events[next_event]);
        continue;
      }
      if (i >= kToolSwitch) {
        const std::vector<std::string>& names = instrument_names();
        if (i - kToolSwitch >= names.size())
          throw std::runtime_error(fmt::format("recording: event {} switches to instrument {}, but there are {}: "
                                               "replay with the version that recorded it", i, i - kToolSwitch, names.size()));
        switch_instrument(scene, state, names[i - kToolSwitch]);
        if (on_event) on_event(state, r.events[next_event]);
        continue;
      }
      if (i >= scene.events.size())
        throw std::runtime_error(fmt::format("recording: event {} does not exist in scene '{}' ({} events): "
                                             "replay into the scene that was recorded", i, scene.name, scene.events.size()));
      apply_event(scene, state, scene.events[i]);
      if (on_event) on_event(state, r.events[next_event]);
    }
    state.tool_pose = s.tool_pose;
    step(scene.model, state, StepOptions{threads, nullptr});
    forces.push_back(state.tool_wrench.force);
  }
  if (final_state) *final_state = std::move(state);
  return forces;
}

}  // namespace dentsph
