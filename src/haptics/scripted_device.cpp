// A scripted device: the hand follows the scene's tool keyframes in real time.
#include <memory>

#include "dentsph/haptics/device.hpp"
#include "dentsph/scene.hpp"

namespace dentsph {

namespace {

class ScriptedDevice final : public Device {
 public:
  ScriptedDevice(const ToolTrajectory& trajectory, const WorkspaceMap& map, double end_s)
      : trajectory_(trajectory), map_(map), end_s_(end_s) {}
  std::string name() const override { return "scripted"; }
  void start(std::int64_t t0_ns) override { t0_ns_ = t0_ns; }
  bool read(std::int64_t now_ns, DeviceSample& s) override {
    const double t = double(now_ns - t0_ns_) * 1e-9;
    const Pose p = trajectory_.keyframes.empty() ? Pose{} : trajectory_.at(real(t));
    s.pose = {map_.to_device(p.position), p.orientation};
    s.stamp_ns = now_ns;
    s.device_time_s = t;
    s.sequence = ++sequence_;
    s.valid = true;
    return true;
  }
  void write(std::int64_t, const ForceCommand&) override {}
  bool finished(std::int64_t now_ns) const override { return double(now_ns - t0_ns_) * 1e-9 >= end_s_; }

 private:
  const ToolTrajectory& trajectory_;
  WorkspaceMap map_;
  double end_s_;
  std::int64_t t0_ns_ = 0;
  std::uint32_t sequence_ = 0;
};

}  // namespace

std::unique_ptr<Device> make_scripted_device(const Scene& scene, const WorkspaceMap& map, double duration_s,
                                             double tail_s) {
  double end = duration_s;
  if (end <= 0) end = (scene.tool.keyframes.empty() ? 0.0 : double(scene.tool.keyframes.back().t)) + tail_s;
  if (end <= 0) end = scene.duration > 0 ? double(scene.duration) : 1.0;
  return std::make_unique<ScriptedDevice>(scene.tool, map, end);
}

}  // namespace dentsph
