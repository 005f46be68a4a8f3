// The haptic runtime's parts on their own: the triple buffer, the wire format, the force limiter,
// the watchdog, the interpolator, the scripted hand's path, the virtual coupling, the timing histogram, the recording and
// the passivity measure.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "dentsph/haptics.hpp"
#include "dentsph/haptics/protocol.hpp"
#include "dentsph/haptics/replay.hpp"
#include "haptics/clock.hpp"
#include "haptics/exchange.hpp"
#include "haptics/force_interpolator.hpp"
#include "haptics/force_limiter.hpp"
#include "haptics/passivity_control.hpp"
#include "haptics/force_renderer.hpp"
#include "haptics/hand_path.hpp"
#include "haptics/haptic_loop.hpp"
#include "haptics/shared.hpp"
#include "haptics/sim_loop.hpp"
#include "haptics/timing_stats.hpp"
#include "haptics/virtual_coupling.hpp"
#include "haptics/watchdog.hpp"

namespace dentsph {
namespace {

namespace proto = haptic_protocol;
using haptics::TripleBuffer;

TEST(TripleBuffer, ReaderSeesTheNewestValueOnce) {
  TripleBuffer<int> b;
  EXPECT_FALSE(b.update());
  b.back() = 1;
  b.publish();
  b.back() = 2;
  b.publish();
  EXPECT_TRUE(b.update());
  EXPECT_EQ(b.front(), 2);
  EXPECT_FALSE(b.update());
  EXPECT_EQ(b.front(), 2);
  b.back() = 3;
  b.publish();
  EXPECT_TRUE(b.update());
  EXPECT_EQ(b.front(), 3);
}

// Two threads: the reader never sees a torn value, and values only move forward.
TEST(TripleBuffer, ConcurrentValuesAreWholeAndInOrder) {
  struct Payload {
    std::uint64_t k = 0;
    double a[8] = {};
  };
  TripleBuffer<Payload> b;
  constexpr std::uint64_t n = 200000;
  std::thread writer([&] {
    for (std::uint64_t k = 1; k <= n; ++k) {
      Payload& p = b.back();
      p.k = k;
      for (int i = 0; i < 8; ++i) p.a[i] = double(k) * (i + 1);
      b.publish();
    }
  });
  std::uint64_t last = 0, torn = 0, backwards = 0, taken = 0;
  while (last < n) {
    if (!b.update()) continue;
    const Payload& p = b.front();
    ++taken;
    for (int i = 0; i < 8; ++i) torn += p.a[i] != double(p.k) * (i + 1);
    backwards += p.k <= last;
    last = p.k;
  }
  writer.join();
  EXPECT_EQ(torn, 0u);
  EXPECT_EQ(backwards, 0u);
  EXPECT_GT(taken, 0u);
}

TEST(Protocol, PoseAndForceRoundTripExactly) {
  std::array<std::uint8_t, proto::kMaxPacketBytes> buf{};
  proto::PosePacket p;
  p.header.sequence = 0xfffffffe;
  p.header.timestamp_ns = 123456789012345ull;
  p.position[0] = 0.1, p.position[1] = -2e-7, p.position[2] = 3.25;
  p.orientation[0] = 0.5, p.orientation[1] = 0.5, p.orientation[2] = -0.5, p.orientation[3] = 0.5;
  p.buttons = 5;
  ASSERT_EQ(proto::encode(p, buf), proto::kPoseBytes);
  EXPECT_EQ(buf[0], 'D');
  EXPECT_EQ(buf[4], proto::kVersion);
  EXPECT_EQ(buf[5], 1);
  EXPECT_EQ(buf[8], 0xfe);  // little-endian sequence
  EXPECT_EQ(buf[11], 0xff);
  proto::PosePacket q;
  ASSERT_EQ(proto::decode(std::span<const std::uint8_t>(buf.data(), proto::kPoseBytes), q), proto::DecodeError::none);
  EXPECT_EQ(q.header.sequence, p.header.sequence);
  EXPECT_EQ(q.header.timestamp_ns, p.header.timestamp_ns);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(q.position[i], p.position[i]);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(q.orientation[i], p.orientation[i]);
  EXPECT_EQ(q.buttons, 5u);

  proto::ForcePacket f;
  f.header.sequence = 7;
  f.force[0] = -1.5, f.force[1] = 2.0, f.force[2] = 8.999;
  f.pose_sequence = 99, f.status = proto::kSimStale, f.pose_timestamp_ns = 42, f.force_age_us = 1234;
  ASSERT_EQ(proto::encode(f, buf), proto::kForceBytes);
  proto::ForcePacket g;
  ASSERT_EQ(proto::decode(std::span<const std::uint8_t>(buf.data(), proto::kForceBytes), g), proto::DecodeError::none);
  EXPECT_EQ(g.force[2], 8.999);
  EXPECT_EQ(g.pose_sequence, 99u);
  EXPECT_EQ(g.status, std::uint32_t(proto::kSimStale));
  EXPECT_EQ(g.pose_timestamp_ns, 42u);
  EXPECT_EQ(g.force_age_us, 1234u);
  for (double v : g.torque) EXPECT_EQ(v, 0);  // a force packet carries no torque

  // A wrench: the force packet's bytes, then the torque; its type says which.
  f.torque[0] = 0.25, f.torque[1] = -0.125, f.torque[2] = 0.375;
  ASSERT_EQ(proto::encode(f, buf, true), proto::kWrenchBytes);
  EXPECT_EQ(buf[5], std::uint8_t(proto::Type::wrench));
  ASSERT_EQ(proto::decode(std::span<const std::uint8_t>(buf.data(), proto::kWrenchBytes), g), proto::DecodeError::none);
  EXPECT_EQ(g.header.type, proto::Type::wrench);
  EXPECT_EQ(g.force[2], 8.999);
  EXPECT_EQ(g.torque[0], 0.25);
  EXPECT_EQ(g.torque[1], -0.125);
  EXPECT_EQ(g.torque[2], 0.375);
  EXPECT_EQ(proto::decode(std::span<const std::uint8_t>(buf.data(), proto::kForceBytes), g), proto::DecodeError::bad_length);
  f.torque[1] = std::numeric_limits<double>::quiet_NaN();
  proto::encode(f, buf, true);
  EXPECT_EQ(proto::decode(std::span<const std::uint8_t>(buf.data(), proto::kWrenchBytes), g), proto::DecodeError::non_finite);

  // A pose's capabilities (the bytes a version-1.0 pose left zero).
  p.capabilities = proto::kCapabilityTorque;
  proto::encode(p, buf);
  ASSERT_EQ(proto::decode(std::span<const std::uint8_t>(buf.data(), proto::kPoseBytes), q), proto::DecodeError::none);
  EXPECT_EQ(q.capabilities, proto::kCapabilityTorque);
}

TEST(Protocol, RefusesEveryKindOfBadDatagram) {
  std::array<std::uint8_t, proto::kMaxPacketBytes> buf{};
  proto::PosePacket p;
  const std::size_t n = proto::encode(p, buf);
  proto::PosePacket q;
  auto decode = [&](std::size_t len) { return proto::decode(std::span<const std::uint8_t>(buf.data(), len), q); };
  EXPECT_EQ(decode(10), proto::DecodeError::too_short);
  EXPECT_EQ(decode(n - 1), proto::DecodeError::bad_length);
  auto tampered = [&](std::size_t at, std::uint8_t v) {
    const std::uint8_t old = buf[at];
    buf[at] = v;
    const proto::DecodeError e = decode(n);
    buf[at] = old;
    return e;
  };
  EXPECT_EQ(tampered(0, 'X'), proto::DecodeError::bad_magic);
  EXPECT_EQ(tampered(4, 9), proto::DecodeError::bad_version);
  EXPECT_EQ(tampered(5, 77), proto::DecodeError::bad_type);
  EXPECT_EQ(tampered(5, std::uint8_t(proto::Type::heartbeat)), proto::DecodeError::bad_length);
  p.position[1] = std::numeric_limits<double>::quiet_NaN();
  proto::encode(p, buf);
  EXPECT_EQ(decode(n), proto::DecodeError::non_finite);
  p.position[1] = 0;
  p.orientation[0] = 0;
  proto::encode(p, buf);
  EXPECT_EQ(decode(n), proto::DecodeError::non_finite);  // no rotation in a zero quaternion
}

TEST(Protocol, SequencesCompareAcrossTheWrap) {
  EXPECT_TRUE(proto::sequence_newer(1, 0));
  EXPECT_TRUE(proto::sequence_newer(0, 0xffffffff));
  EXPECT_FALSE(proto::sequence_newer(0xffffffff, 0));
  EXPECT_FALSE(proto::sequence_newer(5, 5));
}

// Time-domain passivity control (haptics/passivity_control.hpp). The hand is a position source
// moving back and forth (2 mm at 2 Hz) at 1 kHz ticks.
namespace passivity {
constexpr double T = 1e-3, A = 2e-3, w = 2 * std::numbers::pi * 2;
Vec3 hand(int k) { return {A * std::sin(w * k * T), 0, 0}; }
Vec3 hand_velocity(int k) { return {A * w * std::cos(w * k * T), 0, 0}; }
}  // namespace passivity

// A spring with enough damping for its tick (b > k T / 2: Colgate & Schenkel's condition) takes
// energy from the hand: the control never acts and sends every force unchanged.
TEST(PassivityControl, APassiveRenderingIsSentUnchanged) {
  using namespace passivity;
  haptics::PassivityControl pc;
  const double k = 400, b = 2;
  for (int n = 0; n < 2000; ++n) {
    pc.observe(hand(n));
    const Vec3 f = hand(n) * -k - hand_velocity(n) * b;
    const Vec3 sent = pc.correct(f, hand_velocity(n), T);
    ASSERT_EQ(sent, f) << "tick " << n;
    pc.sent(sent);
  }
  EXPECT_EQ(pc.damped_ticks(), 0u);
  EXPECT_LT(pc.energy_J(), 0) << "the hand's work taken in";
}

// A force that pushes the hand along its motion (a negative damper, as a late simulation's force
// can be) would give it energy every cycle. The control damps the excess back each tick: the energy
// done on the hand stays within one tick's work of zero, where without it it grows.
TEST(PassivityControl, AnActiveRenderingIsDampedBackToPassive) {
  using namespace passivity;
  haptics::PassivityControl pc, raw;
  const double c = 3;  // N s/m along the motion
  double most = 0, tick_work = 0;
  for (int n = 0; n < 2000; ++n) {
    pc.observe(hand(n));
    raw.observe(hand(n));
    const Vec3 f = hand_velocity(n) * c;
    pc.sent(pc.correct(f, hand_velocity(n), T));
    raw.sent(f);
    most = std::max(most, pc.energy_J());
    tick_work = std::max(tick_work, c * norm2(hand_velocity(n)) * T);
  }
  EXPECT_GT(raw.energy_J(), 1e-3) << "J: the raw force gives the hand energy";
  EXPECT_GT(pc.damped_ticks(), 1000u);
  EXPECT_LE(most, 2 * tick_work) << "J: the controlled force gives back what it gave within a tick";
  EXPECT_LT(pc.energy_J(), 0.01 * raw.energy_J());
}

// A session starts owing nothing; a hand at rest or a tick of no time is not damped (alpha would
// be infinite), nor is a non-finite velocity used.
TEST(PassivityControl, ASessionStartsOwingNothing) {
  using namespace passivity;
  haptics::PassivityControl pc;
  pc.observe({0, 0, 0});
  pc.sent({1, 0, 0});
  pc.observe({1e-3, 0, 0});  // 1 mJ given to the hand
  EXPECT_NEAR(pc.energy_J(), 1e-3, 1e-15);
  const Vec3 f{0.5, 0, 0};
  EXPECT_EQ(pc.correct(f, {}, T), f) << "at rest";
  EXPECT_EQ(pc.correct(f, {0.1, 0, 0}, 0), f) << "no time";
  EXPECT_EQ(pc.correct(f, {NAN, 0, 0}, T), f) << "not finite";
  const Vec3 damped = pc.correct(f, {0.1, 0, 0}, T);
  EXPECT_NEAR(damped.x, 0.5 - haptics::PassivityControl::kMaxDamping * 0.1, 1e-12)
      << "alpha = E / (|v|^2 dt) = 1e5 N s/m, capped";
  const Vec3 fast = pc.correct(f, {20, 0, 0}, T);
  EXPECT_NEAR(fast.x, 0.5 - 1e-3 / (400 * T) * 20, 1e-12) << "alpha = E / (|v|^2 dt) = 2.5 N s/m";
  // Energy given back within kTolerance of what the hand put in is left alone.
  haptics::PassivityControl tol;
  tol.observe({0, 0, 0});
  tol.sent({-1, 0, 0});
  tol.observe({1e-3, 0, 0});  // the hand put in 1 mJ
  tol.sent({1, 0, 0});
  tol.observe({2.004e-3, 0, 0});  // 1.004 mJ back: 4 uJ more than it put in, within 0.5% of 1 mJ
  EXPECT_EQ(tol.correct(f, {0.1, 0, 0}, T), f);
  tol.observe({2.008e-3, 0, 0});  // 8 uJ more: 3 uJ beyond
  EXPECT_NEAR(tol.correct(f, {0.1, 0, 0}, T).x, 0.5 - 3e-6 / (0.01 * T) * 0.1, 1e-9);
  pc.reset();
  EXPECT_EQ(pc.energy_J(), 0);
  EXPECT_EQ(pc.correct(f, {0.1, 0, 0}, T), f);
  pc.observe({5e-3, 0, 0});  // the first position of a session does no work
  EXPECT_EQ(pc.energy_J(), 0);
}

TEST(ForceLimiter, NeverSendsNonFiniteOrTooLargeOrTooSudden) {
  const DeviceProfile falcon = device_profile("falcon");
  haptics::ForceLimiter lim(falcon);
  const double dt = 1e-3, step = falcon.max_force_rate_N_per_s * dt;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  Vec3 prev;
  const Vec3 inputs[] = {{0, 0, 100}, {nan, 0, 0}, {0, inf, 0}, {-50, 0, 0}, {3, 4, 0}, {3, 4, 0}, {0, 0, 0}};
  for (int rep = 0; rep < 20; ++rep)
    for (const Vec3& in : inputs) {
      const auto r = lim.apply(in, dt);
      ASSERT_TRUE(is_finite(r.force));
      EXPECT_LE(norm(r.force), falcon.max_force_N + 1e-12);
      EXPECT_LE(norm(r.force - prev), step + 1e-12);
      prev = r.force;
    }
  // A steady 5 N is reached and held exactly.
  for (int k = 0; k < 20; ++k) lim.apply({3, 4, 0}, dt);
  EXPECT_EQ(lim.apply({3, 4, 0}, dt).force, (Vec3{3, 4, 0}));
  EXPECT_TRUE(lim.apply({nan, 0, 0}, dt).non_finite);
  DeviceProfile bad = falcon;
  bad.max_force_N = -1;
  EXPECT_THROW(haptics::ForceLimiter{bad}, std::invalid_argument);
  EXPECT_THROW(device_profile("phantom"), std::invalid_argument);
  EXPECT_EQ(device_profile("omega").max_force_N, 12.0);
  // The hard contact's settings: CHAI3D's for the Falcon and the omega, torque on the sigma.7 only.
  EXPECT_EQ(falcon.contact.stiffness_N_per_m, 3000);
  EXPECT_EQ(falcon.contact.damping_N_s_per_m, 20);
  EXPECT_EQ(device_profile("omega").contact.stiffness_N_per_m, 5000);
  EXPECT_EQ(falcon.max_torque_N_m, 0);
  EXPECT_GT(device_profile("sigma7").max_torque_N_m, 0);
}

TEST(Watchdog, RampsDownOnAFaultAndUpAfterRecovery) {
  WatchdogParams p;  // timeouts 25 / 20 ms, ramps 10 / 100 ms
  haptics::Watchdog w(p);
  const double dt = 1e-3;
  double g = 0;
  for (int k = 0; k < 150; ++k) g = w.update(0.001, 0.001, dt);
  EXPECT_DOUBLE_EQ(g, 1.0);
  EXPECT_EQ(w.trips(), 0u);
  // The simulation goes quiet: ages beyond the timeout.
  double prev = g;
  int ticks_to_zero = 0;
  for (int k = 0; k < 30; ++k) {
    g = w.update(0.03 + k * dt, 0.001, dt);
    EXPECT_LE(prev - g, dt / p.ramp_down_s + 1e-12);  // a ramp, not a step
    if (g > 0) ++ticks_to_zero;
    prev = g;
  }
  EXPECT_EQ(g, 0.0);
  EXPECT_LE(ticks_to_zero, 10);
  EXPECT_TRUE(w.sim_stale());
  EXPECT_EQ(w.trips(), 1u);
  for (int k = 0; k < 50; ++k) g = w.update(0.001, 0.001, dt);
  EXPECT_NEAR(g, 0.5, 1e-9);
  // The pose goes stale (or never came: a negative age).
  EXPECT_LT(w.update(0.001, -1, dt), 0.5);
  EXPECT_TRUE(w.pose_stale());
  EXPECT_EQ(w.trips(), 2u);
}

TEST(ForceInterpolator, ContinuousBetweenSlowSamples) {
  haptics::ForceInterpolator f;
  const std::int64_t ms = 1'000'000;
  // Samples every 10 ms alternating 0 and 1 N; read every 1 ms.
  double max_step = 0;
  Vec3 prev;
  for (std::int64_t t = 0; t < 500 * ms; t += ms) {
    if (t % (10 * ms) == 0) f.add({0, 0, double((t / (10 * ms)) % 2)}, t);
    const Vec3 v = f.at(t);
    if (t > 50 * ms) max_step = std::max(max_step, norm(v - prev));
    prev = v;
  }
  EXPECT_NEAR(f.interval_s(), 0.01, 1e-6);
  EXPECT_LE(max_step, 0.1 + 1e-9);  // 1 N spread over the 10 ticks of a sample interval
}

TEST(ForceInterpolator, NoJumpWhenASampleComesEarlyOrLate) {
  // Gaps of 8 and 12 ms in turn move the filtered interval at every sample; the output must not
  // step at the moment a sample arrives (it starts from where it was).
  haptics::ForceInterpolator f;
  const std::int64_t ms = 1'000'000;
  std::int64_t t = 0;
  double worst = 0;
  for (int k = 0; k < 60; ++k) {
    t += (k % 2 ? 8 : 12) * ms;
    const Vec3 before = f.at(t);
    f.add({0, 0, double(k % 2)}, t);
    if (k > 0) worst = std::max(worst, double(norm(f.at(t) - before)));
  }
  EXPECT_LE(worst, 1e-12);
}

// A step that is not a whole number of haptic ticks publishes on whole ticks: every second 1.5 ms
// step at 1 kHz (3 ticks); whole-tick steps, steps under a tick and steps no small multiple of
// which is whole publish every step.
TEST(SimLoop, PublishesOnWholeHapticTicks) {
  EXPECT_EQ(haptics::publish_every(1.5e-3, 1000), 2);
  EXPECT_EQ(haptics::publish_every(2.5e-3, 1000), 2);
  EXPECT_EQ(haptics::publish_every(1.25e-3, 1000), 4);
  EXPECT_EQ(haptics::publish_every(1.5e-3, 2000), 1) << "3 ticks of 0.5 ms";
  EXPECT_EQ(haptics::publish_every(2e-3, 1000), 1);
  EXPECT_EQ(haptics::publish_every(1e-3, 1000), 1);
  EXPECT_EQ(haptics::publish_every(5e-5, 1000), 1) << "the paper's step: many a tick";
  EXPECT_EQ(haptics::publish_every(1.19e-3, 1000), 1) << "no multiple up to 8 is whole";
  EXPECT_EQ(haptics::publish_every(std::nan(""), 1000), 1);
}

TEST(VirtualCoupling, StableAtAnyStiffnessAndBalancingTheToolForce) {
  for (const double k : {100.0, 1e4, 1e7}) {
    CouplingParams p;
    p.stiffness_N_per_m = k;
    haptics::VirtualCoupling c(p);
    c.reset({0, 0, 0});
    Vec3 f;
    // The device 1 cm down, the tool pushed up by a constant 1 N: the proxy settles where the
    // spring balances it, 1 N / k above the device, without oscillating out of bounds.
    for (int i = 0; i < 20000; ++i) {
      c.step({0, 0, -0.01}, {}, {0, 0, 1}, 1e-3);
      f = haptics::coupling_force(p, c.position(), c.velocity(), {0, 0, -0.01}, {});
      ASSERT_TRUE(is_finite(f));
      ASSERT_LE(std::abs(c.position().z), 0.02);
    }
    EXPECT_NEAR(f.z, 1.0, 1e-6) << k;  // the hand feels the tool force
    EXPECT_NEAR(c.position().z, -0.01 + 1 / k, 1e-9) << k;
  }
  EXPECT_THROW(haptics::VirtualCoupling(CouplingParams{-1, 1, 1, 1}), std::invalid_argument);
}

// The tool force comes from the last simulation step: a stiff contact at the iisph solver's 1 ms
// step (the flat plugger on paste, about 4e6 N/m at the device) against an explicit proxy of 50 g
// returned a force of alternating sign every step. The coupling takes the contact's stiffness,
// estimated from the steps, implicitly: the proxy settles on the wall without ringing, and in air
// the estimate decays to nothing.
TEST(VirtualCoupling, AStiffContactAtAMillisecondStepSettlesWithoutRinging) {
  const CouplingParams p;  // 400 N/m, 50 g
  const double dt = 1e-3, wall_k = 4e6, device_z = -0.002;  // the device 2 mm into a wall at z = 0
  haptics::VirtualCoupling c(p);
  c.reset({0, 0, 0.001});
  auto wall = [&](const Vec3& x) { return Vec3{0, 0, x.z < 0 ? -wall_k * x.z : 0}; };
  Vec3 force = wall(c.position());
  std::vector<double> forces;
  double largest_estimate = 0;
  for (int i = 0; i < 400; ++i) {
    c.step({0, 0, device_z}, {}, force, dt);  // the tool force of the step before
    force = wall(c.position());               // this step's, where the proxy put the tool
    ASSERT_TRUE(is_finite(force));
    forces.push_back(force.z);
    largest_estimate = std::max(largest_estimate, c.tool_stiffness());
  }
  // Equilibrium: the coupling's spring pulls the proxy down as hard as the wall pushes it up.
  const double settled = p.stiffness_N_per_m * wall_k / (p.stiffness_N_per_m + wall_k) * -device_z;
  EXPECT_NEAR(forces.back(), settled, 1e-3 * settled);
  double largest_change = 0;
  int sign_flips = 0;
  for (std::size_t i = 300; i < forces.size(); ++i) {
    largest_change = std::max(largest_change, std::abs(forces[i] - forces[i - 1]));
    sign_flips += (forces[i] - forces[i - 1]) * (forces[i - 1] - forces[i - 2]) < 0;
  }
  EXPECT_LT(largest_change, 1e-3 * settled) << "the contact rings";
  EXPECT_LE(sign_flips, 2);
  EXPECT_NEAR(largest_estimate, wall_k, 0.1 * wall_k);  // found the wall's stiffness
  // Lifted off into air: no tool force, the estimate decays and the proxy follows the device freely.
  for (int i = 0; i < 400; ++i) c.step({0, 0, 0.01}, {}, {}, dt);
  EXPECT_EQ(c.tool_stiffness(), 0);
  EXPECT_NEAR(c.position().z, 0.01, 1e-4);
}

TEST(DurationHistogram, Quantiles) {
  haptics::DurationHistogram h;
  for (int i = 1; i <= 1000; ++i) h.add(i);
  EXPECT_EQ(h.count(), 1000u);
  EXPECT_NEAR(h.quantile(0.5), 500, 1);
  EXPECT_NEAR(h.quantile(0.99), 990, 1);
  EXPECT_EQ(h.max(), 1000);
  h.add(1e9);  // beyond the bins: counted, exact maximum
  EXPECT_EQ(h.max(), 1e9);
  EXPECT_EQ(h.quantile(1.0), 1e9);
}

TEST(Passivity, EnergyToHandOfASpringAndOfAnActiveForce) {
  // The hand moves sinusoidally against a spring to a fixed point: the energy it gets back never
  // exceeds what it put in (E <= 0 up to rounding). A force along the velocity is active.
  std::vector<HapticSample> spring, active;
  for (int i = 0; i <= 2000; ++i) {
    HapticSample s;
    s.t = i * 1e-3;
    const double x = 0.01 * std::sin(2 * M_PI * s.t), v = 0.01 * 2 * M_PI * std::cos(2 * M_PI * s.t);
    s.device_position = {0, 0, x};
    s.force = {0, 0, -500 * x};
    spring.push_back(s);
    s.force = {0, 0, 50 * v};
    active.push_back(s);
  }
  const auto e = energy_to_hand(spring);
  for (double v : e) EXPECT_LE(v, 1e-4);
  EXPECT_GT(energy_to_hand(active).back(), 0.1);
}

// Between two recorded ticks the replay device moves the position linearly and turns the
// orientation by slerp (not held at the earlier sample's).
TEST(ReplayDevice, InterpolatesPositionAndOrientationBetweenSamples) {
  Recording r;
  r.mode = "direct";
  const Quat q0 = Quat::from_axis_angle({0, 0, 1}, 0.0), q1 = Quat::from_axis_angle({0, 0, 1}, 1.2);
  for (int i = 0; i < 2; ++i) {
    HapticSample h;
    h.t = 0.1 * i;
    h.device_position = {0.01 * i, 0, 0};
    h.device_orientation = i == 0 ? q0 : q1;
    r.haptic.push_back(h);
  }
  const auto dir = std::filesystem::temp_directory_path() / ("dentsph_replay_slerp_test_" + std::to_string(::getpid()));
  save_recording(dir, r);
  const std::unique_ptr<Device> dev = make_replay_device(dir);
  dev->start(0);
  for (const double w : {0.0, 0.25, 0.5, 1.0}) {
    DeviceSample s;
    ASSERT_TRUE(dev->read(std::int64_t(w * 0.1e9), s));
    EXPECT_NEAR(s.pose.position.x, 0.01 * w, 1e-12) << w;
    // A unit vector along x turned by w * 1.2 rad about z.
    const Vec3 turned = s.pose.orientation.rotate({1, 0, 0});
    EXPECT_NEAR(turned.x, std::cos(1.2 * w), 1e-9) << w;
    EXPECT_NEAR(turned.y, std::sin(1.2 * w), 1e-9) << w;
  }
}

// A device held still that keeps every force it is sent (written on the haptic thread, read
// after it has stopped; the count is shared).
class HoldDevice final : public Device {
 public:
  std::string name() const override { return "hold"; }
  bool read(std::int64_t now, DeviceSample& s) override {
    s.pose = {};
    s.stamp_ns = now;
    s.device_time_s = double(now) * 1e-9;
    ++s.sequence;
    s.valid = true;
    return true;
  }
  void write(std::int64_t, const ForceCommand& c) override {
    const std::size_t i = count.load(std::memory_order_relaxed);
    if (i < forces.size()) forces[i] = c.force_N, count.store(i + 1, std::memory_order_release);
  }
  std::vector<Vec3> forces = std::vector<Vec3>(60000);
  std::atomic<std::size_t> count{0};
};

// The haptic loop's screen of the simulation's output: a 100 N force (direct) or a proxy a metre
// away (coupling) is rendered limited to the profile's 9 N; then non-finite outputs arrive
// through the exchange, as from a diverging simulation: each is counted and rendered as no
// force (the renderer never sees it), and every force the device gets is finite and within the
// limit.
TEST(HapticLoop, ScreensNonFiniteSimulationOutput) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const ForceMode mode : {ForceMode::direct, ForceMode::coupling}) {
    RealtimeOptions o;
    o.mode = mode;
    o.record_capacity_s = 40;  // a loaded host may stretch the two phases well past their 600 ms
    haptics::RuntimeShared shared{haptics::Snapshot{}, haptics::ContactWorld{}, haptics::RigidInput{}};
    HoldDevice device;
    haptics::HapticLoop loop(device, o, shared);
    std::thread haptic([&] { loop.run(haptics::now_ns()); });
    std::uint64_t step = 0;
    // Publishes an output every millisecond for at least `ms` ms and until the haptic loop has
    // ticked `ticks` times since (a loaded host may give it far fewer ticks than milliseconds).
    auto publish = [&](const Vec3& v, int ms, std::size_t ticks) {
      const std::size_t from = device.count.load(std::memory_order_acquire);
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
      for (int i = 0; i < ms || (device.count.load(std::memory_order_acquire) < from + ticks &&
                                 std::chrono::steady_clock::now() < deadline);
           ++i) {
        haptics::SimOutput& out = shared.output.back();
        out = {};
        (mode == ForceMode::direct ? out.force_N : out.proxy_position) = v;
        if (!is_finite(v)) out.force_N = out.proxy_position = out.proxy_velocity = v;
        out.step = ++step;
        out.published_ns = out.command_stamp_ns = haptics::now_ns();
        out.valid = true;
        shared.output.publish();
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    };
    publish({0, 0, 100}, 300, 150);
    const std::size_t finite_until = device.count.load(std::memory_order_acquire);
    publish({nan, 0, inf}, 300, 150);
    shared.stop = true;
    haptic.join();
    const std::size_t n = device.count.load(std::memory_order_acquire);
    ASSERT_GT(finite_until, 100u);
    ASSERT_GT(n, finite_until + 100);
    double largest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_TRUE(is_finite(device.forces[i])) << i;
      ASSERT_LE(norm(device.forces[i]), o.profile.max_force_N + 1e-12) << i;
      if (i < finite_until) largest = std::max(largest, double(norm(device.forces[i])));
    }
    const char* name = force_mode_name(mode);
    EXPECT_NEAR(largest, o.profile.max_force_N, 1e-9) << name;  // rendered, and limited
    EXPECT_LT(norm(device.forces[n - 1]), 1e-9) << name;       // the non-finite output: no force
    // Every output the loop took in the second phase was non-finite and screened; under load the
    // loop may take fewer than the 300 published (a stalled tick sees only the newest), so the
    // count is at least one and at most what was published, and is printed.
    const std::uint64_t rejected = loop.report().non_finite_rejected;
    std::printf("%s: %llu non-finite outputs screened of 300 published\n", name, (unsigned long long)rejected);
    EXPECT_GE(rejected, 1u) << name;
    EXPECT_LE(rejected, 2 * (n - finite_until) + 2) << name;  // the screen and the limiter, at most once a tick each
    // The screen sits before the renderer: what it renders (before the watchdog and the
    // limiter) and the proxy it follows stay finite throughout.
    const std::vector<HapticSample> ticks = loop.take_recording();
    ASSERT_GE(ticks.size(), n - 1);
    for (const HapticSample& t : ticks) {
      ASSERT_TRUE(is_finite(t.target)) << name << " at " << t.t;
      ASSERT_TRUE(is_finite(t.proxy_position)) << name << " at " << t.t;
    }
  }
}

