// The procedure as it took place in a run, for the report: each event (an increment dispensed by
// the procedure, the device's button or the viewer, an instrument taken up) at its step and
// time, the particles each increment added, and, measured at the end, how thick each increment
// lies in the cavity. Written as procedure.json in the run folder (docs/report.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "dentsph/haptics/recording.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/state.hpp"

namespace dentsph::report {

struct LoggedEvent {
  std::uint64_t step = 0;   // applied before this step
  double t_s = 0;           // s, simulated (step times dt)
  std::string kind;         // "dispense", "switch_tool", "cure" (a procedure's curing light on) or
                            // "light" (the device's button 2: the light on or off)
  std::string source;       // "procedure", "button" (the device's button or the viewer's D key)
  std::string tool;         // switch_tool: the instrument
  std::int64_t particles = -1;  // dispense: particles added; -1 when not known
};

// Thickness of one increment at the end of a run, along the tooth's long axis: its particles
// binned in columns of two spacings across the axis, each column's volume (its particles times
// spacing^3) over its area (4 spacing^2), so that a particle drawn up a wall or by the instrument
// adds a quarter spacing, not its height; the median and the 90th percentile over the columns.
struct IncrementThickness {
  int index = 0;                 // 1, 2, ... in the order dispensed
  std::uint32_t particles = 0;
  double median_mm = 0, p90_mm = 0;
};

class ProcedureLog {
 public:
  // From the run's initial state (its material is not an increment of the procedure), or the
  // number of its material particles.
  explicit ProcedureLog(const State& initial);
  explicit ProcedureLog(std::uint32_t initial_material) : initial_material_(initial_material), material_(initial_material) {}
  // After `event` was applied to `state` (between steps).
  void applied(const State& state, const ProcedureEvent& event);
  // The same for what a session asked for itself (a recording's events, where the particle
  // counts are not known: the increments' thickness is not measured then).
  void add(const LoggedEvent& e) { events_.push_back(e); }
  // After a recorded event (a realtime session's, replayed) was applied to `state`: its kind from
  // the recording, its particles from the state.
  void replayed(const Scene& scene, const State& state, const EventSample& event);

  const std::vector<LoggedEvent>& events() const { return events_; }
  // Each increment's thickness in `state` (the end of the run), when every increment's
  // particles are known; empty otherwise, or without a tooth.
  std::vector<IncrementThickness> thickness(const Scene& scene, const State& state) const;

 private:
  std::uint32_t initial_material_ = 0, material_ = 0;
  std::vector<LoggedEvent> events_;
};

// The events of a realtime session's recording (steps, scene events by index, button
// increments, instrument switches), particle counts unknown.
ProcedureLog log_of_recording(const Scene& scene, const Recording& recording);

// procedure.json: {"dt_s", "events": [...], "increments": [...]} (docs/report.md).
void write_procedure_json(const std::filesystem::path& file, const Scene& scene, const ProcedureLog& log,
                          const std::vector<IncrementThickness>& increments);

}  // namespace dentsph::report
