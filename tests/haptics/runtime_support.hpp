// What the runtime's end-to-end tests share: their options, the realtime sections of a result,
// the safety check of every force sent, and a run with the reference client as the device.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "client_process.hpp"
#include "dentsph/haptics.hpp"
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
// limit per tick.
inline void expect_safe(const RealtimeResult& r, const DeviceProfile& p) {
  ASSERT_GT(r.recording.haptic.size(), 10u);
  Vec3 prev;
  double prev_t = r.recording.haptic.front().t;
  for (const HapticSample& s : r.recording.haptic) {
    ASSERT_TRUE(is_finite(s.force));
    ASSERT_LE(norm(s.force), p.max_force_N + 1e-12);
    ASSERT_LE(norm(s.force - prev), p.max_force_rate_N_per_s * std::min(0.1, std::max(s.t - prev_t, 0.0)) + 1e-9);
    prev = s.force;
    prev_t = s.t;
  }
}

// The press scene under the runtime with a UDP device, the reference client (given arguments)
// playing it from a separate process; the runtime's result and the client's report.
inline std::pair<RealtimeResult, nlohmann::json> run_with_client(const RealtimeOptions& o, std::vector<std::string> args,
                                                                 const std::string& tag) {
  const Scene scene = press_scene();
  std::uint16_t port = 0;
  auto device = make_udp_device({"127.0.0.1", 0}, &port);
  ClientProcess client(port, std::move(args), tag);
  if (!client.started()) return {};
  RealtimeResult r = run_realtime(scene, *device, o);
  nlohmann::json c = client.wait();
  print_timing(r);
  std::printf("client: %s\n", c.dump().c_str());
  return {std::move(r), std::move(c)};
}

}  // namespace dentsph::testing
