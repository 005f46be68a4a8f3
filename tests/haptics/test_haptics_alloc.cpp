// The haptic loop allocates nothing once it runs: the global operator new counts the allocations
// made on the haptic thread after the device was started on it. The loop runs as the viewer runs
// it, keeping a HapticLive current every tick (the runtime without a viewer skips only that).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <thread>

#include "client_process.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics.hpp"
#include "path_device.hpp"
#include "press_scene.hpp"

// ThreadSanitizer's runtime defines operator new itself: there the count is not taken.
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define DENTSPH_NO_NEW_COUNT 1
#endif
#endif
#if defined(__SANITIZE_THREAD__)
#define DENTSPH_NO_NEW_COUNT 1
#endif

namespace {

std::atomic<std::thread::id> g_watched{};
std::atomic<std::uint64_t> g_allocations{0};

#ifndef DENTSPH_NO_NEW_COUNT
void* counted(std::size_t n) {
  if (g_watched.load(std::memory_order_relaxed) == std::this_thread::get_id())
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}

#endif
}  // namespace

#ifndef DENTSPH_NO_NEW_COUNT
void* operator new(std::size_t n) { return counted(n); }
void* operator new[](std::size_t n) { return counted(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
// The nothrow forms too (std::stable_sort's buffer takes one): every form a delete above may free
// comes from malloc, or AddressSanitizer sees its own operator new's memory freed by free().
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return counted(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
#endif

namespace dentsph {
namespace {

// A device, watching the thread it is started on.
class Watched final : public Device {
 public:
  explicit Watched(std::unique_ptr<Device> d) : d_(std::move(d)) {}
  std::string name() const override { return d_->name(); }
  void start(std::int64_t t0) override {
    d_->start(t0);
    g_allocations = 0;
    g_watched = std::this_thread::get_id();
  }
  bool read(std::int64_t now, DeviceSample& s) override { return d_->read(now, s); }
  void write(std::int64_t now, const ForceCommand& c) override { d_->write(now, c); }
  bool finished(std::int64_t now) const override { return d_->finished(now); }

 private:
  std::unique_ptr<Device> d_;
};

TEST(HapticLoop, AllocatesNothingWhileItRuns) {
#ifdef DENTSPH_NO_NEW_COUNT
  GTEST_SKIP() << "ThreadSanitizer replaces operator new; counted in the other builds";
#endif
  // The count works: an allocation on the watched thread is seen.
  g_watched = std::this_thread::get_id();
  g_allocations = 0;
  delete new std::uint64_t(1);
  g_watched = std::thread::id{};
  ASSERT_EQ(g_allocations.load(), 1u);

  const Scene scene = testing::press_scene();
  for (const ForceMode mode : {ForceMode::coupling, ForceMode::direct}) {
    RealtimeOptions o;
    o.mode = mode;
    o.force_scale = 20;
    o.record_capacity_s = 5;
    o.workspace.origin = {0, 0, 0.09};
    HapticLive live;
    o.live = &live;
    Watched device(make_scripted_device(scene, o.workspace, 0.6));
    const RealtimeResult r = run_realtime(scene, device, o);
    g_watched = std::thread::id{};
    EXPECT_GT(r.haptic.timing.ticks, 100u);
    EXPECT_GT(r.haptic.max_force_N, 0.0);
    EXPECT_EQ(live.ticks.load(), r.haptic.timing.ticks) << "the live figures were kept every tick";
    EXPECT_EQ(g_allocations.load(), 0u) << force_mode_name(mode);
  }
}

// The same with the hand pressing the built-in crown's empty cavity floor: the hard contact's
// field, proxy and friction run every tick and allocate nothing either.
TEST(HapticLoop, AllocatesNothingPressingTheTooth) {
#ifdef DENTSPH_NO_NEW_COUNT
  GTEST_SKIP() << "ThreadSanitizer replaces operator new; counted in the other builds";
#endif
  Scene scene = default_dental_procedure();
  scene.events.clear();
  const ToothFrame& f = scene.tooth->frame();
  const Vec3 from = f.to_world({0.5e-3, 0, 0.5e-3}), to = f.to_world({0.5e-3, 0, -3.5e-3});
  RealtimeOptions o;
  o.force_scale = dental_force_scale;
  o.record_capacity_s = 5;
  HapticLive live;
  o.live = &live;
  Watched device(std::make_unique<testing::PathDevice>(
      [=](double t) { return from + (to - from) * std::clamp(t / 0.5, 0.0, 1.0); }, 0.8));
  const RealtimeResult r = run_realtime(scene, device, o);
  g_watched = std::thread::id{};
  EXPECT_GT(r.haptic.contact_ticks, 100u) << "the instrument met the floor";
  EXPECT_EQ(g_allocations.load(), 0u);
}

// The same with the UDP bridge, the reference client playing the device from another process:
// receiving poses and sending forces allocate nothing either.
TEST(HapticLoop, AllocatesNothingWithTheUdpDevice) {
#ifdef DENTSPH_NO_NEW_COUNT
  GTEST_SKIP() << "ThreadSanitizer replaces operator new; counted in the other builds";
#endif
  const Scene scene = testing::press_scene();
  RealtimeOptions o;
  o.force_scale = 20;
  o.record_capacity_s = 5;
  o.duration_s = 1.0;
  o.workspace.origin = {0, 0, 0.09};
  HapticLive live;
  o.live = &live;
  std::uint16_t port = 0;
  Watched device(make_udp_device({"127.0.0.1", 0}, &port));
  // Every path of the bridge: a hello, heartbeats, an absurd pose, a restart of the numbering, a
  // button pressed fast (new sessions, refused poses, refused presses).
  testing::ClientProcess client(port, {"--rate", "1000", "--duration", "0.8", "--motion", "press", "--depth", "0.04",
                                       "--hello", "--heartbeat-every", "0.05", "--spike-at", "0.3", "--spike-m", "50",
                                       "--restart-at", "0.5", "--toggle-button-hz", "50"},
                                "alloc");
  ASSERT_TRUE(client.started());
  const RealtimeResult r = run_realtime(scene, device, o);
  g_watched = std::thread::id{};
  ASSERT_FALSE(client.wait().is_null()) << "the client failed";
  EXPECT_GT(r.haptic.timing.ticks, 500u);
  EXPECT_GT(r.haptic.max_force_N, 0.0);  // poses arrived and forces went back
  EXPECT_EQ(live.ticks.load(), r.haptic.timing.ticks);
  EXPECT_EQ(r.haptic.sessions, 2u);  // the first hello's, the restart's
  EXPECT_GT(r.haptic.dispense_presses_refused, 0u);
  EXPECT_EQ(g_allocations.load(), 0u);
}

}  // namespace
}  // namespace dentsph
