// A replay device: the device poses of a recorded session, played in real time (positions
// interpolated between recorded ticks).
#include <algorithm>
#include <memory>

#include "dentsph/haptics/device.hpp"
#include "dentsph/haptics/recording.hpp"

namespace dentsph {

namespace {

class ReplayDevice final : public Device {
 public:
  explicit ReplayDevice(std::vector<HapticSample> samples) : samples_(std::move(samples)) {}
  std::string name() const override { return "replay"; }
  void start(std::int64_t t0_ns) override { t0_ns_ = t0_ns; }
  bool read(std::int64_t now_ns, DeviceSample& s) override {
    if (samples_.empty()) return false;
    const double t = double(now_ns - t0_ns_) * 1e-9;
    while (next_ + 1 < samples_.size() && samples_[next_ + 1].t <= t) ++next_;
    const HapticSample& a = samples_[next_];
    const HapticSample& b = samples_[std::min(next_ + 1, samples_.size() - 1)];
    const double w = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
    s.pose = {a.device_position + (b.device_position - a.device_position) * w, a.device_orientation};
    s.stamp_ns = now_ns;
    s.device_time_s = t;
    s.sequence = ++sequence_;
    s.valid = true;
    return true;
  }
  void write(std::int64_t, const ForceCommand&) override {}
  bool finished(std::int64_t now_ns) const override {
    return samples_.empty() || double(now_ns - t0_ns_) * 1e-9 > samples_.back().t;
  }

 private:
  std::vector<HapticSample> samples_;
  std::size_t next_ = 0;
  std::int64_t t0_ns_ = 0;
  std::uint32_t sequence_ = 0;
};

}  // namespace

std::unique_ptr<Device> make_replay_device(const std::filesystem::path& recording_dir) {
  return std::make_unique<ReplayDevice>(load_recording(recording_dir).haptic);
}

}  // namespace dentsph
