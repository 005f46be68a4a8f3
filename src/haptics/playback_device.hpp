// A device that plays poses as a function of time, in real time (scripted, replay): a new pose on
// every read, forces ignored, finished at the end of what it plays.
#pragma once

#include "dentsph/haptics/device.hpp"

namespace dentsph::haptics {

class PlaybackDevice : public Device {
 public:
  void start(std::int64_t t0_ns) override { t0_ns_ = t0_ns; }
  bool read(std::int64_t now_ns, DeviceSample& s) final {
    const double t = seconds(now_ns);
    s.pose = pose_at(t);
    s.stamp_ns = now_ns;
    s.device_time_s = t;
    s.sequence = ++sequence_;
    s.valid = true;
    return true;
  }
  void write(std::int64_t, const ForceCommand&) override {}
  bool finished(std::int64_t now_ns) const final { return seconds(now_ns) >= end_s(); }

 protected:
  // The pose (device frame) t s after the start; called from the haptic loop only.
  virtual Pose pose_at(double t) = 0;
  virtual double end_s() const = 0;

 private:
  double seconds(std::int64_t now_ns) const { return double(now_ns - t0_ns_) * 1e-9; }
  std::int64_t t0_ns_ = 0;
  std::uint32_t sequence_ = 0;
};

}  // namespace dentsph::haptics
