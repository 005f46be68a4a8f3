// A scripted device: a hand follows the scene's tool keyframes in real time, as a hand moves
// (hand_path.hpp: without a hand's instant changes of velocity at the keyframes).
#include <memory>

#include "dentsph/scene.hpp"
#include "haptics/hand_path.hpp"
#include "haptics/playback_device.hpp"

namespace dentsph {

namespace {

class ScriptedDevice final : public haptics::PlaybackDevice {
 public:
  ScriptedDevice(const ToolTrajectory& trajectory, const WorkspaceMap& map, double end_s)
      : path_(trajectory), map_(map), end_s_(end_s) {}
  std::string name() const override { return "scripted"; }

 protected:
  Pose pose_at(double t) override {
    const Pose p = path_.at(t);
    return {map_.to_device(p.position), p.orientation};
  }
  double end_s() const override { return end_s_; }

 private:
  haptics::HandPath path_;
  WorkspaceMap map_;
  double end_s_;
};

}  // namespace

std::unique_ptr<Device> make_scripted_device(const Scene& scene, const WorkspaceMap& map, double duration_s,
                                             double tail_s) {
  double end = duration_s;
  if (end <= 0)
    end = (scene.tool.keyframes.empty() ? 0.0 : double(scene.tool.keyframes.back().t) + haptics::HandPath(scene.tool).lag_s()) +
          tail_s;
  if (end <= 0) end = scene.duration > 0 ? double(scene.duration) : 1.0;
  return std::make_unique<ScriptedDevice>(scene.tool, map, end);
}

}  // namespace dentsph
