// The viewer's simulation loop (sim_session.hpp).
#include "sim_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <pthread.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "dentsph/dispense.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/step.hpp"
#include "dentsph/tools.hpp"

namespace dentsph::viewer {

namespace {

using clock_type = std::chrono::steady_clock;

}  // namespace

SimSession::SimSession(Scene scene, SessionOptions options) : scene_(std::move(scene)), opt_(options) {
  force_scale_ = scene_.force_scale;
  const IncrementPaste paste = scene_paste(scene_);
  paste_ = paste.material;
  press_axis_ = increment_axis(scene_);
  if (scene_.tooth) {
    AssessParams ap;
    ap.spacing = increment_spacing(scene_);
    assessor_.emplace(*scene_.tooth, ap);
  }
  opt_.dispense_volume = increment_volume_or_default(scene_, opt_.dispense_volume);
  contact_field_ = scene_contact_field(scene_);
  contact_rigid_ = RigidWatch(scene_rigid_band(scene_));
  paused_ = opt_.start_paused;
  reset();
  publish(*sim_, true, 0);
}

SimSession::~SimSession() { stop(); }

void SimSession::reset() {
  auto fresh = std::make_unique<Simulation>(scene_, SimulationOptions{opt_.backend, opt_.threads, false});
  if (paste_edited_) fresh->set_paste(adhesion_, paste_);  // the paste as edited, not as the scene gave it
  sim_ = std::move(fresh);  // only once it stands: a reset that fails keeps the running simulation
  tool_name_ = scene_.tooth ? "ball_burnisher" : "scene tool";
  target_ = scene_.tool.keyframes.empty() ? Vec3{} : scene_.tool.at(0).position;
  diverged_ = false;
  force_log_.clear();
  contact_.reset(sim_->state().tool_pose_applied.position);
  contact_rigid_.forget();
  contact_stale_ = true;
  steps_.store(0, std::memory_order_release);
}

std::vector<std::string> SimSession::tools() const { return instrument_names(); }

void SimSession::use_device(std::unique_ptr<Device> device, RealtimeOptions options) {
  if (running_.load()) throw std::logic_error("SimSession::use_device after start()");
  device_ = std::move(device);
  rt_options_ = std::move(options);
  // One increment for the D key and the device's button, the one the recording replays.
  rt_options_.dispense_volume = opt_.dispense_volume;
  rt_options_.backend = opt_.backend;
  rt_options_.contact_field = std::make_shared<const ContactField>(contact_field_);  // made once, for the mouse
  force_scale_ = rt_options_.force_scale.value_or(scene_.force_scale);
}

void SimSession::start() {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this] {
    pthread_setname_np(pthread_self(), "viewer-sim");  // as top -H and perf show it
    // The session's own loop steps as fast as it can: the frames and the paste's surface come
    // first (its threads, made by this one, inherit the nice value). The haptic runtime keeps its
    // pace and its priority.
    if (!device_) {
      const id_t self = id_t(syscall(SYS_gettid));
      (void)setpriority(PRIO_PROCESS, self, std::min(19, getpriority(PRIO_PROCESS, self) + kFreeRunningNice));
    }
    if (device_) run_device();
    else run();
  });
}

void SimSession::stop() {
  running_.store(false);
  rt_stop_.store(true);
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void SimSession::post(const Command& c) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(c);
  }
  wake_.notify_all();
}

void SimSession::post_at(std::uint64_t step, const Command& c) {
  {
    std::lock_guard lock(mutex_);
    scheduled_.emplace(step, c);
  }
  wake_.notify_all();
}

bool SimSession::schedule_done() const {
  std::lock_guard lock(mutex_);
  return scheduled_.empty() && queue_.empty();
}

bool SimSession::latest(Snapshot& out) const {
  std::lock_guard lock(mutex_);
  if (published_.version <= out.version && out.version != 0) return false;
  out = published_;
  return true;
}

Vec3 SimSession::held_by_contact(const Pose& pose) {
  if (!contact_field_.has_tooth() && !contact_field_.has_grid()) return pose.position;
  const State& st = sim_->state();
  if ((contact_stale_ || st.steps % kContactCheckSteps == 0) && contact_rigid_.changed(st)) {
    contact_field_.set_particles(contact_rigid_.particles());
    contact_shape_ = instrument_contact_shape(contact_rigid_.tool(), instrument_contact_spacing(scene_));
  }
  contact_stale_ = false;
  return contact_.update(contact_field_, contact_shape_, pose.position, pose.orientation, {}).proxy;
}

Vec3 SimSession::tool_tip_goal() const {
  const real s = increment_spacing(scene_);
  return pressed_ ? target_ - press_axis_ * (opt_.press_depth_spacings * s) : target_;
}

