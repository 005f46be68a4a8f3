// The hard contact's parts at the haptic rate: its field against the tooth's own distance and a
// slab of set paste, and the god-object proxy pressing, sliding and letting go on them (1 kHz
// ticks, as the haptic loop runs it). The runtime's tests (test_haptics_contact.cpp) press through
// the threads and devices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact_support.hpp"
#include "dentsph/contact.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/tools.hpp"
#include "haptics/force_limiter.hpp"

namespace dentsph {
namespace {

using testing::ContactBench;
using testing::angle_deg;

TEST(ContactField, IsTheToothsDistanceNearItsSurface) {
  const ContactBench& b = ContactBench::get();
  const ToothFrame& f = b.tooth().frame();
  int checked = 0;
  for (real y = -4e-3; y <= 4e-3; y += 0.5e-3)
    for (real z = -3e-3; z <= 1.5e-3; z += 0.25e-3) {
      const Vec3 p = f.to_world({0.3e-3, y, z});
      const SurfacePoint exact = b.tooth().distance(p);
      if (std::abs(exact.distance) > 0.5e-3) continue;
      const ContactField::Sample s = b.field.sample(p, true, false);
      EXPECT_NEAR(s.distance, exact.distance, 0.03e-3) << "at local y " << y << " z " << z;
      ++checked;
    }
  EXPECT_GT(checked, 20);
  // Without particles the grid holds nothing near the cavity: the far value, the tooth's distance wins.
  EXPECT_EQ(b.field.particles(), 0u) << "the built-in Class I has no band";
}

TEST(ContactField, SetParticlesMakeASurfaceAboveTheirTopLayer) {
  const ContactBench& b = ContactBench::get();
  ContactField field = b.field;
  const real top = b.set_slab(field);
  ASSERT_GT(field.particles(), 50u);
  const ToothFrame& f = b.tooth().frame();
  // Along the axis, over the slab: the surface lies between the top layer's centres and half a
  // spacing above them (the particles' radius).
  real lo = top, hi = top + 1.5e-3;
  for (int k = 0; k < 60; ++k) {
    const real mid = 0.5 * (lo + hi);
    (field.sample(f.to_world({0, 0, mid}), false, true).distance > 0 ? hi : lo) = mid;
  }
  EXPECT_GE(lo, top - 1e-9);
  EXPECT_LE(lo, top + 0.5 * b.spacing + 1e-9);
  const ContactField::Sample s = field.sample(f.to_world({0, 0, lo + 0.05e-3}), false, true);
  EXPECT_LT(angle_deg(s.normal, f.z), 5.0);
}

// Presses the ball into the enamel beside the cavity, into the cavity floor and onto set paste,
// 1 mm behind the surface: the force is the stiffness times the device's distance behind the
// proxy, the proxy on the surface, the force along the surface's normal; pressing in and letting
// go returns no energy to the hand, and the force never steps by more than the rate limit.
struct PressCase {
  const char* name;
  Vec3 start_local;  // m, tooth frame: above the surface
  bool set_paste;
};

class HardContactPress : public ::testing::TestWithParam<PressCase> {};

TEST_P(HardContactPress, ForceIsStiffnessTimesPenetrationAlongTheNormal) {
  const ContactBench& b = ContactBench::get();
  ContactField field = b.field;
  if (GetParam().set_paste) b.set_slab(field);
  const ToothFrame& f = b.tooth().frame();
  const DeviceProfile profile = device_profile("falcon");
  HardContact contact(profile.contact);
  const Vec3 start = f.to_world(GetParam().start_local);
  // Where the ball first touches, going down the axis, and the surface's normal there.
  testing::PressRun run = testing::press(contact, field, b.shape, start, -f.z, 1e-3, 0.02, true,
                                         GetParam().set_paste ? nullptr : &b.tooth());
  ASSERT_TRUE(run.touched) << "the ball reached no surface";
  const ContactResult& r = run.held;
  ASSERT_TRUE(r.touching);
  // The force is k times the device's distance behind the proxy (at rest: no damping).
  const real behind = norm(r.proxy - run.device);
  EXPECT_NEAR(behind, 1e-3, 0.1e-3) << "the device pressed 1 mm past the first contact";
  EXPECT_NEAR(norm(r.force_N), profile.contact.stiffness_N_per_m * behind, 0.1 * profile.contact.stiffness_N_per_m * behind);
  // The proxy on the surface: its lowest sphere within 0.05 mm of it.
  EXPECT_LT(std::abs(run.clearance), 0.05e-3) << GetParam().name;
  // Along the surface's normal (the tooth's own, or the field's on set paste).
  EXPECT_LT(angle_deg(r.force_N, run.surface_normal), 5.0) << GetParam().name;
  // Passive: over the press and the release the hand got no energy back (at most 1% of its work).
  EXPECT_LE(run.energy_to_hand_J, 0.01 * run.work_in_J) << "work in " << run.work_in_J;
  EXPECT_GT(run.work_in_J, 0);
  EXPECT_LE(run.max_force_step_N, profile.max_force_rate_N_per_s * 1e-3);
  // And let go, the proxy follows the hand again with no force.
  EXPECT_FALSE(run.released.touching);
  EXPECT_EQ(norm(run.released.force_N), 0);
}

INSTANTIATE_TEST_SUITE_P(Surfaces, HardContactPress,
                         ::testing::Values(PressCase{"enamel beside the cavity", {0, 2.6e-3, 6e-3}, false},
                                           PressCase{"cavity floor", {0.5e-3, 0, 0.5e-3}, false},
                                           PressCase{"set paste", {0, 0, 0.5e-3}, true}),
                         [](const auto& info) {
                           std::string n = info.param.name;
                           std::replace(n.begin(), n.end(), ' ', '_');
                           return n;
                         });

TEST(HardContact, SlidingAlongTheFloorMeetsCoulombFriction) {
  const ContactBench& b = ContactBench::get();
  const ToothFrame& f = b.tooth().frame();
  const DeviceProfile profile = device_profile("falcon");
  HardContact contact(profile.contact);
  testing::PressRun run = testing::press(contact, b.field, b.shape, f.to_world({-0.5e-3, 0, 0.5e-3}), -f.z, 0.5e-3, 0.02,
                                         /*release=*/false);
  ASSERT_TRUE(run.held.touching);
  // Slide 1 mm along the frame's x at 10 mm/s, pressed: once sliding, the force along the floor is
  // mu times the force into it, against the motion.
  Vec3 x = run.device;
  int sliding = 0;
  for (int k = 0; k < 100; ++k) {
    x += f.x * 1e-5;
    const ContactResult& r = contact.update(b.field, b.shape, x, {}, f.x * 0.01);
    if (!r.sliding) continue;
    ++sliding;
    const double fn = dot(r.force_N, r.normal), ft = norm(r.force_N - r.normal * fn);
    EXPECT_NEAR(ft / fn, profile.contact.friction, 0.1 * profile.contact.friction);
    EXPECT_LT(dot(r.force_N, f.x), 0) << "friction opposes the motion";
  }
  EXPECT_GT(sliding, 50);
  // Held still, the proxy sticks: the same force, no slide.
  const ContactResult still = contact.update(b.field, b.shape, x, {}, {});
  EXPECT_FALSE(still.sliding);
}

TEST(HardContact, TheShankMeetsTheTooth) {
  // The instrument lying across the tooth (its handle along -y), the ball over the cavity: going
  // down, the shank meets the crown beside the cavity first, and the contact's lever from the tip
  // is millimetres long, not the ball's.
  const ContactBench& b = ContactBench::get();
  const ToothFrame& f = b.tooth().frame();
  HardContact contact(device_profile("falcon").contact);
  const Quat lying = Quat::from_axis_angle(f.x, 90 * std::numbers::pi / 180);  // +z to -y
  Vec3 x = f.to_world({0, 0, 4e-3});
  contact.reset(x);
  ContactResult r;
  for (int k = 0; k < 600 && !r.touching; ++k) {
    x -= f.z * 1e-5;
    r = contact.update(b.field, b.shape, x, lying, {});
  }
  ASSERT_TRUE(r.touching) << "nothing met";
  const double lever = norm(r.torque_N_m) / norm(r.force_N);
  EXPECT_GT(lever, 2e-3) << "lever " << lever * 1e3 << " mm";
  EXPECT_GT(dot(r.proxy - f.origin, f.z), 0) << "stopped above the occlusal reference, the ball not in the cavity";
}

TEST(HardContact, AnInstrumentInsideSetPasteIsNotThrownOut) {
  // Paste that sets around the instrument: the proxy is not pushed out through the paste with a
  // jolt; the set paste holds it only once it has left.
  const ContactBench& b = ContactBench::get();
  const ToothFrame& f = b.tooth().frame();
  ContactField field = b.field;
  const real top = b.set_slab(field);
  HardContact contact(device_profile("falcon").contact);
  const Vec3 inside = f.to_world({0, 0, top - 0.5e-3});
  contact.reset(inside);
  const ContactResult r = contact.update(field, b.shape, inside, {}, {});
  EXPECT_EQ(norm(r.force_N), 0);
  EXPECT_EQ(norm(r.proxy - inside), 0);
}

TEST(HardContact, StaysFiniteOnBadInputAndRefusesBadSettings) {
  const ContactBench& b = ContactBench::get();
  HardContact contact(device_profile("falcon").contact);
  const double nan = std::nan("");
  const ContactResult& r = contact.update(b.field, b.shape, {nan, 0, 0}, {}, {});
  EXPECT_TRUE(is_finite(r.force_N));
  EXPECT_TRUE(is_finite(r.proxy));
  ContactParams bad;
  bad.stiffness_N_per_m = -1;
  EXPECT_THROW(HardContact{bad}, std::invalid_argument);
}

// Far from the tooth's and the particles' grids the field is the distance to their boxes: never
// more than the true distance, so the contact's broad phase does not call a sphere free that a
// long instrument's shank brings to the tooth.
// The contact loop rebuilds the field only when what it was built from changed: paste that set,
// set paste that shrank by more than the watch's tolerance (0.02 mm) from where the field has it,
// or another instrument. A step's reordering of the particles, and shrinkage below the tolerance,
// are no change.
TEST(RigidWatch, SaysWhenTheFieldIsOutOfDate) {
  State s;
  const std::vector<Vec3> band{{1e-3, 0, 0}, {1.2e-3, 0, 0}};
  // ids 0..3: two boundary particles that may set, one moving paste particle, one tool particle.
  s.id = {0, 1, 2, 3};
  s.role = {Role::boundary, Role::boundary, Role::material, Role::tool};
  s.pos = {{0, 0, 0}, {0.2e-3, 0, 0}, {0.4e-3, 0, 0}, {0, 0, 1e-3}};
  s.anchor = {{}, {}, {}, {0, 0, 1e-3}};
  s.cure.rigid = {1, 0, 0, 0};
  RigidWatch w(band);
  ASSERT_TRUE(w.changed(s)) << "the first call builds";
  EXPECT_EQ(w.particles().size(), 3u) << "the band and the one set particle";
  EXPECT_EQ(w.tool().size(), 1u);
  EXPECT_FALSE(w.changed(s));
  // Shrinkage: 0.015 mm is below the tolerance; another 0.015 mm (0.03 from where the field has
  // it) is not.
  s.pos[0].z -= 0.015e-3;
  EXPECT_FALSE(w.changed(s));
  s.pos[0].z -= 0.015e-3;
  ASSERT_TRUE(w.changed(s));
  EXPECT_NEAR(w.particles()[2].z, -0.03e-3, 1e-12);
  EXPECT_FALSE(w.changed(s));
  // The step reorders its particles: nothing changed.
  std::swap(s.id[0], s.id[1]), std::swap(s.pos[0], s.pos[1]), std::swap(s.role[0], s.role[1]);
  EXPECT_FALSE(w.changed(s));
  // Paste sets; then another instrument.
  s.cure.rigid[1] = 1;
  ASSERT_TRUE(w.changed(s));
  EXPECT_EQ(w.particles().size(), 4u);
  s.anchor[3].z = 2e-3;
  EXPECT_TRUE(w.changed(s));
  EXPECT_FALSE(w.changed(s));
  w.forget();
  EXPECT_TRUE(w.changed(s)) << "after a reset";
}

TEST(ContactField, OutsideItsGridsIsALowerBound) {
  const ContactBench& b = ContactBench::get();
  const ToothFrame& f = b.tooth().frame();
  for (const Vec3 local : {Vec3{0, 0, 12e-3}, Vec3{20e-3, 0, 0}, Vec3{0, -15e-3, 5e-3}}) {
    const Vec3 p = f.to_world(local);
    const real d = b.field.sample(p).distance;
    EXPECT_LE(d, b.tooth().distance(p).distance + 1e-9);
    EXPECT_GT(d, 0);
  }
}

TEST(HardContact, TorqueIsLimitedLikeTheForce) {
  // A device that renders torque gets it through a ForceLimiter of torque_profile: the sigma.7's
  // 0.4 N m, changing by at most 0.04 N m a millisecond.
  haptics::ForceLimiter lim(haptics::torque_profile(device_profile("sigma7")));
  EXPECT_NEAR(norm(lim.apply({0, 0, 0.03}, 1e-3).force), 0.03, 1e-12);
  EXPECT_NEAR(norm(lim.apply({0, 0, 5}, 1e-3).force), 0.07, 1e-12) << "rate";
  for (int k = 0; k < 20; ++k) lim.apply({0, 0, 5}, 1e-3);
  EXPECT_NEAR(norm(lim.apply({0, 0, 5}, 1e-3).force), 0.4, 1e-12) << "magnitude";
}

}  // namespace
}  // namespace dentsph