TEST(Recording, SavesAndLoadsExactly) {
  Recording r;
  r.mode = "coupling";
  for (int i = 0; i < 5; ++i) {
    HapticSample h;
    h.t = i / 3.0;
    h.device_position = {1.0 / 7, -i * 1e-9, 3};
    h.force = {0.1 * i, 1e-300, -2};
    h.gain = 0.3;
    h.status = 5;
    h.pose_sequence = 4000000000u;
    r.haptic.push_back(h);
    StepSample s;
    s.step = std::uint64_t(i);
    s.tool_pose.position = {M_PI, 0, i / 11.0};
    s.tool_pose.orientation = Quat::from_axis_angle({1, 2, 3}, 0.3);
    s.tool_force = {1e-5 / 3, 0, 0};
    r.steps.push_back(s);
  }
  r.events.push_back({3, 1});
  r.events.push_back({3, kButtonIncrement});
  r.events.push_back(tool_switch_event(4, "condenser"));
  EXPECT_EQ(r.events.back().index, kToolSwitch + 2);
  EXPECT_THROW(tool_switch_event(4, "drill"), std::invalid_argument);
  r.haptic_rate_hz = 1000.0 / 3;
  r.force_scale = 1.5e4;
  r.haptic_dropped = 7;
  r.dispense_volume = 1e-9 / 3;
  r.solver = "iisph";
  const auto dir = std::filesystem::temp_directory_path() / ("dentsph_recording_test_" + std::to_string(::getpid()));
  save_recording(dir, r);
  const Recording q = load_recording(dir);
  EXPECT_EQ(q.mode, r.mode);
  EXPECT_EQ(q.haptic_rate_hz, r.haptic_rate_hz);
  EXPECT_EQ(q.force_scale, r.force_scale);
  EXPECT_EQ(q.haptic_dropped, r.haptic_dropped);
  EXPECT_EQ(q.dispense_volume, r.dispense_volume);
  EXPECT_EQ(q.solver, "iisph") << "the step that ran the session";
  ASSERT_EQ(q.haptic.size(), 5u);
  ASSERT_EQ(q.steps.size(), 5u);
  ASSERT_EQ(q.events.size(), 3u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(q.haptic[i].t, r.haptic[i].t);
    EXPECT_EQ(q.haptic[i].device_position, r.haptic[i].device_position);
    EXPECT_EQ(q.haptic[i].force, r.haptic[i].force);
    EXPECT_EQ(q.haptic[i].pose_sequence, r.haptic[i].pose_sequence);
    EXPECT_EQ(q.steps[i].tool_pose.position, r.steps[i].tool_pose.position);
    EXPECT_EQ(q.steps[i].tool_pose.orientation.x, r.steps[i].tool_pose.orientation.x);
    EXPECT_EQ(q.steps[i].tool_force, r.steps[i].tool_force);
  }
  EXPECT_EQ(q.events[0].step, 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(q.events[k].index, r.events[k].index) << k;
  EXPECT_EQ(q.events[2].step, 4u);
  // A broken file is named with its line.
  { std::ofstream(dir / "steps.csv") << "step,wall_t,x,y,z,qw,qx,qy,qz,fx,fy,fz\n1,2,3\n"; }
  try {
    load_recording(dir);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("steps.csv: line 2"), std::string::npos) << e.what();
  }
  // A file larger than a session writes is refused before it is read (sparse files): reading it
  // would take about twice its size in memory.
  auto refused_when = [&](const char* file, std::uintmax_t mb, const std::string& expected) {
    save_recording(dir, r);
    std::filesystem::resize_file(dir / file, mb << 20);
    try {
      load_recording(dir);
      ADD_FAILURE() << file << " of " << mb << " MB was read";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused_when("haptic.csv", 600, "haptic.csv: 600 MB, more than the 512 MB a recording's file can be");
  refused_when("session.json", 2, "session.json: 2 MB, more than the 1 MB");
  // steps.csv may be as large as the most steps a realtime run records (limits::max_recorded_steps):
  // 600 MB is read, and this one (its 5 rows, then NUL bytes) refused for its line 7, not its size.
  refused_when("steps.csv", 600, "steps.csv: line 7, column 1 (step)");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

TEST(SceneFile, HapticsForceScaleIsReadAndChecked) {
  const std::string base = R"({"name": "s", "simulation": {"dt": 1e-4, "h": 0.02},
    "adhesion": {"A": 0.012, "B": 0.03},
    "materials": {"paste": {"viscosity": 0.5, "stiffness": 60, "rest_density": 1000, "adhesion": 0}},
    "roles": {"material": "paste"},
    "blocks": [{"role": "material", "shape": "box", "min": [0, 0, 0], "max": [0.02, 0.02, 0.02], "spacing": 0.01}])";
  EXPECT_EQ(parse_scene(base + "}", "a.json").force_scale, 1.0);
  EXPECT_EQ(parse_scene(base + R"(, "haptics": {"force_scale": 20}})", "a.json").force_scale, 20.0);
  try {
    parse_scene(base + R"(, "haptics": {"force_scale": -2}})", "a.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("force_scale"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// A replay on another backend agrees within kBackendParityTolerance of the recorded peak force,
// or of kBackendParityForceFloor where the session's peak is smaller (a tool that touched nothing
// records rounding, which another summation order changes entirely).
TEST(ReplayComparison, ToleranceIsRelativeToThePeakWithAFloor) {
  auto recording = [](const std::vector<Vec3>& forces) {
    Recording r;
    for (std::size_t k = 0; k < forces.size(); ++k) {
      StepSample s;
      s.step = k;
      s.tool_force = forces[k];
      r.steps.push_back(s);
    }
    return r;
  };
  // Rounding alone: 4.3e-32 N recorded, 4.6e-32 N off.
  const Recording air = recording({{0, 0, 4.3e-32}, {1e-33, 0, 0}});
  ReplayComparison c = compare_replay({{0, 0, 9e-32}, {0, 0, 0}}, air, kBackendParityTolerance);
  EXPECT_EQ(c.differ, 2u);
  EXPECT_EQ(c.outside, 0u);
  EXPECT_NEAR(c.peak, 4.3e-32, 1e-45);
  // A session that pressed: 1e-3 N peak, so 1e-7 N is the bound.
  const Recording press = recording({{0, 0, 1e-3}, {0, 5e-4, 0}, {0, 0, 0}});
  c = compare_replay({{0, 0, 1e-3 + 5e-8}, {0, 5e-4 - 2e-7, 0}, {0, 0, 0}}, press, kBackendParityTolerance);
  EXPECT_EQ(c.differ, 2u);
  EXPECT_EQ(c.outside, 1u);
  EXPECT_NEAR(c.largest, 2e-7, 1e-15);
  // Just under the floor's bound, and over it.
  c = compare_replay({{0, 0, 0.9e-13}, {0, 0, 0}}, air, kBackendParityTolerance);
  EXPECT_EQ(c.outside, 0u);
  c = compare_replay({{0, 0, 1.1e-13}, {0, 0, 0}}, air, kBackendParityTolerance);
  EXPECT_EQ(c.outside, 1u);
  EXPECT_THROW(compare_replay({{0, 0, 0}}, air, kBackendParityTolerance), std::invalid_argument);
}

// The force in air: ticks whose last 20 ms of steps had no tool force are free, the others in
// contact; ticks before any step count as neither.
TEST(FreeAir, TicksAreSplitByTheToolForceOfTheLastWindow) {
  Recording r;
  // Steps every 2 ms from t = 0.010 s; the tool touches paste from 0.100 s to 0.200 s.
  for (int k = 0; k < 150; ++k) {
    StepSample s;
    s.step = std::uint64_t(k);
    s.wall_t = 0.010 + 0.002 * k;
    if (k >= 45 && k < 95) s.tool_force = {0, 0, 1e-4};  // steps at 0.100 to 0.198 s
    r.steps.push_back(s);
  }
  // Ticks every 1 ms from 0 to 0.300 s; rendered 0.01 N in air, 2 N in contact (3 N after 0.150 s),
  // a tick inside the contact's ends.
  for (int k = 0; k <= 300; ++k) {
    HapticSample h;
    h.t = 0.001 * k;
    const bool touching = k >= 102 && k <= 215;
    h.force = {0, touching ? (h.t < 0.150 ? 2.0 : 3.0) : 0.01, 0};
    r.haptic.push_back(h);
  }
  const FreeAirForce f = free_air_force(r);
  // Before 0.010 s: no step yet (10 ticks). In contact: a step with force within the last 20 ms,
  // from the first touching step (0.100) to 20 ms after the last (0.198 + 0.020).
  EXPECT_EQ(f.free_ticks + f.contact_ticks, 301u - 10u);
  EXPECT_NEAR(double(f.contact_ticks), 118.0, 2.0);
  EXPECT_NEAR(f.free_mean_N, 0.01, 1e-12) << "only the air's ticks";
  EXPECT_NEAR(f.free_p95_N, 0.01, 1e-12);
  EXPECT_NEAR(f.contact_p95_N, 3.0, 1e-12);
  EXPECT_GT(f.contact_mean_N, 2.0);
  EXPECT_LT(f.contact_mean_N, 3.0);
  // A longer window makes more ticks contact.
  EXPECT_GT(free_air_force(r, 0.05).contact_ticks, f.contact_ticks);
  EXPECT_EQ(free_air_force(Recording{}).free_ticks, 0u) << "an empty recording";
  // The hard contact touching (the tooth, set paste: no force on the simulated tool) is contact.
  for (int k = 250; k < 270; ++k) r.haptic[std::size_t(k)].contact_force = {0, 3.0, 0};
  const FreeAirForce g = free_air_force(r);
  EXPECT_EQ(g.contact_ticks, f.contact_ticks + 20);
  EXPECT_EQ(g.free_ticks, f.free_ticks - 20);
}

// A recording of `seconds` at `rate` whose tick k renders force(k / rate), at time t(k).
Recording force_recording(double rate, double seconds, const std::function<Vec3(double)>& force,
                          const std::function<double(int)>& t = {}) {
  Recording r;
  r.haptic_rate_hz = rate;
  const int n = int(std::lround(seconds * rate));
  for (int k = 0; k < n; ++k) {
    HapticSample h;
    h.t = t ? t(k) : k / rate;
    h.force = force(k / rate);
    r.haptic.push_back(h);
  }
  return r;
}

// The rendered force's spectrum: a 20 Hz sine of 1 N and a 250 Hz sine of 0.1 N (on a constant
// 2 N) at 1 kHz ticks: above 100 Hz is the 250 Hz sine's RMS, 0.1 / sqrt(2) N, in the 200-300 Hz
// band, peaking at 250 Hz with 0.1 N.
TEST(ForceSpectrum, TwoSinesAreSplitAtTheCutoff) {
  const double two_pi = 2 * std::numbers::pi;
  const Recording r = force_recording(1000, 4, [&](double t) {
    return Vec3{std::sin(two_pi * 20 * t) + 0.1 * std::sin(two_pi * 250 * t + 0.3), 0, 2};
  });
  const ForceSpectrum s = force_spectrum(r);
  EXPECT_EQ(s.ticks, 4000u);
  EXPECT_DOUBLE_EQ(s.rate_hz, 1000);
  EXPECT_DOUBLE_EQ(s.cutoff_hz, 100);
  EXPECT_NEAR(s.above_rms_N, 0.1 / std::sqrt(2.0), 0.02 * 0.1 / std::sqrt(2.0));
  EXPECT_NEAR(s.fluctuation_rms_N, std::sqrt(0.5 + 0.005), 1e-3) << "the 2 N mean removed";
  EXPECT_NEAR(s.above_share, 0.1 / std::sqrt(1.01), 0.003);
  EXPECT_NEAR(s.peak_hz, 250, 1e-9);
  EXPECT_NEAR(s.peak_amplitude_N, 0.1, 0.003);
  ASSERT_EQ(s.bands.size(), 4u) << "100 Hz wide from 100 Hz to the Nyquist frequency, 500 Hz";
  EXPECT_DOUBLE_EQ(s.bands.front().lo_hz, 100);
  EXPECT_DOUBLE_EQ(s.bands.back().hi_hz, 500);
  EXPECT_EQ(s.top_band, 1u);
  EXPECT_DOUBLE_EQ(s.bands[1].lo_hz, 200);
  EXPECT_NEAR(s.bands[1].rms_N, s.above_rms_N, 1e-3 * s.above_rms_N);
  for (std::size_t b : {0u, 2u, 3u}) EXPECT_LT(s.bands[b].rms_N, 1e-3 * s.above_rms_N) << b;

  // Off the bins, on the y axis, with 3 s: the same within the frequency resolution (2 Hz).
  const ForceSpectrum off = force_spectrum(force_recording(1000, 3, [&](double t) {
    return Vec3{0, std::sin(two_pi * 23.3 * t) + 0.1 * std::sin(two_pi * 247.1 * t), 0};
  }));
  EXPECT_NEAR(off.above_rms_N, 0.1 / std::sqrt(2.0), 0.03 * 0.1 / std::sqrt(2.0));
  EXPECT_NEAR(off.peak_hz, 247.1, 1.0);
  EXPECT_NEAR(off.peak_amplitude_N, 0.1, 0.005);
  EXPECT_EQ(off.top_band, 1u);
}

// The force is held between ticks and read at the middle of each nominal period: ticks late by
// less than half a period change nothing; a skipped tick is the previous force held; a recording
// without its rate is read at its median period's.
TEST(ForceSpectrum, TickTimingIsReadAtTheNominalRate) {
  const double two_pi = 2 * std::numbers::pi;
  auto force = [&](double t) { return Vec3{0.5 * std::sin(two_pi * 7 * t), 0.05 * std::sin(two_pi * 330 * t), 0}; };
  const ForceSpectrum even = force_spectrum(force_recording(1000, 2, force));
  const ForceSpectrum late = force_spectrum(force_recording(1000, 2, force, [](int k) {
    return 1e-3 * k + 0.45e-3 * double((k * 7919) % 101) / 100;  // 0 to 0.45 ms late
  }));
  EXPECT_EQ(late.ticks, even.ticks);
  EXPECT_DOUBLE_EQ(late.above_rms_N, even.above_rms_N);
  EXPECT_DOUBLE_EQ(late.peak_hz, even.peak_hz);
  EXPECT_NEAR(even.peak_hz, 330, 1e-9);

  Recording skipped = force_recording(1000, 2, force);
  skipped.haptic.erase(skipped.haptic.begin() + 1000);
  const ForceSpectrum held = force_spectrum(skipped);
  EXPECT_EQ(held.ticks, even.ticks) << "the skipped tick's period read as the force held";
  EXPECT_NEAR(held.above_rms_N, even.above_rms_N, 0.02 * even.above_rms_N);

  Recording unknown_rate = force_recording(1000, 2, force);
  unknown_rate.haptic_rate_hz = 0;
  const ForceSpectrum median = force_spectrum(unknown_rate);
  EXPECT_NEAR(median.rate_hz, 1000, 1e-6);
  EXPECT_NEAR(median.above_rms_N, even.above_rms_N, 1e-9);
}

// A constant force has nothing above the cutoff and no fluctuation; recordings too short (or too
// slow for the cutoff) are not analysed: zeros, never NaN.
TEST(ForceSpectrum, ConstantShortAndEmptyRecordingsGiveZeros) {
  const ForceSpectrum constant = force_spectrum(force_recording(1000, 1, [](double) { return Vec3{0.3, -1.7, 2.9}; }));
  EXPECT_EQ(constant.ticks, 1000u);
  EXPECT_EQ(constant.above_rms_N, 0);
  EXPECT_EQ(constant.fluctuation_rms_N, 0);
  EXPECT_EQ(constant.above_share, 0);
  EXPECT_EQ(constant.peak_hz, 0);
  EXPECT_EQ(constant.peak_amplitude_N, 0);
  for (const ForceBand& b : constant.bands) EXPECT_EQ(b.rms_N, 0);

  auto not_analysed = [](const ForceSpectrum& s, const char* what) {
    EXPECT_EQ(s.ticks, 0u) << what;
    EXPECT_EQ(s.segments, 0u) << what;
    EXPECT_TRUE(s.bands.empty()) << what;
    for (double x : {s.rate_hz, s.segment_s, s.fluctuation_rms_N, s.above_rms_N, s.above_share, s.peak_hz,
                     s.peak_amplitude_N})
      EXPECT_EQ(x, 0) << what;
  };
  not_analysed(force_spectrum(Recording{}), "an empty recording");
  Recording one;
  one.haptic_rate_hz = 1000;
  one.haptic.push_back({});
  not_analysed(force_spectrum(one), "one tick");
  auto wobble = [](double t) { return Vec3{std::sin(1000 * t), 0, 0}; };
  not_analysed(force_spectrum(force_recording(1000, 0.05, wobble)), "50 ticks");
  not_analysed(force_spectrum(force_recording(150, 2, wobble)), "150 Hz ticks: the cutoff above the Nyquist frequency");
  Recording jump = force_recording(1000, 1, wobble);  // a clock jump of a day: not held tick by tick
  jump.haptic.back().t += 86400;
  not_analysed(force_spectrum(jump), "a recording spanning far more periods than it has ticks");
  // The shortest analysed: one segment of the whole recording.
  const ForceSpectrum shortest = force_spectrum(force_recording(1000, 0.064, wobble));
  EXPECT_EQ(shortest.ticks, 64u);
  EXPECT_EQ(shortest.segments, 1u);
  EXPECT_TRUE(std::isfinite(shortest.above_rms_N));
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// The proxy never outruns the step's velocity CFL limit however hard the tool is pushed, and the
// limit only slows it (the same direction, the same position without it when it does not bind).
TEST(VirtualCouplingSpeed, TheProxyIsSlowedToTheStepsLimit) {
  CouplingParams p;
  p.max_speed_m_per_s = 0.24;  // 0.4 h / dt at h = 0.6 mm, dt = 1 ms
  haptics::VirtualCoupling limited(p), free(CouplingParams{});
  limited.reset({0, 0, 0});
  free.reset({0, 0, 0});
  for (int k = 0; k < 50; ++k) {
    limited.step({0, 0, 0}, {}, {0, 0, 500}, 1e-3);  // a contact force of 500 N
    free.step({0, 0, 0}, {}, {0, 0, 500}, 1e-3);
    EXPECT_LE(norm(limited.velocity()), 0.24 * (1 + 1e-12)) << "tick " << k;
    EXPECT_NEAR(limited.velocity().x, 0, 1e-15);
  }
  EXPECT_GT(norm(free.velocity()), 1.0) << "unlimited, the same push throws the proxy";
  haptics::VirtualCoupling slow(p), ref(CouplingParams{});
  slow.reset({0, 0, 0});
  ref.reset({0, 0, 0});
  for (int k = 0; k < 50; ++k) {
    slow.step({0.001, 0, 0}, {}, {}, 1e-3);  // a gentle pull by the spring
    ref.step({0.001, 0, 0}, {}, {}, 1e-3);
  }
  EXPECT_EQ(slow.position().x, ref.position().x) << "below the limit nothing changes";
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// Keyframes: at rest at the origin until 0.5 s, 0.1 m/s along x until 1.5 s, then 0.1 m/s along y
// until 2.5 s, held after.
ToolTrajectory corner_path() {
  ToolTrajectory tr;
  for (const auto& [t, x, y] : {std::tuple{0.5, 0.0, 0.0}, {1.5, 0.1, 0.0}, {2.5, 0.1, 0.1}}) {
    ToolKeyframe k;
    k.t = t;
    k.pose.position = {x, y, 0};
    tr.keyframes.push_back(k);
  }
  return tr;
}

TEST(HandPath, FollowsEachSegmentExactlyOneLagBehind) {
  const ToolTrajectory tr = corner_path();
  const haptics::HandPath hand(tr);
  const double omega = 2 * std::numbers::pi * haptics::hand_bandwidth_hz;
  EXPECT_NEAR(hand.lag_s(), 2 / omega, 1e-15);
  // Away from the corners (more than 40 / omega after one), the keyframes delayed by the lag.
  for (const double t : {0.0, 0.5, 1.4, 1.5, 2.5, 3.5, 10.0}) {
    const Vec3 want = tr.at(real(t - hand.lag_s())).position;
    EXPECT_LT(norm(hand.at(t).position - want), 1e-10) << "t = " << t;
  }
  // One lag after a corner the keyframes are at it; the hand has cut it.
  EXPECT_GT(norm(hand.at(1.5 + hand.lag_s()).position - Vec3{0.1, 0, 0}), 1e-3);
  EXPECT_LT(norm(hand.at(10.0).position - Vec3{0.1, 0.1, 0}), 1e-12) << "comes to rest at the last keyframe";
}

TEST(HandPath, StartsFromRestWithTheFiltersLargestAcceleration) {
  const ToolTrajectory tr = corner_path();
  const haptics::HandPath hand(tr);
  const double omega = 2 * std::numbers::pi * haptics::hand_bandwidth_hz, h = 1e-4;
  double vmax_jump = 0, amax = 0;
  Vec3 v_prev = (hand.at(h).position - hand.at(0).position) / h;
  for (double t = 2 * h; t < 3.0; t += h) {
    const Vec3 v = (hand.at(t).position - hand.at(t - h).position) / h;
    vmax_jump = std::max(vmax_jump, double(norm(v - v_prev)));
    if (t < 1.4) amax = std::max(amax, double(norm(v - v_prev)) / h);
    v_prev = v;
  }
  // The keyframes jump by 0.1 m/s at once; the hand's velocity moves by at most a ~1e-4 of it per
  // 0.1 ms step (its acceleration is bounded), and starting from rest at 0.1 m/s its largest
  // acceleration is the filter's dv omega / e (3.1 m/s^2 for a 0.1 m/s start at 5 Hz).
  EXPECT_LT(vmax_jump, 0.1 * omega * h);
  EXPECT_NEAR(amax, 0.1 * omega / std::numbers::e, 0.01 * 0.1 * omega / std::numbers::e);
}

TEST(HandPath, RefusesAnImpossibleBandwidthAndKeepsAnEmptyPathAtTheOrigin) {
  const ToolTrajectory tr = corner_path();
  EXPECT_THROW(haptics::HandPath(tr, 0.0), std::invalid_argument);
  EXPECT_THROW(haptics::HandPath(tr, std::nan("")), std::invalid_argument);
  const ToolTrajectory none;
  EXPECT_EQ(haptics::HandPath(none).at(1.0).position, Vec3{});
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// In air (no tool force) the proxy's drag against the world is not felt: a device moving steadily
// at 62.5 mm/s drags the proxy with it at no force. In contact the drag acts: the hand feels drag x
// speed (0.125 N at 62.5 mm/s) on top of the tool force.
TEST(VirtualCoupling, TheDragActsInContactAlone) {
  CouplingParams p;
  const Vec3 v{0.0625, 0, 0};
  for (const bool touching : {false, true}) {
    haptics::VirtualCoupling c(p);
    c.reset({});
    const Vec3 tool = touching ? Vec3{0, 0, 1e-3} : Vec3{};
    Vec3 f, x;
    for (int i = 1; i <= 3000; ++i) {
      x = v * (i * 1e-3);
      c.step(x, v, tool, 1e-3);
      f = haptics::coupling_force(p, c.position(), c.velocity(), x, v);
    }
    if (touching) {
      EXPECT_NEAR(f.x, -p.proxy_drag_N_s_per_m * v.x, 1e-6) << "drag x speed against the motion";
    } else {
      EXPECT_NEAR(f.x, 0, 1e-9) << "in air the hand feels nothing";
    }
  }
}

// The renderer carries the proxy forward from the device pose it followed to now: a proxy that
// follows the device exactly, published 3 ms after each pose at 500 Hz, renders no force against a
// device moving at 62.5 mm/s (interpolated as it stands, the spring is stretched by speed x 5 ms:
// 0.125 N on 400 N/m), and this holds when the simulation's own clock runs 20 times slower than
// the device's (a proxy velocity 20 times larger).
TEST(ForceRenderer, CarriesTheProxyForwardToNow) {
  CouplingParams p;
  const double v = 0.0625;
  for (const double sim_per_device_s : {1.0, 0.05}) {
    haptics::ForceRenderer r(ForceMode::coupling, p);
    double worst = 0;
    for (int k = 0; k < 200; ++k) {
      const std::int64_t stamp = 1'000'000'000 + std::int64_t(k) * 2'000'000, published = stamp + 3'000'000;
      haptics::SimOutput o;
      o.proxy_position = {v * double(stamp) * 1e-9, 0, 0};
      o.proxy_velocity = {v / sim_per_device_s, 0, 0};
      o.command_stamp_ns = stamp;
      o.valid = true;
      r.add(o, published);
      if (k < 10) continue;
      for (std::int64_t t = published; t < published + 2'000'000; t += 1'000'000) {
        const Vec3 f = r.render({v * double(t) * 1e-9, 0, 0}, {v, 0, 0}, t);
        worst = std::max(worst, std::abs(f.x));
      }
    }
    EXPECT_LT(worst, 1e-6) << "simulated s per device s " << sim_per_device_s;
  }
}

}  // namespace
}  // namespace dentsph
