// The Simulation's curing (simulation.hpp, docs/architecture.md "Curing"): the cure updated after
// every step with the light that is on, and the large updates of a long cure while nothing else
// happens (CureSchedule).
#include <algorithm>
#include <cmath>
#include <limits>

#include "dentsph/dispense.hpp"
#include "dentsph/paste_presets.hpp"
#include "dentsph/simulation.hpp"

namespace dentsph {

namespace {

bool same_pose(const Pose& a, const Pose& b) {
  return a.position == b.position && a.orientation.w == b.orientation.w && a.orientation.x == b.orientation.x &&
         a.orientation.y == b.orientation.y && a.orientation.z == b.orientation.z;
}

}  // namespace

void Simulation::start_curing() {
  if (cure_) return;
  cure_ = make_cure_model(model_, cure_material_preset(scene_paste_cure(scene_)), increment_spacing(scene_),
                          scene_paste(scene_).material);
}

void Simulation::set_light(const std::optional<CuringLight>& light) {
  if (light) start_curing();
  hand_light_ = light;
}

std::optional<CuringLight> Simulation::light() const {
  if (hand_light_) return hand_light_;
  return lights_.at(state_.time + 0.5 * model_.dt);
}

CuringLight Simulation::light_over_cavity() const {
  CuringLight l;
  if (scene_.tooth) {
    // 1 mm above the occlusal reference, or a spacing above the highest paste in the beam.
    const ToothFrame& f = scene_.tooth->frame();
    real height = 1e-3;
    for (std::uint32_t i = 0; i < state_.size(); ++i) {
      if (!state_.is_paste(i) || !is_finite(state_.pos[i])) continue;
      const Vec3 p = f.to_local(state_.pos[i]);
      if (std::hypot(p.x, p.y) < 0.5 * l.diameter) height = std::max(height, p.z + increment_spacing(scene_));
    }
    l.tip = f.origin + f.z * height;
    l.direction = -f.z;
    return l;
  }
  // No tooth: a kernel radius over the paste's top, above its middle (the domain's without paste).
  Vec3 mid = 0.5 * (model_.domain_min + model_.domain_max);
  real top = model_.domain_min.z, n = 0;
  Vec3 sum;
  for (std::uint32_t i = 0; i < state_.size(); ++i)
    if (state_.is_paste(i)) top = std::max(top, state_.pos[i].z), sum = sum + state_.pos[i], n += 1;
  if (n > 0) mid = sum / n;
  l.tip = {mid.x, mid.y, top + model_.kernel.h};
  // A window at least as wide as the paste.
  real reach = 0;
  for (std::uint32_t i = 0; i < state_.size(); ++i)
    if (state_.is_paste(i)) reach = std::max(reach, std::hypot(state_.pos[i].x - mid.x, state_.pos[i].y - mid.y));
  l.diameter = std::max(l.diameter, 2 * reach + increment_spacing(scene_));
  l.direction = {0, 0, -1};
  return l;
}

void Simulation::cure_after_step(real t_before) {
  if (!cure_) return;
  const real dt = state_.time - t_before;
  const std::optional<CuringLight> light = hand_light_ ? hand_light_ : lights_.at(t_before + 0.5 * dt);
  if (light && light->on) light_on_s_ += dt;
  // Only a pass reads and changes the particles: a GPU backend downloads them for it and takes them
  // back when it changed them (edit); the dose of the other steps is the cure state's own.
  if (cure_pass_due(*cure_, state_, light)) {
    stepper_->sync_to_host(state_);
    last_cure_ = cure_between_steps(*cure_, state_, light, dt);
    if (last_cure_.changed()) edited_ = true;
  } else {
    last_cure_ = cure_between_steps(*cure_, state_, light, dt);
  }
}

real Simulation::tool_still_until(real t) const {
  const std::vector<ToolKeyframe>& kf = scene_.tool.keyframes;
  const Pose now = scene_.tool.at(t);
  real still = t;
  for (const ToolKeyframe& k : kf) {
    if (k.t <= t) continue;
    if (!same_pose(k.pose, now)) return still;
    still = k.t;
  }
  return std::numeric_limits<real>::infinity();  // held after the last keyframe
}

bool Simulation::paste_at_rest(real speed) {
  if (state_.diagnostics.max_speed < speed) return true;
  if (!std::isfinite(state_.diagnostics.max_speed)) return false;
  Vec3 lo = model_.domain_min, hi = model_.domain_max;
  if (scene_.tooth) {
    const Bounds b = scene_.tooth->cavity_bounds();
    const real r = 4 * model_.kernel.h;  // the heap above the cavity too
    lo = b.min - Vec3{r, r, r};
    hi = b.max + Vec3{r, r, r};
  }
  const State& s = synced();  // a GPU backend downloads here only when the fastest particle moves
  const real speed2 = speed * speed;
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    if (s.role[i] != Role::material) continue;
    const Vec3& p = s.pos[i];
    const bool inside = p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    if (inside && !(norm2(s.vel[i]) < speed2)) return false;
  }
  return true;
}

real Simulation::advance_cure_at_rest(real until) {
  if (!cure_ || hand_light_ || diverged_) return 0;
  const CureSchedule& cs = options_.cure_schedule;
  const real t = state_.time;
  const std::optional<CuringLight> light = lights_.at(t + 0.5 * model_.dt);
  if (!light || !light->on || state_.steps == 0 || steps_since_cure_update_ < cs.steps_between ||
      !paste_at_rest(cs.rest_speed))
    return 0;
  real end = std::min({t + cs.update, until, lights_.next_change(t), tool_still_until(t)});
  if (next_event_ < scene_.events.size()) end = std::min(end, scene_.events[next_event_].t - model_.dt);
  const real span = end - t;
  if (!(span >= 2 * model_.dt)) return 0;  // too short to be worth it: step
  State& s = edit();  // the CPU: nothing to download; a GPU: once, and the time handed back
  s.time = end;
  last_cure_ = cure_between_steps(*cure_, s, light, span);
  light_on_s_ += span;
  cure_at_rest_s_ += span;
  ++cure_updates_at_rest_;
  steps_since_cure_update_ = 0;
  return span;
}

}  // namespace dentsph
