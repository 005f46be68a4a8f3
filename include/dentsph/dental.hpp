// The built-in dental scene: a molar crown with a Class I cavity (include/dentsph/tooth.hpp),
// paste in the cavity, a ball tool. It needs no file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "dentsph/scene.hpp"
#include "dentsph/tooth.hpp"

namespace dentsph {

struct DentalSceneParams {
  real dt = 5e-5;                        // s
  int material_particles = 1600;         // the cavity's share first, the rest heaped above it
  Material paste{1.0, 10, 2000, 50};     // mu Pa s, Kp m^2/s^2, rho0 kg/m^3, Ka Pa
  Material wall{1.0, 15, 2000, 0};       // boundary and tool
};

// A dental scene on a prepared, lined tooth: `material_particles` of paste in the cavity (half a
// spacing clear of its walls) and heaped above it within the outline, a 42-particle ball tool
// pressing in and lifting every 0.1 s, gravity down the tooth's long axis.
Scene dental_scene(const ToothScene& tooth, const DentalSceneParams& params, const std::string& name,
                   const std::string& source);

// The built-in scene (default_tooth_scene(): the procedural crown, about 1480 boundary particles).
Scene default_dental_scene(const DentalSceneParams& params = {});

// The same on a scanned tooth: the mesh (mm) loaded, checked and repaired, its long axis found,
// the default Class I cavity carved and lined. Throws MeshError or CavityError with the reason.
Scene dental_scene_from_mesh(const std::filesystem::path& mesh_file, const DentalSceneParams& params = {});

}  // namespace dentsph
