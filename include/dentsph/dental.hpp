// The built-in dental scene: a molar crown with a Class I cavity (include/dentsph/tooth.hpp),
// paste in the cavity, a ball tool. It needs no file.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
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

// The dental scenes' force scale (Scene::force_scale): N rendered on a haptic device per N of
// tool force in the simulation. Measured on the built-in procedure: a compaction press gives
// about 2e-4 N of tool force (90th percentile of the press phases), a sweep along the walls a
// median of 2.4e-4 to 3.1e-4 N; 1.5e4 renders them as 3 N and 3.6 to 4.6 N, and the largest
// device force (12 N) is 8e-4 N in the simulation. See docs/procedure-format.md.
inline constexpr real dental_force_scale = 1.5e4;

// A lined tooth without paste or tool: the model (h = 2 spacings, gravity down the long axis, a
// domain around the cavity), the boundary particles, the prepared tooth for the assessment.
Scene dental_base_scene(const ToothScene& tooth, const DentalSceneParams& params, const std::string& name,
                        const std::string& source);

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

// ---- procedures (docs/procedure-format.md) ------------------------------------------------------

// The built-in procedure: scenes/default_procedure.json, compiled in.
std::string_view default_procedure_json();

// A procedure (JSON text: the first instrument, keyframes and events in mm in the tooth frame)
// on a lined tooth with no paste: the increments laid into the cavity as the events say. Throws
// SceneError naming `source`, the field and the fix.
Scene dental_procedure(const ToothScene& tooth, const std::string& procedure_json, const std::string& source,
                       const DentalSceneParams& params = {});
// The same from a file.
Scene load_dental_procedure(const ToothScene& tooth, const std::filesystem::path& file,
                            const DentalSceneParams& params = {});
// The built-in procedure on the built-in crown: what `dentsph run` runs.
Scene default_dental_procedure(const DentalSceneParams& params = {});
// What `dentsph run` runs without a scene file: the procedure file (empty: the built-in one) on
// the scanned tooth (empty: the built-in crown) with its default Class I cavity.
Scene dental_run_scene(const std::filesystem::path& mesh_file, const std::filesystem::path& procedure_file);

}  // namespace dentsph
