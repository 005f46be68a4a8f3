#include "haptics/sim_loop.hpp"

#include <algorithm>
#include <cmath>

#include "dentsph/dispense.hpp"
#include "dentsph/haptics/protocol.hpp"
#include "haptics/clock.hpp"
#include "haptics/free_path.hpp"
#include "haptics/virtual_coupling.hpp"

namespace dentsph::haptics {

int publish_every(double dt_s, double haptic_rate_hz) {
  const double ticks = dt_s * haptic_rate_hz;  // haptic periods a step
  if (!(ticks > 1) || !std::isfinite(ticks)) return 1;
  for (int k = 1; k <= 8; ++k) {
    const double n = k * ticks;
    if (std::abs(n - std::round(n)) < 1e-6 * n) return k;
  }
  return 1;
}

SimLoop::SimLoop(Simulation& sim, const RealtimeOptions& o, double force_scale, RuntimeShared& shared,
                 std::vector<Vec3> band)
    : sim_(sim), opt_(o), force_scale_(force_scale), shared_(shared), step_times_(1e6), rigid_(std::move(band)) {
  steps.reserve(1 << 16);
}

void SimLoop::publish_rigid(std::int64_t now) {
  if (now - rigid_checked_ns_ < kRigidCheckNs) return;
  rigid_checked_ns_ = now;
  if (!rigid_.changed(sim_.state())) return;
  RigidInput& in = shared_.rigid.back();
  in.particles = rigid_.particles();
  in.tool = rigid_.tool();
  in.tool_spacing = instrument_contact_spacing(sim_.scene());
  shared_.rigid.publish();
}

void SimLoop::run(std::int64_t t0_ns, const std::function<bool(std::int64_t)>& should_stop) {
  t0_ns_ = t0_ns;
  const real dt = sim_.model().dt;
  const std::uint64_t every = std::uint64_t(publish_every(dt, opt_.haptic_rate_hz));
  const std::int64_t min_step_ns = opt_.sim_rate_limit_hz > 0 ? std::int64_t(1e9 / opt_.sim_rate_limit_hz) : 0;
  const std::int64_t snapshot_ns = opt_.snapshot_rate_hz > 0 ? std::int64_t(1e9 / opt_.snapshot_rate_hz) : 0;
  std::int64_t next_snapshot = t0_ns, last_step_start = t0_ns - min_step_ns;
  bool stalled = false;
  ToolCommand cmd;
  const State& state = sim_.state();
  CouplingParams coupling = opt_.coupling;
  coupling.max_speed_m_per_s = sim_.model().iisph.cfl * sim_.model().kernel.h / dt / opt_.workspace.scale;
  VirtualCoupling proxy(coupling);
  const real reach = std::max(sim_.model().kernel.h, sim_.model().adhesion.B);  // the tool's farthest pair
  bool proxy_started = false;
  std::uint32_t proxy_session = 0;
  std::uint64_t presses_handled = 0, light_presses_handled = 0;
  const real dispense_volume = increment_volume_or_default(sim_.scene(), opt_.dispense_volume);
  const IncrementPaste paste = scene_paste(sim_.scene());
  while (!shared_.stop.load(std::memory_order_relaxed)) {
    std::int64_t now = now_ns();
    if (should_stop(now)) {
      shared_.stop.store(true, std::memory_order_relaxed);
      break;
    }
    // ---- pacing ---------------------------------------------------------------------------------
    if (opt_.faults.sim_stall_at_s >= 0 && !stalled && double(now - t0_ns) * 1e-9 >= opt_.faults.sim_stall_at_s) {
      stalled = true;
      ++rep_.stalls_injected;
      sleep_until_ns(now + std::int64_t(opt_.faults.sim_stall_s * 1e9), 0);
    }
    std::int64_t wake = 0;
    if (opt_.pace_realtime) wake = t0_ns + std::int64_t(double(state.time) * 1e9);
    if (min_step_ns > 0) wake = std::max(wake, last_step_start + min_step_ns);
    if (wake > now) {
      // Sleep in slices so that a stop is seen quickly.
      sleep_until_ns(std::min(wake, now + 5'000'000), 0);
      continue;
    }
    last_step_start = now;

      // ---- the newest tool command, the events due, one step ---------------------------------------
    if (shared_.command.update()) cmd = shared_.command.front();
    // Button 1 dispenses one increment per press (holding it does not repeat), however many
    // presses came since the last step.
    for (; presses_handled < cmd.dispense_presses; ++presses_handled) {
      events.push_back({state.steps, kButtonIncrement});
      sim_.dispense(dispense_volume, paste);
      ++rep_.button_dispenses;
    }
    // Button 2 turns the curing light over the cavity on or off, each press recorded.
    for (; light_presses_handled < cmd.light_presses; ++light_presses_handled) {
      events.push_back({state.steps, kLightToggle});
      sim_.toggle_light();
      ++rep_.light_toggles;
    }
    sim_.apply_due_events([&](std::size_t i) { events.push_back({state.steps, std::uint32_t(i)}); });
    Pose pose = state.tool_pose;  // without a device pose yet, the tool stays where it is
    bool free = false;
    if (cmd.valid) {
      Vec3 tool = cmd.pose.position;
      if (opt_.mode == ForceMode::coupling) {
        // The proxy: pulled by the coupling to the device, pushed by the tool force of the last
        // step, over this step's dt.
        // A new hand (the device's first command, or a new session's) starts with the proxy at its
        // pose, at rest; the last step's tool force was the previous hand's tool's, not felt by this one.
        Vec3 tool_force = state.tool_wrench.force * force_scale_;
        if (!proxy_started || cmd.session != proxy_session) {
          proxy.reset(tool), proxy_started = true, proxy_session = cmd.session;
          tool_force = {};
        }
        // A free move: no paste or wall particle within reach of the instrument's path from the proxy to the hand
        // (the kernel's support, or the adhesion's where a bond reaches farther), and the proxy
        // goes there at once; otherwise it goes freely as far as the path is clear, and on from
        // there under the coupling and the step's speed limit.
        const Vec3 at = proxy.position();
        const real share = free_share(state, {opt_.workspace.to_scene(at), state.tool_pose.orientation},
                                      {opt_.workspace.to_scene(tool), cmd.pose.orientation}, reach, tools_);
        free = share >= 1;
        if (free) {
          proxy.place(tool, cmd.velocity);
        } else {
          if (share > 0) proxy.place(at + (tool - at) * share, cmd.velocity);
          proxy.step(cmd.pose.position, cmd.velocity, tool_force, dt);
          // The hard contact's surface holds the simulated tool too: the coupling's swing does
          // not carry it into the tooth or set paste.
          if (cmd.contact_normal != Vec3{}) proxy.keep_outside(cmd.pose.position, cmd.contact_normal);
        }
        tool = proxy.position();
      }
      pose = {opt_.workspace.to_scene(tool), cmd.pose.orientation};
    }
    if (opt_.between_steps) opt_.between_steps(sim_, events);
    StepSample sample;
    sample.step = state.steps;
    sample.wall_t = double(now - t0_ns) * 1e-9;
    sample.tool_pose = pose;
    const std::int64_t s0 = now_ns();
    const bool going = sim_.step(pose);
    now = now_ns();
    step_times_.add(double(now - s0) * 1e-3);
    sample.tool_force = state.tool_wrench.force;
    steps.push_back(sample);
    if (!going) break;  // diverged: nothing more is published, the watchdog ramps the force to zero

    // ---- publish (on whole haptic ticks: publish_every) ---------------------------------------------
    if (state.steps % every == 0) {
      SimOutput& out = shared_.output.back();
      out.force_N = state.tool_wrench.force * force_scale_;
      out.torque_N_m = state.tool_wrench.torque * (force_scale_ / opt_.workspace.scale);
      out.free = free;
      out.proxy_position = proxy_started ? proxy.position() : cmd.pose.position;
      out.proxy_velocity = proxy_started ? proxy.velocity() : Vec3{};
      out.step = state.steps;
      out.sim_time = state.time;
      out.command_stamp_ns = cmd.valid ? cmd.stamp_ns : now;
      out.published_ns = now;
      out.valid = true;
      shared_.output.publish();
    }
    publish_rigid(now);
    if (snapshot_ns > 0 && now >= next_snapshot) {
      publish_snapshot(now);
      next_snapshot = std::max(next_snapshot + snapshot_ns, now);
    }
  }
  end_ns_ = now_ns();
}

void SimLoop::publish_snapshot(std::int64_t now_ns) {
  const State& state = sim_.synced();
  Snapshot& s = shared_.snapshots.back();
  if (s.positions.size() < state.size()) s.positions.resize(state.size());  // dispensed material
  std::copy(state.pos.begin(), state.pos.end(), s.positions.begin());
  s.count = state.size();
  s.sim_time = state.time;
  s.step = state.steps;
  s.published_ns = now_ns;
  shared_.snapshots.publish();
}

SimReport SimLoop::report() const {
  SimReport r = rep_;
  r.steps = steps.size();
  const double wall = double(end_ns_ - t0_ns_) * 1e-9;
  r.steps_per_second = wall > 0 ? double(r.steps) / wall : 0;
  r.realtime_factor = wall > 0 ? double(r.steps) * double(sim_.model().dt) / wall : 0;
  r.step_p50_us = step_times_.quantile(0.5);
  r.step_p99_us = step_times_.quantile(0.99);
  r.step_max_us = step_times_.max();
  return r;
}

}  // namespace dentsph::haptics
