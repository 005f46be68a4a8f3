// A device playing a path of time (s since it started), in the device frame: the runtime's tests
// that need a hand moving where no scene keyframe goes.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <string>

#include "dentsph/haptics/device.hpp"

namespace dentsph::testing {

// A device playing a path of time (s since it started), in the device frame.
class PathDevice : public Device {
 public:
  PathDevice(std::function<Vec3(double)> path, double duration) : path_(std::move(path)), duration_(duration) {}
  std::string name() const override { return "path"; }
  void start(std::int64_t t0) override { t0_ = t0; }
  bool read(std::int64_t now, DeviceSample& s) override {
    const double t = double(now - t0_) * 1e-9;
    s.pose.position = path_(std::max(0.0, t));
    s.stamp_ns = now;
    s.device_time_s = t;
    ++s.sequence;
    s.valid = true;
    return true;
  }
  void write(std::int64_t, const ForceCommand&) override {}
  bool finished(std::int64_t now) const override { return double(now - t0_) * 1e-9 >= duration_; }

 private:
  std::function<Vec3(double)> path_;
  double duration_;
  std::int64_t t0_ = 0;
};

}  // namespace dentsph::testing
