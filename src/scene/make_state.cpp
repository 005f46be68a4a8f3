// make_state: the initial State of a scene.
#include "dentsph/scene.hpp"

namespace dentsph {

State make_state(const Scene& scene) {
  State state;
  // Both poses at the first keyframe, so that add_particles places the tool there and the first
  // step does not see the tool jump.
  state.tool_pose = scene.tool.at(0);
  state.tool_pose_applied = state.tool_pose;
  state.add_particles(scene.model, scene.particles);
  return state;
}

}  // namespace dentsph
