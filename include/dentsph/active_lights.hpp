// Which curing light is on at a time: the scene's cure events (a light on from t for a duration),
// looked up by the run loops before each cure update (docs/architecture.md, "Curing"). Built once
// from the scene; at() neither allocates nor blocks.
#pragma once

#include <optional>
#include <vector>

#include "dentsph/curing_light.hpp"
#include "dentsph/scene.hpp"

namespace dentsph {

class ActiveLights {
 public:
  ActiveLights() = default;
  explicit ActiveLights(const std::vector<ProcedureEvent>& events);

  // The light on at time t: that of the cure event with t0 <= t < t0 + duration, the latest begun
  // when several are on at once; none when no event's light is on.
  std::optional<CuringLight> at(real t) const;
  // Whether the scene has any cure event (a loop without one never needs the light transport).
  bool empty() const { return spans_.empty(); }
  // When the last light goes off (s); 0 without cure events.
  real end() const;
  // The first time after t when a light comes on or goes off (s); infinity when none does.
  real next_change(real t) const;

 private:
  struct Span {
    real begin = 0, end = 0;
    CuringLight light;
  };
  std::vector<Span> spans_;  // in the events' (time) order
};

}  // namespace dentsph
