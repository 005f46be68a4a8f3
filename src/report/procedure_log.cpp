// The procedure's log and the increments' thickness (procedure_log.hpp).
#include "report/procedure_log.hpp"

#include <cmath>
#include <fstream>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/layer_thickness.hpp"
#include "dentsph/tools.hpp"

namespace dentsph::report {

namespace {

// Paste particles: moving, or set by the cure (now wall, still paste).
std::uint32_t material_count(const State& s) {
  std::uint32_t n = 0;
  for (std::uint32_t i = 0; i < s.size(); ++i) n += s.is_paste(i);
  return n;
}

}  // namespace

ProcedureLog::ProcedureLog(const State& initial) : ProcedureLog(material_count(initial)) {}

void ProcedureLog::applied(const State& state, const ProcedureEvent& event) {
  LoggedEvent e;
  e.step = state.steps;
  e.t_s = state.time;
  e.source = "procedure";
  const std::uint32_t now = material_count(state);
  if (event.kind == ProcedureEvent::Kind::dispense) {
    e.kind = "dispense";
    e.particles = std::int64_t(now) - std::int64_t(material_);
  } else if (event.kind == ProcedureEvent::Kind::cure) {
    e.kind = "cure";
  } else {
    e.kind = "switch_tool";
    e.tool = event.tool;
  }
  material_ = now;
  events_.push_back(e);
}

std::vector<IncrementThickness> ProcedureLog::thickness(const Scene& scene, const State& state) const {
  std::vector<IncrementThickness> out;
  if (!scene.tooth) return out;
  // Material in id order: the initial paste, then each increment's particles (ids are given in
  // the order particles are added, and removing the tool's keeps their order).
  std::vector<std::uint32_t> material;
  for (std::uint32_t id = 0; id < state.size(); ++id)
    if (state.is_paste(state.index_of_id[id])) material.push_back(state.index_of_id[id]);
  // Each increment's particles: logged with its event, or, where the log does not know them (an
  // increment of the device's button in a realtime session), counted from the state's increment
  // numbers (every dispense numbers its increment, in the order they came: CureState).
  std::vector<std::uint32_t> tagged;
  if (state.cure.increment.size() == state.size())
    for (std::uint32_t id = 0; id < state.size(); ++id) {
      const std::uint16_t k = state.cure.increment[id];
      if (k == 0) continue;
      if (tagged.size() < k) tagged.resize(k, 0);
      ++tagged[k - 1];
    }
  std::vector<std::uint32_t> counts;
  std::uint64_t total = initial_material_;
  for (const LoggedEvent& e : events_) {
    if (e.kind != "dispense") continue;
    const std::size_t k = counts.size();
    if (e.particles < 0 && k >= tagged.size()) return {};  // not known: no thickness
    counts.push_back(e.particles >= 0 ? std::uint32_t(e.particles) : tagged[k]);
    total += counts.back();
  }
  if (total != material.size()) return {};
  const ToothFrame& fr = scene.tooth->frame();
  const double s = scene.material_spacing > 0 ? scene.material_spacing : default_tooth_spacing;
  std::size_t next = initial_material_;
  for (std::size_t k = 0; k < counts.size(); ++k) {
    IncrementThickness t;
    t.index = int(k + 1);
    t.particles = counts[k];
    std::vector<Vec3> points;
    for (std::size_t q = next; q < next + counts[k]; ++q)
      if (is_finite(state.pos[material[q]])) points.push_back(state.pos[material[q]]);
    next += counts[k];
    const LayerThickness layer = layer_thickness(points, fr.z, s);
    t.median_mm = layer.median * 1e3;
    t.p90_mm = layer.p90 * 1e3;
    out.push_back(t);
  }
  return out;
}

namespace {

// A recorded event as the log notes it (particles unknown); none for an index the scene lacks.
std::optional<LoggedEvent> logged(const Scene& scene, const EventSample& r) {
  const std::vector<std::string>& names = instrument_names();
  LoggedEvent e;
  e.step = r.step;
  e.t_s = double(r.step) * scene.model.dt;
  if (r.index == kButtonIncrement) {
    e.kind = "dispense";
    e.source = "button";
  } else if (r.index == kLightToggle) {
    e.kind = "light";
    e.source = "button";
  } else if (r.index >= kToolSwitch) {
    e.kind = "switch_tool";
    e.source = "button";
    e.tool = r.index - kToolSwitch < names.size() ? names[r.index - kToolSwitch] : "unknown";
  } else if (r.index < scene.events.size()) {
    const ProcedureEvent& ev = scene.events[r.index];
    e.source = "procedure";
    e.kind = ev.kind == ProcedureEvent::Kind::dispense ? "dispense"
             : ev.kind == ProcedureEvent::Kind::cure   ? "cure"
                                                         : "switch_tool";
    e.tool = ev.tool;
  } else {
    return std::nullopt;
  }
  return e;
}

}  // namespace

void ProcedureLog::replayed(const Scene& scene, const State& state, const EventSample& event) {
  std::optional<LoggedEvent> e = logged(scene, event);
  const std::uint32_t now = material_count(state);
  if (!e) return;
  if (e->kind == "dispense") e->particles = std::int64_t(now) - std::int64_t(material_);
  material_ = now;
  events_.push_back(*e);
}

ProcedureLog log_of_recording(const Scene& scene, const Recording& recording) {
  std::uint32_t material = 0;
  for (const ParticleInit& p : scene.particles) material += p.role == Role::material;
  ProcedureLog log(material);
  for (const EventSample& r : recording.events)
    if (const std::optional<LoggedEvent> e = logged(scene, r)) log.add(*e);
  return log;
}

void write_procedure_json(const std::filesystem::path& file, const Scene& scene, const ProcedureLog& log,
                          const std::vector<IncrementThickness>& increments) {
  nlohmann::json j;
  j["dt_s"] = scene.model.dt;
  j["events"] = nlohmann::json::array();
  for (const LoggedEvent& e : log.events()) {
    nlohmann::json ev = {{"step", e.step}, {"t_s", e.t_s}, {"kind", e.kind}, {"source", e.source}};
    if (!e.tool.empty()) ev["tool"] = e.tool;
    if (e.particles >= 0) ev["particles"] = e.particles;
    j["events"].push_back(ev);
  }
  j["increments"] = nlohmann::json::array();
  for (const IncrementThickness& t : increments)
    j["increments"].push_back({{"index", t.index},
                               {"particles", t.particles},
                               {"thickness_median_mm", t.median_mm},
                               {"thickness_p90_mm", t.p90_mm}});
  std::ofstream out(file);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the procedure's log", file.string()));
}

}  // namespace dentsph::report
