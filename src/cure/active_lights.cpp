// Which curing light is on (include/dentsph/active_lights.hpp).
#include "dentsph/active_lights.hpp"

#include <algorithm>
#include <limits>

namespace dentsph {

ActiveLights::ActiveLights(const std::vector<ProcedureEvent>& events) {
  for (const ProcedureEvent& e : events)
    if (e.kind == ProcedureEvent::Kind::cure) spans_.push_back({e.t, e.t + e.duration, e.light});
}

std::optional<CuringLight> ActiveLights::at(real t) const {
  for (auto s = spans_.rbegin(); s != spans_.rend(); ++s)
    if (s->begin <= t && t < s->end) return s->light;
  return std::nullopt;
}

real ActiveLights::end() const {
  real e = 0;
  for (const Span& s : spans_) e = std::max(e, s.end);
  return e;
}

real ActiveLights::next_change(real t) const {
  real next = std::numeric_limits<real>::infinity();
  for (const Span& s : spans_) {
    if (s.begin > t) next = std::min(next, s.begin);
    if (s.end > t) next = std::min(next, s.end);
  }
  return next;
}

}  // namespace dentsph
