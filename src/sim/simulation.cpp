// The run core (simulation.hpp): the State, its Stepper and the bookkeeping around each step.
#include "dentsph/simulation.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "dentsph/cure_assessment.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/dispense.hpp"
#include "dentsph/paste_presets.hpp"
#include "dentsph/tools.hpp"

namespace dentsph {

Simulation::Simulation(const Scene& scene, const SimulationOptions& options)
    : scene_(scene), options_(options), model_(scene.model), state_(make_state(scene)),
      solver_(solver_properties(scene.model.solver)) {
  limits_ = check_time_step(scene, state_, options.allow_unstable);
  limits_.force = std::numeric_limits<real>::infinity();
  acoustic_violated_ = model_.dt > limits_.acoustic;
  viscous_violated_ = model_.dt > limits_.viscous;
  stepper_ = new_stepper();
  lights_ = ActiveLights(scene.events);
  // A light cures the paste; an amalgam sets by itself, light or none.
  if (!lights_.empty() || cure_material_preset(scene_paste_cure(scene)).self_setting) start_curing();
}

const State& Simulation::synced() {
  stepper_->sync_to_host(state_);
  return state_;
}

State& Simulation::edit() {
  stepper_->sync_to_host(state_);
  edited_ = true;
  return state_;
}

std::size_t Simulation::apply_due_events(const std::function<void(std::size_t)>& on_applied) {
  std::size_t applied = 0;
  while (next_event_ < scene_.events.size() && scene_.events[next_event_].t <= state_.time + 0.5 * model_.dt) {
    apply_event(next_event_);
    if (on_applied) on_applied(next_event_);  // after: the log counts the particles it added
    ++next_event_;
    ++applied;
  }
  return applied;
}

void Simulation::apply_event(std::size_t index) {
  dentsph::apply_event(scene_, edit(), scene_.events.at(index));
  ++events_applied_;
}

std::size_t Simulation::dispense(real volume, const IncrementPaste& paste) {
  return dispense_increment(scene_, edit(), volume, increment_axis(scene_), paste);
}

void Simulation::switch_instrument(const std::string& name) {
  (void)tool_by_name(name, increment_spacing(scene_), Solver::paper);  // an unknown name changes nothing
  dentsph::switch_instrument(scene_, edit(), name);
}

void Simulation::set_paste(const AdhesionParams& adhesion, const Material& paste) {
  Model next = with_adhesion(model_, adhesion);
  if (!next.materials.paste) next.materials.paste = next.materials.find(scene_paste(scene_).material);
  StabilityLimits l = stability_limits(next, synced(), &paste);
  const std::string excess = time_step_excess(next.dt, l);
  if (!excess.empty())
    throw UnstableTimeStep(fmt::format("refused: {} with this paste; lower its stiffness (Kp) or viscosity (mu)", excess));
  State& st = edit();
  // The Model's paste material is edited (its rest density kept), then every particle of it takes
  // the new values: other materials, and paste the cure has changed, keep theirs.
  model_ = std::move(next);
  MaterialTable& table = model_.materials;
  if (table.paste) {
    Material& m = table[*table.paste];
    m.Kp = paste.Kp;
    m.Ka = paste.Ka;
    m.mu = paste.mu;
  }
  st.refresh_materials(model_);
  // What the cure's mapping starts from, so that the next rise in conversion keeps the edit.
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.role[i] == Role::material) {
      const std::uint32_t id = st.id[i];
      st.cure.Kp0[id] = paste.Kp;
      st.cure.Ka0[id] = paste.Ka;
      st.cure.mu0[id] = paste.mu;
    }
  l.force = limits_.force;
  limits_ = l;
  rebuild_stepper();
}

std::unique_ptr<Stepper> Simulation::new_stepper() const {
  std::unique_ptr<Stepper> s = make_stepper(options_.backend, model_, state_, options_.threads, options_.thread_policy);
  s->set_solve_budget(options_.solve_budget_s);
  return s;
}

void Simulation::rebuild_stepper() {
  stepper_->sync_to_host(state_);
  stepper_ = new_stepper();
  edited_ = false;
}

