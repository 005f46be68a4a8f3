// The built-in dental scene: a molar crown with a Class I cavity (include/dentsph/tooth.hpp),
// paste in the cavity, a ball tool. It needs no file.
#pragma once

#include <filesystem>
#include <optional>
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

// ---- the tooth and its cavity as a user chooses them (the command line, dental scene files) -----

// Which tooth, how it is oriented and which cavity is carved into it.
struct ToothSpec {
  std::filesystem::path mesh;     // STL, OBJ or PLY in mm; empty: the built-in crown
  CavityParams cavity;            // the preparation; default: the built-in Class I
  std::optional<Vec3> long_axis;  // towards the crown, in the mesh's coordinates; none: found
                                  // from the mesh (the built-in crown: its own, +z)
  std::optional<Vec3> mesial;     // towards mesial (the Class II side "mesial"), made orthogonal
                                  // to the axis; none: the found frame's mesio-distal axis
};

// "the built-in crown" or the mesh file's name.
std::string tooth_name(const ToothSpec& spec);

// The tooth of `spec` loaded (or built), its frame found or made from the given axes, the cavity
// carved and lined at default_tooth_spacing (a Class II with its matrix band). Throws MeshError,
// CavityError (its reason after the tooth's name) and std::invalid_argument (an axis that is
// zero or not finite, a mesial direction along the long axis).
ToothScene prepare_tooth(const ToothSpec& spec);

// One number of CavityParams as a dental scene file ("cavity": {key: ...}) and the command line
// (option) name it, in the unit people use (mm or degrees). The one table both read.
struct CavityField {
  const char* key;              // field of a scene file's "cavity" object
  const char* option;           // command-line option
  const char* unit;             // "mm" or "degrees"
  real CavityParams::*member;   // where it goes
  real scale;                   // CavityParams' unit (m or degrees) per `unit`
  real min;                     // smallest value accepted (in `unit`)
  bool min_inclusive;           // min itself accepted
  real max;                     // values must be below this (in `unit`)
  bool class_2_only;            // a proximal box's parameter
  const char* hint;             // what it is and a typical value, for the fix of a message
};
const std::vector<CavityField>& cavity_fields();
// Empty when `value` (in the field's unit) is accepted, else what is wrong ("must be > 0 mm").
std::string check_cavity_field(const CavityField& field, real value);

// Names as the command line and scene files write them: "class1", "class2"; "mesial", "distal".
const char* cavity_class_name(CavityClass kind);
std::optional<CavityClass> cavity_class_from_name(std::string_view name);
const char* proximal_side_name(ProximalSide side);
std::optional<ProximalSide> proximal_side_from_name(std::string_view name);

// One line for people: "Class II (mesial box), outline 3 x 5 mm, 2 mm deep, ...".
std::string cavity_description(const CavityParams& params);
// The run summary's "cavity" object (class, side, dimensions in mm and degrees, the volume
// removed and the thinnest wall and floor left), as JSON text.
std::string cavity_json(const PreparedTooth& tooth);

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
// The procedure file on a lined tooth; an empty path: the built-in procedure.
Scene procedure_or_built_in(const ToothScene& tooth, const std::filesystem::path& file);
// The built-in procedure on the built-in crown: what `dentsph run` runs.
Scene default_dental_procedure(const DentalSceneParams& params = {});
// What `dentsph run` runs without a scene file: the procedure file (empty: the built-in one) on
// the tooth of `tooth` (by default the built-in crown with its Class I cavity).
Scene dental_run_scene(const ToothSpec& tooth, const std::filesystem::path& procedure_file);

}  // namespace dentsph