void SimSession::apply(const Command& c, Simulation& sim, std::vector<EventSample>* recorded) {
  message_.clear();
  switch (c.kind) {
    case Command::Kind::pause:
    case Command::Kind::resume:
    case Command::Kind::single_step:
      if (device_) {
        message_ = "the haptic runtime does not pause: the device's hand keeps moving (close the window to stop)";
        return;
      }
      if (c.kind == Command::Kind::single_step) single_ = true;
      paused_ = c.kind != Command::Kind::resume;
      return;
    case Command::Kind::reset:
      if (device_) {
        // The runtime's clock, its procedure events and its recording all run on from the state's
        // time: a state set back to t = 0 would break the pacing and the replay.
        message_ = "the haptic runtime does not reset: close the window and start again";
        return;
      }
      try {
        reset();
      } catch (const std::exception& e) {
        message_ = fmt::format("reset refused: {}", e.what());
      }
      return;
    case Command::Kind::tool_target: target_ = c.target; return;  // the device's pose wins in device mode
    case Command::Kind::press: pressed_ = c.pressed; return;
    case Command::Kind::light:
      // The curing light held over the cavity (the L key; the device's second button in the
      // haptic runtime, which records it): the paste under it cures.
      if (device_) {
        message_ = "with a device, its second button turns the curing light on and off";
        return;
      }
      sim.set_light(c.pressed ? std::optional<CuringLight>(sim.light_over_cavity()) : std::nullopt);
      return;
    case Command::Kind::dispense:
      if (recorded) recorded->push_back({sim.state().steps, kButtonIncrement});
      sim.dispense(opt_.dispense_volume, scene_paste(scene_));  // the Model's paste, as edited
      return;
    case Command::Kind::switch_tool:
      try {
        const EventSample event = tool_switch_event(sim.state().steps, c.tool);  // refuses an unknown tool first
        sim.switch_instrument(c.tool);
        if (recorded) recorded->push_back(event);
        tool_name_ = c.tool;
      } catch (const std::exception& e) {
        message_ = e.what();
      }
      return;
    case Command::Kind::set_material:
      if (device_) {
        // The runtime's recording holds the session's increments and tool switches, not the
        // paste: a replay must step the paste the session stepped.
        message_ = "the paste is fixed while a device drives the runtime (its recording replays the scene's paste)";
        return;
      }
      set_material(c.material, sim);
      return;
    case Command::Kind::load_preset:
      if (device_) {
        message_ = "the paste is fixed while a device drives the runtime (its recording replays the scene's paste)";
        return;
      }
      load_preset(c.preset, c.temperature_c);
      return;
  }
}

void SimSession::load_preset(const std::string& preset, double temperature_c) {
  if (!opt_.rebuild) {
    message_ = "this scene has no paste presets (a scene file's materials are its own); start the viewer without one";
    return;
  }
  try {
    Scene sc = opt_.rebuild(preset, temperature_c);  // refused before anything changes
    scene_ = std::move(sc);
    force_scale_ = scene_.force_scale;
    paste_ = scene_paste(scene_).material;
    paste_edited_ = false;
    reset();
    message_ = preset.empty() ? std::string("filled with the scene's own paste")
                              : fmt::format("filled with {} at {:g} C, its force at scale {:g}", preset, temperature_c,
                                            force_scale_);
  } catch (const std::exception& e) {
    message_ = fmt::format("preset refused: {}", e.what());
  }
}

void SimSession::set_material(const MaterialEdit& m, Simulation& sim) {
  if (!(m.Kp > 0) || !(m.mu >= 0) || !(m.Ka >= 0)) {
    message_ = "material: Kp must be positive, mu and Ka non-negative";
    return;
  }
  AdhesionParams adhesion = sim.model().adhesion;
  adhesion.A = m.A;
  adhesion.B = m.B;
  adhesion.eps = m.eps;
  adhesion.zeta = m.zeta;
  Material paste = paste_;
  paste.Kp = m.Kp;
  paste.Ka = m.Ka;
  paste.mu = m.mu;
  try {
    // Made on the Simulation's Model, the one its stepper reads; refused (nothing changed) for an
    // impossible kernel, or where dt would be over the acoustic or viscous limit: the paste would
    // explode. The scene stays as it was given: a reset builds its particles from it and then
    // makes the edit again.
    sim.set_paste(adhesion, paste);
    adhesion_ = adhesion;
    paste_ = paste;
    paste_edited_ = true;
  } catch (const std::exception& e) {
    message_ = e.what();
  }
}