bool Simulation::step(const Pose& tool_pose) {
  if (edited_) {
    // Particles added between steps took their values from the scene's table: the Model's (with
    // its edits) wins.
    state_.refresh_materials(model_);
    stepper_->sync_from_host(state_);
    edited_ = false;
  }
  const real t = state_.time;
  stepper_->step(state_, tool_pose);
  ++steps_since_cure_update_;
  const StepDiagnostics& d = state_.diagnostics;
  forces_.add(state_.tool_wrench.force, model_.dt);
  const real force_limit = solver_.motion_limit(model_, d);
  limits_.force = std::min(limits_.force, force_limit);
  if (model_.dt > force_limit && force_violation_steps_++ == 0) first_force_violation_t_ = t;
  solver_.record(solver_statistics_, d);
  // Exploded material: the run says so instead of stepping garbage.
  if (!diverged_ && exploded(d, state_.tool_wrench, limits_.sound_speed)) {
    diverged_ = true;
    std::string what;
    if (d.non_finite > 0)
      what = fmt::format("{} material particles became non-finite", d.non_finite);
    else if (tool_force_exploded(state_.tool_wrench))
      what = fmt::format("the tool force reached {:.3g} N, over {:.0e} N", norm(state_.tool_wrench.force),
                         exploded_tool_force);
    else
      what = fmt::format("material reached {:.3g} m/s, over {} times the sound speed {:.3g} m/s", d.max_speed,
                         explosion_speed_factor, limits_.sound_speed);
    divergence_ = fmt::format(
        "{} at t = {:.6g} s (step {}); the smallest {} limit seen was {:.3g} s against dt = {:.3g} s: lower "
        "simulation.dt or the stiffness",
        what, state_.time, state_.steps, solver_.motion_limit_name(), limits_.force, model_.dt);
  }
  if (!diverged_) cure_after_step(t);
  return !diverged_;
}

RunSummary Simulation::summary() {
  const State& st = synced();
  RunSummary s;
  s.scene = scene_.name;
  s.paste_preset = scene_.paste_preset;
  s.paste_temperature_c = scene_.paste_temperature_c;
  s.backend = stepper_->name();
  s.threads = options_.threads;
  s.solver = model_.solver;
  s.pressure_solve = model_.iisph.pressure_solve;
  s.gradient = model_.iisph.gradient;
  s.density_kernel = model_.iisph.density_kernel;
  s.viscous_pressure = model_.iisph.viscous_pressure;
  s.solver_statistics = solver_statistics_;
  if (diverged_) {
    s.status = "diverged";
    s.message = divergence_;
  }
  s.steps = st.steps;
  s.sim_time_s = st.time;
  // At the end: increments add paste; paste set by the cure is still paste (a wall to the step).
  std::uint32_t set = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) set += st.role[i] == Role::boundary && st.is_paste(i);
  s.material = st.count(Role::material) + set;
  s.boundary = st.count(Role::boundary) - set;
  s.tool = st.count(Role::tool);
  s.bonds = st.bonds.counters;
  s.bonds_current = st.bonded_pairs();
  s.dt = model_.dt;
  s.limits = limits_;
  s.acoustic_violated = acoustic_violated_;
  s.viscous_violated = viscous_violated_;
  s.forced = options_.allow_unstable && (acoustic_violated_ || viscous_violated_);
  s.force_violation_steps = force_violation_steps_;
  s.first_force_violation_t = first_force_violation_t_;
  s.peak_tool_force_N = forces_.peak_N;
  s.force_scale = scene_.force_scale;
  s.events_applied = events_applied_;
  if (scene_.tooth) s.cavity_json = cavity_json(*scene_.tooth);
  if (cure_) {
    s.curing = true;
    s.light_on_s = light_on_s_;
    s.cure_at_rest_s = cure_at_rest_s_;
    s.cure_updates_at_rest = cure_updates_at_rest_;
    if (scene_.tooth) {
      // Paste more than 1 mm above the occlusal reference (drawn up on the instrument, above the
      // light's window over the cavity) or more than 1 mm below the cavity's lowest point (thrown
      // out and fallen) is no part of the filling.
      const ToothFrame& f = scene_.tooth->frame();
      const Vec3 up = f.z / norm(f.z);
      const Bounds cb = scene_.tooth->cavity_bounds();
      real lowest = std::numeric_limits<real>::infinity();
      for (int k = 0; k < 8; ++k)
        lowest = std::min(lowest, dot(Vec3{k & 1 ? cb.max.x : cb.min.x, k & 2 ? cb.max.y : cb.min.y,
                                          k & 4 ? cb.max.z : cb.min.z},
                                     up));
      const CureAssessment a = assess_cure(*cure_, st, f.z, 0.8, dot(f.origin, up) + 1e-3, lowest - 1e-3);
      s.cure_json = cure_assessment_json(a);
      s.cure_report = cure_assessment_report(a);
    }
  }
  return s;
}

}  // namespace dentsph
