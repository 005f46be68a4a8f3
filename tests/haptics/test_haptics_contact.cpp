// Hard contact and free moves through the haptic runtime's threads: a hand pressing the built-in
// crown beside its cavity and into its empty cavity feels the tooth (k times its distance behind
// the proxy) and the simulated instrument never enters it; a quick move through air drags nothing;
// entering paste from such a move does not jolt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include <fmt/format.h>

#include "client_process.hpp"
#include "contact_support.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics.hpp"
#include "dentsph/haptics/replay.hpp"
#include "path_device.hpp"
#include "runtime_support.hpp"

namespace dentsph {
namespace {

RealtimeOptions contact_options() {
  RealtimeOptions o = testing::options(ForceMode::coupling);
  o.workspace.origin = {};  // device frame = scene frame
  o.force_scale = dental_force_scale;
  o.record_capacity_s = 10;
  return o;
}

// The built-in procedure without its events: a lined, empty cavity and the ball.
Scene empty_cavity_scene() {
  Scene s = default_dental_procedure();
  s.events.clear();
  return s;
}

double energy_ratio(const Recording& rec, double* work_in) {
  // Energy to the hand over the run, against the hand's work where it pushed against the force.
  const std::vector<double> e = energy_to_hand(rec.haptic);
  double in = 0;
  for (std::size_t k = 1; k < e.size(); ++k) in += std::max(0.0, e[k - 1] - e[k]);
  *work_in = in;
  return in > 0 ? e.back() / in : 0;
}

struct ToothPress {
  const char* name;
  Vec3 start_local;
};

class HardContactRuntime : public ::testing::TestWithParam<ToothPress> {};

TEST_P(HardContactRuntime, TheToothStopsTheInstrumentAndIsFelt) {
  const testing::ContactBench& b = testing::ContactBench::get();
  const Scene scene = empty_cavity_scene();
  const ToothFrame& f = b.tooth().frame();
  const DeviceProfile profile = device_profile("falcon");
  // Where the ball meets the surface going down, and the device 1 mm behind it along the normal.
  HardContact probe(profile.contact);
  const Vec3 start = f.to_world(GetParam().start_local);
  const testing::PressRun plan =
      testing::press(probe, b.field, b.shape, start, -f.z, 1e-3, 0.02, false, &b.tooth());
  ASSERT_TRUE(plan.touched);
  const Vec3 hold = plan.device;
  // Down at 20 mm/s, hold from 0.6 s to 1.2 s, up again.
  const double travel = norm(hold - start) / 0.02;
  auto path = [=](double t) {
    const double a = std::clamp(t / travel, 0.0, 1.0), back = std::clamp((t - 1.2) / travel, 0.0, 1.0);
    return start + (hold - start) * (a - back);
  };
  ASSERT_LT(travel, 0.6);
  testing::PathDevice device(path, 1.3 + travel);
  const RealtimeResult r = run_realtime(scene, device, contact_options());
  testing::print_timing(r);
  testing::expect_safe(r, profile);
  int held = 0;
  for (const HapticSample& s : r.recording.haptic) {
    if (s.t < 0.8 || s.t > 1.15 || s.gain < 1) continue;  // the watchdog scales everything when the simulation lags
    ++held;
    const double behind = norm(s.contact_proxy - s.device_position);
    EXPECT_NEAR(behind, 1e-3, 0.1e-3);
    EXPECT_NEAR(norm(s.force), profile.contact.stiffness_N_per_m * behind, 0.1 * profile.contact.stiffness_N_per_m * behind)
        << "at " << s.t << " s";
    EXPECT_LT(testing::angle_deg(s.force, plan.surface_normal), 5.0) << "at " << s.t << " s";
  }
  EXPECT_GT(held, 200);
  // The simulated instrument never entered the tooth: every step's pose keeps the ball's spheres
  // out of it (within the contact's tolerance).
  double deepest = 0;
  for (const StepSample& st : r.recording.steps)
    for (const ContactSphere& sp : b.shape.spheres)
      deepest = std::min(deepest, b.tooth().distance(st.tool_pose.apply(sp.centre)).distance - sp.radius);
  EXPECT_GT(deepest, -0.05e-3);
  // Passive over the press and the release.
  double work_in = 0;
  EXPECT_LE(energy_ratio(r.recording, &work_in), 0.01);
  EXPECT_GT(work_in, 0);
  const nlohmann::json h = testing::realtime_sections(r)["haptic"];
  EXPECT_GT(h["hard_contact"]["ticks"].get<int>(), 500);
}

INSTANTIATE_TEST_SUITE_P(Surfaces, HardContactRuntime,
                         ::testing::Values(ToothPress{"enamel", {0, 2.6e-3, 6e-3}}, ToothPress{"floor", {0.5e-3, 0, 0.5e-3}}),
                         [](const auto& info) { return std::string(info.param.name); });

// Set paste through the runtime: the built-in procedure's first increment, cured under its light
// from 0.9 s (the later increments left out), and the hand coming down onto it at 20 mm/s from
// 3.5 s, 2.6 s into the light, to the cavity's floor level and holding there. The set paste stops the
// instrument above the floor: the contact's force is k times the device's distance behind its proxy,
// along that offset, and the simulated instrument stays with the proxy, not with the hand.
TEST(HardContactRuntime, SetPasteStopsTheInstrumentAndIsFelt) {
  if (testing::kUnderThreadSanitizer)
    GTEST_SKIP() << "the press waits for 2.6 s of simulated light by the wall clock; under ThreadSanitizer the "
                    "simulation runs at a tenth of real time and the paste has not set (the threads' races are "
                    "checked by the enamel and floor presses)";
  Scene scene = default_dental_procedure();
  scene.events.resize(2);  // the first increment and its cure
  ASSERT_EQ(scene.events[1].kind, ProcedureEvent::Kind::cure);
  const ToothFrame f = scene.tooth->frame();
  const DeviceProfile profile = device_profile("falcon");
  const Vec3 above = f.to_world({0.5e-3, 0, 4e-3}), floor_level = f.to_world({0.5e-3, 0, -1.9e-3});
  const double down = norm(floor_level - above) / 0.02;
  auto path = [=](double t) {
    const double a = std::clamp((t - 3.5) / down, 0.0, 1.0), back = std::clamp((t - 5.0) / down, 0.0, 1.0);
    return above + (floor_level - above) * (a - back);
  };
  testing::PathDevice device(path, 5.4);
  RealtimeOptions o = contact_options();
  const RealtimeResult r = run_realtime(scene, device, o);
  testing::print_timing(r);
  testing::expect_safe(r, profile);
  int held = 0;
  double proxy_height = 0;
  for (const HapticSample& s : r.recording.haptic) {
    if (s.t < 4.0 || s.t > 4.95 || s.gain < 1) continue;
    ++held;
    const Vec3 behind = s.contact_proxy - s.device_position;
    proxy_height = f.to_local(s.contact_proxy).z;
    ASSERT_GT(norm(behind), 0.5e-3) << "at " << s.t << " s: the instrument went into the set paste";
    EXPECT_NEAR(norm(s.contact_force), profile.contact.stiffness_N_per_m * norm(behind),
                0.1 * profile.contact.stiffness_N_per_m * norm(behind))
        << "at " << s.t << " s";
    EXPECT_LT(testing::angle_deg(s.contact_force, behind), 5.0) << "at " << s.t << " s";
  }
  EXPECT_GT(held, 500);
  if (held == 0) return;  // nothing below means anything
  // Pressing set paste is contact, not a force in air (the simulated tool feels nothing there).
  EXPECT_LE(r.haptic.free_air.free_p95_N, 0.05);
  EXPECT_GT(r.haptic.free_air.contact_ticks, 500u);
  std::printf("the set paste held the proxy at %.3f mm (tooth frame; the floor is at -1.9 mm)\n", proxy_height * 1e3);
  EXPECT_GT(proxy_height, -1.5e-3) << "held above the floor";
  // The simulated instrument stayed with the proxy, within the coupling's reach, not with the hand.
  for (const StepSample& st : r.recording.steps) {
    if (st.wall_t > 4.2 && st.wall_t < 4.9) {
      EXPECT_GT(f.to_local(st.tool_pose.position).z, proxy_height - 0.1e-3) << "at " << st.wall_t << " s";
    }
  }
}

// The same presses played by the reference client over UDP, as a device would: the hand 1 mm into
// the enamel beside the cavity, and into the cavity floor, feels k times its distance behind the
// proxy, along the surface's normal; the client receives that force.
class HardContactUdp : public ::testing::TestWithParam<ToothPress> {};

TEST_P(HardContactUdp, TheReferenceClientFeelsTheTooth) {
  const testing::ContactBench& b = testing::ContactBench::get();
  const ToothFrame& f = b.tooth().frame();
  const DeviceProfile profile = device_profile("falcon");
  HardContact probe(profile.contact);
  const Vec3 start = f.to_world(GetParam().start_local);
  const testing::PressRun plan = testing::press(probe, b.field, b.shape, start, -f.z, 1e-3, 0.02, false, &b.tooth());
  ASSERT_TRUE(plan.touched);
  // The client's device origin is `start`; it goes to the hold point in 0.45 s (a smooth step) and stays.
  const Vec3 to = plan.device - start;
  RealtimeOptions o = contact_options();
  o.workspace.origin = start;
  o.duration_s = 2.5;
  std::uint16_t port = 0;
  auto device = make_udp_device({"127.0.0.1", 0}, &port);
  testing::ClientProcess client(port,
                                {"--wait", "30", "--duration", "1.2", "--motion", "hold", "--period", "1.5", "--depth",
                                 fmt::format("{:.9g}", norm(to)), "--axis", fmt::format("{:.9g}", to.x),
                                 fmt::format("{:.9g}", to.y), fmt::format("{:.9g}", to.z)},
                                std::string("udp_") + GetParam().name);
  ASSERT_TRUE(client.started());
  const RealtimeResult r = run_realtime(empty_cavity_scene(), *device, o);
  const nlohmann::json c = client.wait();
  ASSERT_FALSE(c.is_null()) << "the client failed";
  testing::expect_safe(r, profile);
  int held = 0;
  Vec3 last_force;
  for (const HapticSample& s : r.recording.haptic) {
    if (norm(s.device_position - to) > 1e-6 || s.gain < 1) continue;  // not yet there (device frame), or the watchdog acting
    ++held;
    const double behind = norm(s.contact_proxy - s.device_position);
    EXPECT_NEAR(behind, 1e-3, 0.1e-3) << "at " << s.t << " s";
    EXPECT_NEAR(norm(s.force), profile.contact.stiffness_N_per_m * behind, 0.1 * profile.contact.stiffness_N_per_m * behind)
        << "at " << s.t << " s";
    EXPECT_LT(testing::angle_deg(s.force, plan.surface_normal), 5.0) << "at " << s.t << " s";
    last_force = s.force;
  }
  EXPECT_GT(held, 300);
  // What the client received last is what the hand was held with.
  const Vec3 received{c["last_force_N"][0].get<double>(), c["last_force_N"][1].get<double>(), c["last_force_N"][2].get<double>()};
  EXPECT_NEAR(norm(received), profile.contact.stiffness_N_per_m * 1e-3, 0.1 * profile.contact.stiffness_N_per_m * 1e-3);
  EXPECT_LT(testing::angle_deg(received, plan.surface_normal), 5.0);
  EXPECT_EQ(c["forces_over_limit"].get<int>(), 0);
  EXPECT_EQ(c["wrenches_received"].get<int>(), 0) << "a 3-DoF client gets force packets";
}

INSTANTIATE_TEST_SUITE_P(Surfaces, HardContactUdp,
                         ::testing::Values(ToothPress{"enamel", {0, 2.6e-3, 6e-3}}, ToothPress{"floor", {0.5e-3, 0, 0.5e-3}}),
                         [](const auto& info) { return std::string(info.param.name); });

// A 6-DoF client (--torque) gets wrench packets: with the sigma.7's profile, the instrument lying
// across the tooth and pressed onto it, the shank meets the crown millimetres from the handle
// point and the client feels the torque of that lever (within the profile's limit); a client of a
// profile without torque output gets wrench packets whose torque is zero.
TEST(HardContactUdpTorque, ASixDofClientFeelsTheShanksTorque) {
  const testing::ContactBench& b = testing::ContactBench::get();
  const ToothFrame& f = b.tooth().frame();
  const Quat lying = Quat::from_axis_angle(f.x, 90 * std::numbers::pi / 180);  // as TheShankMeetsTheTooth
  const Vec3 start = f.to_world({0, 0, 4e-3});
  for (const char* name : {"sigma7", "falcon"}) {
    SCOPED_TRACE(name);
    const DeviceProfile profile = device_profile(name);
    // Where the shank touches going down, and 0.5 mm beyond.
    HardContact probe(profile.contact);
    probe.reset(start);
    Vec3 x = start;
    ContactResult touch;
    for (int k = 0; k < 600 && !touch.touching; ++k) {
      x -= f.z * 1e-5;
      touch = probe.update(b.field, b.shape, x, lying, {});
    }
    ASSERT_TRUE(touch.touching);
    const Vec3 to = x - f.z * 0.5e-3 - start;
    RealtimeOptions o = contact_options();
    o.profile = profile;
    o.workspace.origin = start;
    o.duration_s = 2.5;
    std::uint16_t port = 0;
    auto device = make_udp_device({"127.0.0.1", 0}, &port);
    testing::ClientProcess client(
        port,
        {"--wait", "30", "--duration", "1.2", "--motion", "hold", "--period", "1.5", "--torque", "--depth",
         fmt::format("{:.9g}", norm(to)), "--axis", fmt::format("{:.9g}", to.x), fmt::format("{:.9g}", to.y),
         fmt::format("{:.9g}", to.z), "--orientation", fmt::format("{:.17g}", lying.w), fmt::format("{:.17g}", lying.x),
         fmt::format("{:.17g}", lying.y), fmt::format("{:.17g}", lying.z), "--limit",
         fmt::format("{}", profile.max_force_N)},
        std::string("torque_") + name);
    ASSERT_TRUE(client.started());
    const RealtimeResult r = run_realtime(empty_cavity_scene(), *device, o);
    const nlohmann::json c = client.wait();
    ASSERT_FALSE(c.is_null()) << "the client failed";
    testing::expect_safe(r, profile);
    const nlohmann::json d = testing::realtime_sections(r)["device"];
    EXPECT_GT(c["wrenches_received"].get<int>(), 500);
    EXPECT_EQ(c["wrenches_received"], c["forces_received"]) << "every answer a wrench";
    EXPECT_EQ(d["wrenches_sent"], d["forces_sent"]);
    EXPECT_EQ(c["torques_over_limit"].get<int>(), 0);
    const Vec3 force{c["last_force_N"][0].get<double>(), c["last_force_N"][1].get<double>(), c["last_force_N"][2].get<double>()};
    const Vec3 torque{c["last_torque_N_m"][0].get<double>(), c["last_torque_N_m"][1].get<double>(),
                      c["last_torque_N_m"][2].get<double>()};
    EXPECT_GT(norm(force), 0.5 * profile.contact.stiffness_N_per_m * 0.5e-3) << "the shank pressed on the crown";
    if (profile.max_torque_N_m > 0) {
      EXPECT_GT(norm(torque) / norm(force), 2e-3) << "a lever of the shank's, not the ball's";
      EXPECT_LE(norm(torque), profile.max_torque_N_m * (1 + 1e-9));
      EXPECT_GT(c["max_torque_N_m"].get<double>(), 0);
    } else {
      EXPECT_EQ(c["max_torque_N_m"].get<double>(), 0) << "a device without torque output gets none";
    }
  }
}

// A quick move through air: the hand 3 mm above the paste heaped in the cavity moves 10 cm and holds
// still. The coupling's proxy goes with it (nothing within reach of its path): what the hand feels
// stays under 0.05 N (p95) and never reaches 0.2 N, during and after the move.
TEST(FreeMove, AQuickMoveThroughAirDragsNothing) {
  Scene scene = default_dental_scene();
  const Vec3 across = scene.tooth->frame().x;
  const Vec3 start = scene.tooth->frame().to_world({0, 0, 3.5e-3});
  for (const double speed : {0.5, 1.0, 2.0}) {
    const double move = 0.1 / speed;
    auto path = [=](double t) {
      // 0.2 s still, the move with smooth ends (a quintic of time), still again.
      const double u = std::clamp((t - 0.2) / move, 0.0, 1.0);
      const double s = u * u * u * (10 - 15 * u + 6 * u * u);
      return start + across * (0.1 * s);
    };
    const double peak = 0.1 / move * 1.875;  // the quintic's top speed
    testing::PathDevice device(path, 0.4 + move + 0.3);
    const RealtimeResult r = run_realtime(scene, device, contact_options());
    testing::expect_safe(r, device_profile("falcon"));
    std::vector<double> forces;
    double largest = 0;
    for (const HapticSample& s : r.recording.haptic)
      if (s.t >= 0.2) {
        forces.push_back(norm(s.force));
        largest = std::max(largest, norm(s.force));
      }
    ASSERT_GT(forces.size(), 100u);
    std::sort(forces.begin(), forces.end());
    const double p95 = forces[std::size_t(0.95 * double(forces.size() - 1))];
    std::printf("free move at %.1f m/s (peak %.2f m/s): force p95 %.4f N, largest %.4f N\n", speed, peak, p95, largest);
    EXPECT_LE(p95, 0.05) << speed << " m/s";
    EXPECT_LT(largest, 0.2) << speed << " m/s";
  }
}

// From a quick move down the tooth's axis into the paste heaped in the cavity: the proxy goes freely up to where the
// paste is within reach, then on under the step's speed limit; the force the renderer asks for
// never steps by more than the profile's rate limit in a tick.
TEST(FreeMove, EnteringPasteFromAQuickMoveDoesNotJolt) {
  if (testing::kUnderThreadSanitizer)
    GTEST_SKIP() << "a 60 ms move into paste against a simulation at a tenth of real time (ThreadSanitizer) meets "
                    "the paste anywhere or not at all";
  Scene scene = default_dental_scene();
  const ToothFrame& f = scene.tooth->frame();
  const Vec3 from = f.to_world({0, 0, 30e-3}), to = f.to_world({0, 0, -0.5e-3});
  const double move = norm(to - from) / 0.5;  // 0.5 m/s
  auto path = [=](double t) { return from + (to - from) * std::clamp((t - 0.1) / move, 0.0, 1.0); };
  testing::PathDevice device(path, 0.1 + move + 0.4);
  const DeviceProfile profile = device_profile("falcon");
  const RealtimeResult r = run_realtime(scene, device, contact_options());
  testing::expect_safe(r, profile);
  double largest_step = 0, largest = 0;
  for (std::size_t k = 1; k < r.recording.haptic.size(); ++k) {
    const HapticSample &a = r.recording.haptic[k - 1], &b = r.recording.haptic[k];
    largest_step = std::max(largest_step, norm(b.target - a.target));
    largest = std::max(largest, norm(b.target));
  }
  std::printf("entering paste at 0.5 m/s: largest force %.3f N, largest step %.3f N a tick\n", largest, largest_step);
  EXPECT_GT(largest, 0.05) << "the paste was met";
  EXPECT_LE(largest_step, profile.max_force_rate_N_per_s * 1e-3);
}

}  // namespace
}  // namespace dentsph