void SimSession::publish(Simulation& sim, bool with_assessment, double steps_per_second) {
  // Filled in the back buffer, whose arrays keep their capacity from publication to publication.
  const State& st = sim.synced();
  Snapshot& s = back_;
  const std::uint32_t n = st.size();
  s.time = st.time;
  s.steps = st.steps;
  s.xyz.resize(3 * std::size_t(n));
  s.role.assign(st.role.begin(), st.role.end());
  s.conversion.assign(n, 0.f);
  for (std::uint32_t i = 0; i < n; ++i)
    if (st.is_paste(i)) {
      s.role[i] = Role::material;  // paste set by the light is still paste (a wall to the step)
      s.conversion[i] = float(st.cure.alpha[st.id[i]]);
    }
  s.light = sim.light();
  if (s.light && !s.light->on) s.light.reset();
  if (const CureModel* cm = sim.cure_model()) s.conversion_max = cm->paste.alpha_max;
  s.pressure.resize(n);
  s.density.resize(n);
  s.speed.resize(n);
  s.bonds.resize(n);
  const bool have_fields = st.rho.size() == n && st.pressure.size() == n;
  for (std::uint32_t i = 0; i < n; ++i) {
    s.xyz[3 * i] = float(st.pos[i].x);
    s.xyz[3 * i + 1] = float(st.pos[i].y);
    s.xyz[3 * i + 2] = float(st.pos[i].z);
    s.pressure[i] = have_fields ? float(st.pressure[i]) : 0.f;
    s.density[i] = have_fields ? float(st.rho[i]) : 0.f;
    s.speed[i] = float(norm(st.vel[i]));
    s.bonds[i] = float(st.bonds.count(st.id[i]));
  }
  s.tool_pose = st.tool_pose_applied;
  s.device_force_N = st.tool_wrench.force * force_scale_;
  s.force_scale = force_scale_;
  s.assessment.reset();
  const Model& model = sim.model();
  if (with_assessment && assessor_) s.assessment = assessor_->assess(st, model, sim.forces(), force_scale_);
  s.limits = stability_limits(model, st);
  s.dt = model.dt;
  s.material = {paste_.Kp, paste_.Ka, paste_.mu, model.adhesion.A, model.adhesion.B, model.adhesion.eps,
                model.adhesion.zeta, paste_.flow_index, paste_.yield_stress};
  s.preset = scene_.paste_preset;
  s.preset_temperature_c = scene_.paste_temperature_c;
  s.tool_name = tool_name_;
  s.message = message_;
  s.paused = paused_;
  s.diverged = diverged_;
  s.steps_per_second = steps_per_second;
  s.backend = sim.stepper().name();
  if (device_) {
    Snapshot::Haptic h;
    constexpr auto r = std::memory_order_relaxed;
    h.device = device_->name();
    h.ticks = live_.ticks.load(r);
    const auto now = std::chrono::steady_clock::now();
    const double wall = std::chrono::duration<double>(now - live_t0_).count();
    if (wall >= 0.25) {
      h.rate_hz = double(h.ticks - live_ticks0_) / wall;
      live_ticks0_ = h.ticks;
      live_t0_ = now;
      last_rate_hz_ = h.rate_hz;
    } else {
      h.rate_hz = last_rate_hz_;
    }
    h.deadline_misses = live_.deadline_misses.load(r);
    h.period_last_us = live_.period_last_us.load(r);
    h.period_max_recent_us = live_.period_max_recent_us.load(r);
    h.force_N = {live_.force_x.load(r), live_.force_y.load(r), live_.force_z.load(r)};
    h.pose_age_ms = live_.pose_age_ms.load(r);
    h.sim_age_ms = live_.sim_age_ms.load(r);
    h.gain = live_.gain.load(r);
    h.status = live_.status.load(r);
    s.haptic = h;
  } else {
    s.haptic.reset();
  }
  std::lock_guard lock(mutex_);
  s.version = published_.version + 1;
  if (!with_assessment && published_.assessment) s.assessment = published_.assessment;  // keep the last one
  std::swap(published_, back_);
}

void SimSession::take_due(std::uint64_t steps) {
  due_.clear();
  std::lock_guard lock(mutex_);
  due_.swap(queue_);  // both keep their capacity: no allocation once they have grown
  while (!scheduled_.empty() && scheduled_.begin()->first <= steps) {
    due_.push_back(scheduled_.begin()->second);
    scheduled_.erase(scheduled_.begin());
  }
}

