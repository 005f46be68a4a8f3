#include "haptics/haptic_loop.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dentsph/haptics/protocol.hpp"
#include "haptics/clock.hpp"

namespace dentsph::haptics {

namespace proto = haptic_protocol;

namespace {
constexpr double kVelocityCutoffHz = 100;  // first-order filter of the finite-difference velocity
}

HapticLoop::HapticLoop(Device& device, const RealtimeOptions& o, RuntimeShared& shared)
    : device_(device),
      opt_(o),
      shared_(shared),
      renderer_(o.mode, o.coupling),
      watchdog_(o.watchdog),
      limiter_(o.profile),
      contact_(o.profile.contact, o.workspace.scale),
      record_(std::size_t(std::max(0.0, o.record_capacity_s) * o.haptic_rate_hz)) {
  rep_.target_rate_hz = o.haptic_rate_hz;
  if (o.profile.max_torque_N_m > 0) torque_limiter_.emplace(torque_profile(o.profile));
}

void HapticLoop::run(std::int64_t t0_ns) {
  t0_ns_ = t0_ns;
  device_.start(t0_ns);
  const auto period_ns = std::int64_t(std::llround(1e9 / opt_.haptic_rate_hz));
  std::int64_t next = t0_ns;
  std::int64_t last = 0;
  while (!shared_.stop.load(std::memory_order_relaxed)) {
    sleep_until_ns(next);
    const std::int64_t now = now_ns();
    double dt = double(period_ns) * 1e-9;
    if (rep_.timing.ticks > 0) {
      last_period_us_ = double(now - last) * 1e-3;
      periods_.add(last_period_us_);
      dt = double(now - last) * 1e-9;
    } else {
      first_tick_ns_ = now;
    }
    if (now - next > period_ns / 2) ++rep_.timing.deadline_misses;
    last = now;
    tick(now, dt);
    ++rep_.timing.ticks;
    last_tick_ns_ = now;
    next += period_ns;
    if (now - next > period_ns) next = now + period_ns;  // far behind: skip, do not burst
    if (device_.finished(now)) shared_.device_finished.store(true, std::memory_order_release);
  }
}

void HapticLoop::publish_live(std::int64_t now, const Vec3& force, double pose_age, double sim_age, double gain,
                              std::uint32_t status) {
  HapticLive& l = *opt_.live;
  constexpr auto r = std::memory_order_relaxed;
  const double period = last_period_us_;
  recent_max_us_ = std::max(recent_max_us_, period);
  if (now - recent_start_ns_ >= 500'000'000) {
    l.period_max_recent_us.store(recent_max_us_, r);
    recent_max_us_ = 0;
    recent_start_ns_ = now;
  }
  l.ticks.store(rep_.timing.ticks + 1, r);
  l.deadline_misses.store(rep_.timing.deadline_misses, r);
  l.period_last_us.store(period, r);
  l.force_x.store(force.x, r);
  l.force_y.store(force.y, r);
  l.force_z.store(force.z, r);
  l.pose_age_ms.store(pose_age < 0 ? -1 : pose_age * 1e3, r);
  l.sim_age_ms.store(sim_age < 0 ? -1 : sim_age * 1e3, r);
  l.gain.store(gain, r);
  l.status.store(status, r);
}

void HapticLoop::tick(std::int64_t now, double dt) {
  // ---- device pose and velocity ----------------------------------------------------------------
  DeviceSample fresh = sample_;
  const bool got = device_.read(now, fresh);
  const Quat& q = fresh.pose.orientation;
  if (got && !(is_finite(fresh.pose.position) && std::isfinite(q.w + q.x + q.y + q.z))) ++rep_.non_finite_poses;
  else if (got) {
    if (fresh.session != sample_.session) start_session(fresh, now);
    // Button 1's presses are counted here, at the device's rate, so that the simulation loop,
    // which sees only the newest command, misses none between two of its steps.
    if ((fresh.buttons & ~sample_.buttons) & haptic_protocol::kButtonDispense) dispense_presses_.press(now);
    // Button 2 turns the curing light on or off, at most as often.
    if ((fresh.buttons & ~sample_.buttons) & haptic_protocol::kButtonLight) light_presses_.press(now);
    sample_ = fresh;
    const Vec3 x = sample_.pose.position;
    const double ddt = sample_.device_time_s - prev_device_time_;
    if (have_prev_ && ddt > 1e-6 && ddt < 0.1) {
      const double a = 1 - std::exp(-2 * std::numbers::pi * kVelocityCutoffHz * ddt);
      velocity_ += ((x - prev_position_) / ddt - velocity_) * a;
    }
    prev_position_ = x;
    prev_device_time_ = sample_.device_time_s;
    have_prev_ = true;
  }
  const double pose_age = sample_.valid ? double(now - sample_.stamp_ns) * 1e-9 : -1;
  if (pose_age > opt_.watchdog.pose_timeout_s) velocity_ = {};  // a quiet device is not moving
  const Vec3 x = sample_.pose.position;
  if (sample_.valid) passivity_.observe(x);  // the work the force sent last did on the hand

  // ---- hard contact: the instrument held out of the tooth, the band and set paste -------------
  // Its proxy is where the instrument may be (device frame): the simulation's tool follows it
  // instead of the device, and the hand feels the contact's spring to it.
  shared_.contact.update();
  const ContactWorld& world = shared_.contact.front();
  Vec3 held = x, held_velocity = velocity_;
  ContactResult contact;
  if (sample_.valid) {
    contact = contact_.update(world.field, world.shape, opt_.workspace.to_scene(x), sample_.pose.orientation, velocity_);
    held = opt_.workspace.to_device(contact.proxy);
    if (contact.touching) {
      held_velocity = {};  // against a surface the proxy moves along it at most: held as at rest
      if (contact.sliding) held_velocity = velocity_ - contact.normal * dot(velocity_, contact.normal);
    }
    if (!is_finite(held) || !is_finite(contact.force_N) || !is_finite(contact.torque_N_m)) {
      held = x, held_velocity = velocity_, contact = {};
      ++rep_.non_finite_rejected;
    }
  }
  if (contact.touching) ++rep_.contact_ticks;

  // ---- newest simulation output ------------------------------------------------------------------
  if (shared_.output.update()) {
    const SimOutput& o = shared_.output.front();
    // Outputs of steps that used a command from before the device's session started answer the
    // previous hand: not rendered.
    if (o.valid && (!have_sim_ || o.step != last_step_) && o.command_stamp_ns >= session_start_ns_) {
      SimOutput clean = o;
      if (!is_finite(o.force_N) || !is_finite(o.torque_N_m) || !is_finite(o.proxy_position) ||
          !is_finite(o.proxy_velocity)) {
        clean.force_N = clean.proxy_velocity = clean.torque_N_m = {};
        clean.proxy_position = held;  // no coupling force
        ++rep_.non_finite_rejected;
      }
      renderer_.add(clean, now);
      sim_torque_ = clean.torque_N_m;
      have_sim_ = true;
      last_step_ = o.step;
      sim_published_ns_ = o.published_ns;
      sim_command_stamp_ns_ = o.command_stamp_ns;
    }
  }
  // An output published after this tick began (while the tick ran: the hard contact takes tens of
  // microseconds) is fresh, not of negative age, which the watchdog would take for no output.
  const double sim_age = have_sim_ ? std::max(0.0, double(now - sim_published_ns_) * 1e-9) : -1;

  // ---- force: renderer, watchdog, limiter -------------------------------------------------------
  // The paste's force (through the coupling from the held proxy, or directly) and the contact's.
  const Vec3 target = renderer_.render(held, held_velocity, now) + contact.force_N;
  const double gain = watchdog_.update(sim_age, pose_age, dt);
  const Vec3 before = limiter_.last();
  // Where the forces have given the hand more energy than it took, damping takes it back.
  const ForceLimiter::Result lim = limiter_.apply(passivity_.correct(target * gain, velocity_, dt), dt);
  passivity_.sent(lim.force);
  // Torque for a device that renders it: the paste's and the contact's, through the same limits
  // (torque_profile); none for a 3-DoF device.
  const Vec3 torque =
      torque_limiter_ ? torque_limiter_->apply((sim_torque_ + contact.torque_N_m) * gain, dt).force : Vec3{};
  std::uint32_t status = 0;
  if (watchdog_.sim_stale()) status |= proto::kSimStale, ++rep_.sim_stale_ticks;
  if (watchdog_.pose_stale()) status |= proto::kPoseStale, ++rep_.pose_stale_ticks;
  if (lim.magnitude_limited) ++rep_.magnitude_limited_ticks;
  if (lim.rate_limited) ++rep_.rate_limited_ticks;
  if (lim.magnitude_limited || lim.rate_limited) status |= proto::kForceLimited;
  if (lim.non_finite) status |= proto::kNonFinite, ++rep_.non_finite_rejected;
  if (gain == 0) ++rep_.zero_gain_ticks;
  std::uint32_t age_us = 0;
  if (have_sim_) {
    const double age = double(now - sim_command_stamp_ns_) * 1e-3;
    force_ages_.add(age);
    age_us = std::uint32_t(std::min(age, 4e9));
  }
  device_.write(now, ForceCommand{lim.force, torque, status, age_us});
  if (opt_.live) publish_live(now, lim.force, pose_age, sim_age, gain, status);
  rep_.max_force_N = std::max(rep_.max_force_N, norm(lim.force));
  rep_.max_force_step_N = std::max(rep_.max_force_step_N, norm(lim.force - before));

  // ---- tool command for the simulation ----------------------------------------------------------
  const Vec3 tool = renderer_.tool_position(held, now);
  if (sample_.valid) {
    ToolCommand& c = shared_.command.back();
    c.pose = {held, sample_.pose.orientation};
    c.velocity = held_velocity;
    c.contact_normal = contact.touching ? contact.normal : Vec3{};
    c.stamp_ns = now;
    c.sequence = sample_.sequence;
    c.session = sample_.session;
    c.dispense_presses = dispense_presses_.counted();
    c.light_presses = light_presses_.counted();
    c.valid = true;
    shared_.command.publish();
  }

  // ---- record ----------------------------------------------------------------------------------
  if (recorded_ < record_.size()) {
    HapticSample& r = record_[recorded_++];
    r.t = double(now - t0_ns_) * 1e-9;
    r.device_position = x;
    r.device_orientation = sample_.pose.orientation;
    r.device_velocity = velocity_;
    r.force = lim.force;
    r.target = target;
    r.proxy_position = tool;
    r.contact_proxy = held;
    r.contact_force = contact.force_N;
    r.torque = torque;
    r.gain = gain;
    r.status = status;
    r.pose_sequence = sample_.sequence;
  } else {
    ++dropped_;
  }
}

void HapticLoop::start_session(const DeviceSample& fresh, std::int64_t now) {
  ++rep_.sessions;
  velocity_ = {};
  have_prev_ = false;
  sample_.buttons = fresh.buttons;  // a button held as the session starts is not a press
  watchdog_.restart();
  renderer_.restart();
  contact_.reset(opt_.workspace.to_scene(fresh.pose.position));
  sim_torque_ = {};
  if (torque_limiter_) torque_limiter_->reset();
  passivity_.reset();
  have_sim_ = false;
  session_start_ns_ = now;
}

HapticReport HapticLoop::report() const {
  HapticReport r = rep_;
  r.passivity_damped_ticks = passivity_.damped_ticks();
  r.passivity_energy_J = passivity_.energy_J();
  r.dispense_presses = dispense_presses_.counted();
  r.dispense_presses_refused = dispense_presses_.refused();
  r.light_presses = light_presses_.counted();
  r.light_presses_refused = light_presses_.refused();
  r.timing.period_p50_us = periods_.quantile(0.5);
  r.timing.period_p99_us = periods_.quantile(0.99);
  r.timing.period_max_us = periods_.max();
  const double span = double(last_tick_ns_ - first_tick_ns_) * 1e-9;
  r.timing.rate_hz = span > 0 ? double(r.timing.ticks - 1) / span : 0;
  r.force_age_p50_us = force_ages_.quantile(0.5);
  r.force_age_p99_us = force_ages_.quantile(0.99);
  r.force_age_max_us = force_ages_.max();
  r.watchdog_trips = watchdog_.trips();
  return r;
}

std::vector<HapticSample> HapticLoop::take_recording() {
  record_.resize(recorded_);
  return std::move(record_);
}

}  // namespace dentsph::haptics
