// The tool of a scene: its particles in the tool frame and its keyframed trajectory
// (docs/scene-format.md, "tool").
#include <fmt/format.h>

#include "scene/parse.hpp"

namespace dentsph::scene {

namespace {

constexpr real pi = 3.14159265358979323846;

// "rotation": {"axis": [x, y, z], "angle_deg": a}, a right-handed rotation about a non-zero axis.
Quat read_rotation(const Reader& r) {
  r.only({"axis", "angle_deg"});
  const Vec3 axis = r.vec3("axis", "the rotation axis [x, y, z] (any non-zero length)");
  if (norm2(axis) == 0) r.fail("axis", "is zero", "give a non-zero axis, e.g. [0, 0, 1]");
  const real deg = r.number("angle_deg", "the rotation angle in degrees about the axis");
  return Quat::from_axis_angle(axis, deg * pi / 180);
}

ToolKeyframe read_keyframe(const Reader& k, const ToolKeyframe* previous) {
  k.only({"t", "position", "rotation"});
  ToolKeyframe kf;
  kf.t = k.number("t", "the keyframe time in s", Range::non_negative);
  if (previous != nullptr && !(kf.t > previous->t))
    k.fail("t", fmt::format("{} s is not after the previous keyframe's {} s", kf.t, previous->t),
           "keyframe times must strictly increase");
  kf.pose.position = k.vec3("position", "the tool-frame origin's position [x, y, z] in m");
  if (const std::optional<Reader> rot =
          k.optional_object("rotation", "the orientation {\"axis\": [0, 0, 1], \"angle_deg\": 0}"))
    kf.pose.orientation = read_rotation(*rot);
  return kf;
}

ToolTrajectory read_trajectory(const Reader& tool) {
  const Json& kfs = tool.array(
      "keyframes", "at least one keyframe, e.g. [{\"t\": 0, \"position\": [0, 0, 0.1]}]");
  ToolTrajectory traj;
  for (std::size_t i = 0; i < kfs.size(); ++i)
    traj.keyframes.push_back(read_keyframe(tool.element(kfs, "keyframes", i, "a keyframe"),
                                           i > 0 ? &traj.keyframes.back() : nullptr));
  return traj;
}

}  // namespace

ToolPart parse_tool(const Reader& tool, const MaterialTable& materials,
                    const KernelCoeffs& kernel) {
  tool.only({"material", "blocks", "keyframes"});
  // The tool's own material (default roles.tool) is the default of each of its blocks.
  MaterialDefault tool_material{materials.default_for(Role::tool), "roles.tool"};
  if (tool.has("material"))
    tool_material = {resolve_material(tool, materials, tool_material), "tool.material"};
  else
    tool_material.from = "tool.material or roles.tool";

  ToolPart part;
  const Json& blocks = tool.array("blocks",
                                  "the tool's shape as blocks in the tool frame, e.g. "
                                  "[{\"shape\": \"sphere\", ...}]");
  const BlockContext ctx{Role::tool, materials, tool_material, kernel};
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const std::vector<ParticleInit> ps =
        parse_block(tool.element(blocks, "blocks", i, "a block"), ctx);
    part.particles.insert(part.particles.end(), ps.begin(), ps.end());
  }
  part.trajectory = read_trajectory(tool);
  return part;
}

}  // namespace dentsph::scene
