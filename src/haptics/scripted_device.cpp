// A scripted device: the hand follows the scene's tool keyframes in real time.
#include <memory>

#include "dentsph/scene.hpp"
#include "haptics/playback_device.hpp"

namespace dentsph {

namespace {

class ScriptedDevice final : public haptics::PlaybackDevice {
 public:
  ScriptedDevice(const ToolTrajectory& trajectory, const WorkspaceMap& map, double end_s)
      : trajectory_(trajectory), map_(map), end_s_(end_s) {}
  std::string name() const override { return "scripted"; }

 protected:
  Pose pose_at(double t) override {
    const Pose p = trajectory_.keyframes.empty() ? Pose{} : trajectory_.at(real(t));
    return {map_.to_device(p.position), p.orientation};
  }
  double end_s() const override { return end_s_; }

 private:
  const ToolTrajectory& trajectory_;
  WorkspaceMap map_;
  double end_s_;
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
