// Scenes: a JSON file (docs/scene-format.md) or a built-in description turned into a Model, the
// initial particles and the tool's trajectory. Every field is checked; errors name the file, the
// field and the fix.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "dentsph/model.hpp"
#include "dentsph/pose.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

// A scene that cannot be used. what() reads "<file>: <field>: <problem>; <fix>".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ToolKeyframe {
  real t = 0;  // s
  Pose pose;
};

// The tool's pose over time: positions interpolated linearly, orientations by slerp, held
// constant before the first and after the last keyframe.
struct ToolTrajectory {
  std::vector<ToolKeyframe> keyframes;  // strictly increasing t
  Pose at(real t) const;
};

struct OutputSettings {
  real snapshot_interval = 0.01;  // s of simulated time between particle snapshots (0: none)
  bool vtk = true;                // write .vtu snapshots and the .pvd index
};

struct Scene {
  std::string name;
  std::string source;                    // file the scene came from, or "built-in"
  ModelParams params;                    // as given (and defaulted)
  Model model;                           // make_model(params)
  std::vector<ParticleInit> particles;   // material and boundary in world frame; tool in tool frame
  ToolTrajectory tool;                   // empty keyframes when the scene has no tool
  OutputSettings output;
  real duration = 0;                     // s, default run length ("run.duration"); 0 if not given
};

// Reads and checks a scene file. Throws SceneError.
Scene load_scene(const std::filesystem::path& file);
// Parses scene JSON text; `source` names it in error messages. Throws SceneError.
Scene parse_scene(const std::string& json_text, const std::string& source);

// The initial state of a scene: tool at its first keyframe, particles added.
State make_state(const Scene& scene);

// Particle mass that gives a particle inside an infinite simple cubic lattice of `spacing` the
// density rho0 under the poly6 kernel of `kernel` (sum_j m W_poly6(r_ij) = rho0).
real lattice_particle_mass(real rho0, real spacing, const KernelCoeffs& kernel);

}  // namespace dentsph