void SimSession::run() {
  last_publish_ = clock_type::now();
  last_assess_ = last_publish_;
  auto rate_t0 = last_publish_;
  std::uint64_t rate_steps0 = sim_->state().steps;
  double rate = 0;
  const auto publish_every = std::chrono::duration<double>(1.0 / opt_.snapshot_hz);
  const auto assess_every = std::chrono::duration<double>(1.0 / opt_.assess_hz);
  while (running_.load(std::memory_order_acquire)) {
    {
      std::unique_lock lock(mutex_);
      const bool idle = (paused_ || diverged_) && !single_ && queue_.empty() &&
                        (scheduled_.empty() || scheduled_.begin()->first > sim_->state().steps || paused_);
      if (idle) wake_.wait_for(lock, std::chrono::milliseconds(20));
    }
    take_due(sim_->state().steps);
    for (const Command& c : due_) apply(c, *sim_);  // a reset makes sim_ anew
    Simulation& sim = *sim_;
    const bool changed = !due_.empty();
    const bool stepping = (!paused_ || single_) && !diverged_;
    if (stepping) {
      single_ = false;
      sim.apply_due_events();
      // The tool follows its goal at a bounded speed: a mouse jumps, a tool must not.
      const Vec3 goal = tool_tip_goal();
      const Pose& applied = sim.state().tool_pose_applied;
      const Vec3 d = goal - applied.position;
      const real max_move = opt_.tool_speed * sim.model().dt;
      const real len = norm(d);
      Pose pose = applied;
      pose.position = len > max_move ? applied.position + d * (max_move / len) : goal;
      pose.position = held_by_contact(pose);
      const real t_forces = sim.state().time;
      const bool going = sim.step(pose);
      force_log_.push_back({t_forces, sim.state().tool_wrench});
      if (!going) {
        diverged_ = true;
        message_ = fmt::format("the simulation diverged: {}; reset it (R) and soften the paste", sim.divergence());
      }
      steps_.store(sim.state().steps, std::memory_order_release);
    }
    const auto now = clock_type::now();
    if (now - rate_t0 >= std::chrono::milliseconds(500)) {
      rate = double(sim.state().steps - rate_steps0) / std::chrono::duration<double>(now - rate_t0).count();
      rate_t0 = now;
      rate_steps0 = sim.state().steps;
    }
    if (changed || now - last_publish_ >= publish_every || !stepping) {
      const bool assess = changed || now - last_assess_ >= assess_every;
      publish(sim, assess, rate);
      last_publish_ = now;
      if (assess) last_assess_ = now;
    }
  }
  publish(*sim_, true, rate);
}

void SimSession::between_steps(Simulation& sim, std::vector<EventSample>& recorded) {
  take_due(sim.state().steps);
  for (const Command& c : due_) apply(c, sim, &recorded);
  steps_.store(sim.state().steps, std::memory_order_release);
  const auto now = clock_type::now();
  const auto publish_every = std::chrono::duration<double>(1.0 / opt_.snapshot_hz);
  const auto assess_every = std::chrono::duration<double>(1.0 / opt_.assess_hz);
  if (!due_.empty() || now - last_publish_ >= publish_every) {
    const bool assess = !due_.empty() || now - last_assess_ >= assess_every;
    const double wall = std::chrono::duration<double>(now - rate_t0_).count();
    if (wall >= 0.5) {
      sim_rate_ = double(sim.state().steps - rate_steps0_) / wall;
      rate_t0_ = now;
      rate_steps0_ = sim.state().steps;
    }
    publish(sim, assess, sim_rate_);
    last_publish_ = now;
    if (assess) last_assess_ = now;
  }
}

void SimSession::run_device() {
  sim_.reset();  // the runtime steps a Simulation of its own (one backend's memory at a time)
  RealtimeOptions o = rt_options_;
  o.stop = &rt_stop_;
  o.live = &live_;
  o.snapshot_rate_hz = 0;  // the viewer publishes its own snapshots from between_steps
  o.between_steps = [this](Simulation& sim, std::vector<EventSample>& recorded) { between_steps(sim, recorded); };
  live_t0_ = rate_t0_ = last_publish_ = last_assess_ = clock_type::now();
  try {
    realtime_result_ = run_realtime(scene_, *device_, o);
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    published_.message = fmt::format("the haptic runtime stopped: {}", e.what());
    ++published_.version;
  }
  if (realtime_result_ && realtime_result_->run.status == "completed" && running_.load()) {
    std::lock_guard lock(mutex_);
    published_.message = fmt::format("the {} device's session ended after {:.1f} s; the last state stays on screen",
                                     device_->name(), realtime_result_->run.wall_time_s);
    ++published_.version;
  }
  if (realtime_result_ && realtime_result_->run.status != "completed") {
    std::lock_guard lock(mutex_);
    published_.message = fmt::format("the simulation diverged: {}", realtime_result_->run.message);
    published_.diverged = true;
    ++published_.version;
  }
  running_.store(false);
}

}  // namespace dentsph::viewer
