// What the runtime's end-to-end tests share: their options, the realtime sections of a result,
// the safety check of every force sent, and a run with the reference client as the device.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <functional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "client_process.hpp"
#include "dentsph/haptics.hpp"
#include "dentsph/haptics/protocol.hpp"
#include "dentsph/simulation.hpp"
#include "press_scene.hpp"

// Built with ThreadSanitizer (clang's __has_feature, gcc's __SANITIZE_THREAD__): the simulation
// runs at about a tenth of real time there.
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define DENTSPH_UNDER_TSAN 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define DENTSPH_UNDER_TSAN 1
#endif

namespace dentsph::testing {

#ifdef DENTSPH_UNDER_TSAN
inline constexpr bool kUnderThreadSanitizer = true;
#else
inline constexpr bool kUnderThreadSanitizer = false;
#endif

// The test scene's tool forces are about 0.02-0.2 N: scaled by 20 they are what a Falcon renders.
inline RealtimeOptions options(ForceMode mode) {
  RealtimeOptions o;
  o.mode = mode;
  o.force_scale = 20;
  o.profile = device_profile("falcon");
  o.threads = 1;
  o.record_capacity_s = 10;
  o.workspace.origin = {0, 0, 0.09};  // the device's origin: the tool's first keyframe
  return o;
}

inline nlohmann::json realtime_sections(const RealtimeResult& r) { return nlohmann::json::parse(r.run.realtime_json); }

inline void print_timing(const RealtimeResult& r) { std::printf("%s", realtime_report(r).c_str()); }

// Every force the runtime sent is finite, within the profile, and changes by at most the rate
// limit per tick: the first from the zero force the runtime starts with at t = 0 (the recording's
// first sample may come a few ticks later on a loaded host, with the force already ramped).
inline void expect_safe(const RealtimeResult& r, const DeviceProfile& p) {
  ASSERT_GT(r.recording.haptic.size(), 10u);
  Vec3 prev;
  double prev_t = 0;
  for (const HapticSample& s : r.recording.haptic) {
    ASSERT_TRUE(is_finite(s.force));
    ASSERT_LE(norm(s.force), p.max_force_N + 1e-12);
    ASSERT_LE(norm(s.force - prev), p.max_force_rate_N_per_s * std::min(0.1, std::max(s.t - prev_t, 0.0)) + 1e-9);
    prev = s.force;
    prev_t = s.t;
  }
}

// Waits, polling, until `done()` or `limit_s` of wall time has passed; returns whether it was done.
// The limit is a guard against a hang, never the measure: a test waits on its events.
inline bool wait_until(const std::function<bool()>& done, double limit_s = 60) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  while (!done()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

// The longest stretch of ticks whose pose was stale (haptic_protocol::kPoseStale), from where the
// watchdog's ramp down is over (and two ticks more) to its last tick: {start, end} in the recording's
// seconds, {0, 0} when no pose went stale.
inline std::pair<double, double> longest_stale_stretch(const RealtimeResult& r, const WatchdogParams& w) {
  std::pair<double, double> best{0, 0};
  double from = -1;
  for (const HapticSample& s : r.recording.haptic) {
    if (!(s.status & haptic_protocol::kPoseStale)) {
      from = -1;
      continue;
    }
    if (from < 0) from = s.t;
    const double start = from + w.ramp_down_s + 0.002;
    if (s.t >= start && s.t - start > best.second - best.first) best = {start, s.t};
  }
  return best;
}

// The runtime on a thread of its own while `drive` runs on this one (starting clients and waiting
// for them to finish: events, not the clock), given the haptic loop's live figures, stopped once
// `drive` returns. `o.duration_s` is a guard (60 s when unset): a run that lasts that long did not
// see its events.
inline RealtimeResult run_while(const Scene& scene, Device& device, RealtimeOptions o,
                                const std::function<void(const HapticLive&)>& drive) {
  std::atomic<bool> stop{false};
  HapticLive live;
  o.stop = &stop;
  o.live = &live;
  if (o.duration_s <= 0) o.duration_s = 60;
  o.record_capacity_s = std::max(o.record_capacity_s, o.duration_s);
  RealtimeResult r;
  std::exception_ptr failed;  // what the runtime threw (a refused option, an unstable step), thrown here
  std::thread runtime([&] {
    try {
      r = run_realtime(scene, device, o);
    } catch (...) {
      failed = std::current_exception();
    }
  });
  drive(live);
  stop.store(true);
  runtime.join();
  if (failed) std::rethrow_exception(failed);
  return r;
}

// Whether the haptic loop has ticked `n` more times from now (each tick reads what the device was
// sent before it), waiting for it: n = 1 when the runtime has just started, a few once a client has
// exited, so that its last messages (its goodbye) are read before the runtime stops.
inline bool haptic_ticks_pass(const HapticLive& live, std::uint64_t n = 1) {
  const std::uint64_t from = live.ticks.load(std::memory_order_relaxed);
  return wait_until([&] { return live.ticks.load(std::memory_order_relaxed) >= from + n; });
}

// `scene` under the runtime with its scripted hand (the device's origin at the tool's first keyframe)
// until the simulation reaches `simulated_s`, however slowly the host steps it (the hand holds its
// last pose meanwhile; 120 s of wall time is a guard).
inline RealtimeResult run_until_simulated(const Scene& scene, RealtimeOptions o, real simulated_s) {
  o.duration_s = 120;
  o.record_capacity_s = 120;
  o.workspace.origin = scene.tool.keyframes.front().pose.position;
  std::atomic<bool> stop{false};
  o.stop = &stop;
  o.between_steps = [&](Simulation& sim, std::vector<EventSample>&) {
    if (sim.state().time >= simulated_s) stop.store(true);
  };
  auto device = make_scripted_device(scene, o.workspace, o.duration_s);
  return run_realtime(scene, *device, o);
}

// The press scene under the runtime with a UDP device, the reference client (given arguments)
// playing it from a separate process; the runtime's result and the client's report. The client
// starts once the haptic loop runs, and the runtime stops once the client has finished, so that a
// slow start on either side changes nothing (`o.duration_s` is only a guard).
inline std::pair<RealtimeResult, nlohmann::json> run_with_client(const RealtimeOptions& o, std::vector<std::string> args,
                                                                 const std::string& tag) {
  const Scene scene = press_scene();
  std::uint16_t port = 0;
  auto device = make_udp_device({"127.0.0.1", 0}, &port);
  nlohmann::json c;
  RealtimeResult r = run_while(scene, *device, o, [&](const HapticLive& live) {
    if (!haptic_ticks_pass(live)) return;
    ClientProcess client(port, std::move(args), tag);
    if (client.started()) c = client.wait();
    haptic_ticks_pass(live, 20);
  });
  print_timing(r);
  std::printf("client: %s\n", c.dump().c_str());
  return {std::move(r), std::move(c)};
}

}  // namespace dentsph::testing
