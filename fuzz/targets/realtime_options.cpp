// Fuzz target: the realtime runtime's options (`run --realtime`'s --haptic-rate, --force-scale,
// --workspace-scale, --workspace-origin, --stiffness, --damping, --solve-deadline, --duration,
// the device profile, the force mode, the watchdog's times), read as doubles from the input, NaN,
// infinities and denormals included, then checked as run_realtime checks them
// (check_realtime_options). Where they are accepted, the rest of the input drives the haptic loop's
// force path as haptic_loop.cpp composes it (the renderer, the watchdog's gain, the limiter) over
// simulation outputs and device poses: every force sent must be finite and at most the device's
// limit, the gain in [0, 1], the tool's scene position of a device pose in its workspace finite.
// The first robustness round found --stiffness 1e308 rendering 0 N all session and
// --workspace-scale 1e308 sending the tool to -6.6e291 m.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "dentsph/haptics.hpp"
#include "fuzz_targets.hpp"
#include "haptics/force_limiter.hpp"
#include "haptics/force_renderer.hpp"
#include "haptics/messages.hpp"
#include "haptics/watchdog.hpp"

namespace dentsph::fuzz {

namespace {

// The input, a double or a byte at a time (zeros once it is used up).
class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool left() const { return at_ < size_; }
  double number() {
    double v = 0;
    const std::size_t n = std::min<std::size_t>(sizeof v, size_ - at_);
    std::memcpy(&v, data_ + at_, n);
    at_ += n;
    return v;
  }
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }

 private:
  const std::uint8_t* data_;
  std::size_t size_, at_ = 0;
};

// A finite value within [-bound, bound] from any double (the device and the simulation hand on
// only finite values: the UDP device and the simulation loop reject the rest).
double within(double v, double bound) { return std::isfinite(v) ? std::clamp(v, -bound, bound) : 0.0; }

}  // namespace

int realtime_options(const std::uint8_t* data, std::size_t size) {
  Reader in(data, size);
  RealtimeOptions o;
  o.haptic_rate_hz = in.number();
  o.snapshot_rate_hz = in.number();
  const double force_scale = in.number();
  o.workspace.scale = in.number();
  o.workspace.origin = Vec3{in.number(), in.number(), in.number()};
  o.coupling.stiffness_N_per_m = in.number();
  o.coupling.damping_N_s_per_m = in.number();
  o.solve_share = in.number();
  o.duration_s = in.number();
  o.dispense_volume = in.number();
  o.watchdog = WatchdogParams{in.number(), in.number(), in.number(), in.number()};
  static const char* const profiles[] = {"falcon", "omega", "touch", "sigma7"};
  const std::uint8_t choice = in.byte();
  o.profile = device_profile(profiles[choice % 4]);
  o.mode = choice & 4 ? ForceMode::direct : ForceMode::coupling;
  try {
    check_realtime_options(o, force_scale);
  } catch (const std::invalid_argument&) {
    return 0;
  }
  haptics::ForceRenderer renderer(o.mode, o.coupling);
  haptics::ForceLimiter limiter(o.profile);
  haptics::Watchdog watchdog(o.watchdog);
  const double dt = 1 / o.haptic_rate_hz;
  std::int64_t now = 1'000'000'000;
  std::uint64_t step = 0;
  while (in.left()) {
    const std::uint8_t flags = in.byte();
    if (flags & 1) {  // a simulation output: a simulated force (N), the proxy near the device
      haptics::SimOutput out;
      out.force_N = Vec3{within(in.number(), 1e6), within(in.number(), 1e6), within(in.number(), 1e6)} * force_scale;
      out.proxy_position = Vec3{within(in.number(), 0.5), within(in.number(), 0.5), within(in.number(), 0.5)};
      out.proxy_velocity = Vec3{within(in.number(), 10), within(in.number(), 10), within(in.number(), 10)};
      out.free = flags & 2;
      out.step = ++step;
      out.valid = true;
      out.published_ns = now;
      if (is_finite(out.force_N)) renderer.add(out, now);
    }
    // The device within the UDP device's workspace (0.3 m of its origin, 2 m/s).
    const Vec3 x{within(in.number(), 0.3), within(in.number(), 0.3), within(in.number(), 0.3)};
    const Vec3 v{within(in.number(), 2), within(in.number(), 2), within(in.number(), 2)};
    if (!is_finite(o.workspace.to_scene(x))) std::abort();
    const double sim_age = (flags & 8) ? within(in.number(), 1) : 0.001, pose_age = (flags & 16) ? 0.5 : 0.001;
    const double gain = watchdog.update(sim_age, pose_age, dt);
    if (!(gain >= 0 && gain <= 1)) std::abort();
    const haptics::ForceLimiter::Result sent = limiter.apply(renderer.render(x, v, now) * gain, dt);
    if (!is_finite(sent.force) || norm(sent.force) > o.profile.max_force_N * (1 + 1e-12)) std::abort();
    now += std::int64_t(dt * 1e9);
  }
  return 0;
}

}  // namespace dentsph::fuzz
