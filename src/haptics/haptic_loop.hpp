// The haptic loop: at a fixed rate, read the device, render the force (renderer, watchdog,
// limiter), write it, hand the tool command to the simulation, record. Everything it uses is
// allocated before it starts; it takes no lock and writes no file or log.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "dentsph/limits.hpp"

#include "dentsph/contact.hpp"
#include "dentsph/haptics.hpp"
#include "haptics/force_limiter.hpp"
#include "haptics/press_limiter.hpp"
#include "haptics/force_renderer.hpp"
#include "haptics/passivity_control.hpp"
#include "haptics/shared.hpp"
#include "haptics/timing_stats.hpp"
#include "haptics/watchdog.hpp"

namespace dentsph::haptics {

class HapticLoop {
 public:
  HapticLoop(Device& device, const RealtimeOptions& options, RuntimeShared& shared);
  // Runs on the calling thread from t0_ns until shared.stop is set.
  void run(std::int64_t t0_ns);
  HapticReport report() const;
  // The recorded ticks (moved out) and how many did not fit.
  std::vector<HapticSample> take_recording();
  std::uint64_t recording_dropped() const { return dropped_; }

 private:
  void tick(std::int64_t now_ns, double dt);
  // A new device session (DeviceSample::session changed): forget the previous one's motion and
  // forces, announce it to the virtual coupling, ramp the force in from zero.
  void start_session(const DeviceSample& fresh, std::int64_t now_ns);
  void publish_live(std::int64_t now_ns, const Vec3& force, double pose_age_s, double sim_age_s, double gain,
                    std::uint32_t status);

  Device& device_;
  RealtimeOptions opt_;
  RuntimeShared& shared_;
  ForceRenderer renderer_;
  Watchdog watchdog_;
  ForceLimiter limiter_;
  PassivityControl passivity_;
  HardContact contact_;  // the tooth, band and set paste, at this loop's rate
  std::optional<ForceLimiter> torque_limiter_;  // a device that renders torque
  DurationHistogram periods_, force_ages_;
  std::vector<HapticSample> record_;
  std::size_t recorded_ = 0;
  std::uint64_t dropped_ = 0;
  // device state
  DeviceSample sample_;
  // Presses counted in fresh samples, handed to the simulation (ToolCommand): button 1 (dispense)
  // and button 2 (the curing light).
  PressLimiter<limits::max_dispense_presses_per_s> dispense_presses_;
  PressLimiter<limits::max_light_presses_per_s> light_presses_;
  std::int64_t session_start_ns_ = 0;  // simulation outputs answering older commands are ignored
  Vec3 velocity_, prev_position_;
  double prev_device_time_ = 0;
  bool have_prev_ = false;
  // simulation output
  bool have_sim_ = false;
  std::uint64_t last_step_ = 0;
  std::int64_t sim_published_ns_ = 0, sim_command_stamp_ns_ = 0;
  Vec3 sim_torque_;  // the newest simulation output's
  HapticReport rep_;
  double last_period_us_ = 0, recent_max_us_ = 0;  // for HapticLive
  std::int64_t recent_start_ns_ = 0;
  std::int64_t first_tick_ns_ = 0, last_tick_ns_ = 0, t0_ns_ = 0;
};

}  // namespace dentsph::haptics
