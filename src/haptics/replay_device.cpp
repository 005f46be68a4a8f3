// A replay device: the device poses of a recorded session, played in real time (positions
// interpolated linearly between recorded ticks, orientations by slerp).
#include <algorithm>
#include <memory>

#include "dentsph/haptics/recording.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/pose.hpp"
#include "haptics/playback_device.hpp"

namespace dentsph {

namespace {

class ReplayDevice final : public haptics::PlaybackDevice {
 public:
  explicit ReplayDevice(std::vector<HapticSample> samples) : samples_(std::move(samples)) {}
  std::string name() const override { return "replay"; }

 protected:
  Pose pose_at(double t) override {
    if (samples_.empty()) return {};
    while (next_ + 1 < samples_.size() && samples_[next_ + 1].t <= t) ++next_;
    const HapticSample& a = samples_[next_];
    const HapticSample& b = samples_[std::min(next_ + 1, samples_.size() - 1)];
    const double w = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
    return interpolate({a.device_position, a.device_orientation}, {b.device_position, b.device_orientation}, w);
  }
  double end_s() const override { return samples_.empty() ? 0.0 : samples_.back().t; }

 private:
  std::vector<HapticSample> samples_;
  std::size_t next_ = 0;
};

}  // namespace

std::unique_ptr<Device> make_replay_device(const std::filesystem::path& recording_dir) {
  return std::make_unique<ReplayDevice>(load_recording(recording_dir).haptic);
}

}  // namespace dentsph
