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

// The dental scenes' time step for each solver (StepSolver::default_time_step), s: the paper's explicit step 5e-5 (under its
// acoustic limit, 62 us for the paste and walls below), the iisph solver 1.5e-3 (with the prepared
// tooth's wall field; it fills the cavities as the paper's step does, where 2 ms left FDI 36's two
// cavities 0.002 behind; a 1 kHz haptic loop gets every second step, 3 ticks apart; docs/model.md).
real dental_time_step(Solver solver);

// The iisph solver's settings for the dental scenes: the defaults, relaxed by 0.7 (at a 2 ms dental
// step, with the equation of state as written, 4.3 pressure iterations a step over bench_step's
// window with 0.6 to 1.0, 0.7 the least; 5.4 with 0.5; docs/model.md).
IisphParams dental_iisph_params();

struct DentalSceneParams {
  Solver solver = Solver::iisph;         // which step runs (Model::solver); paper: the reference
  IisphParams iisph = dental_iisph_params();  // the iisph solver's settings
  real dt = 0;                           // s; 0: dental_time_step(solver)
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
// spacing clear of its walls) and heaped above it within the outline, a ball tool (42 particles; 52
// on the iisph solver, tool_by_name) pressing in and lifting every 0.1 s, gravity down the tooth's
// long axis.
Scene dental_scene(const ToothScene& tooth, const DentalSceneParams& params, const std::string& name,
                   const std::string& source);

// The built-in scene (default_tooth_scene(): the procedural crown, about 1480 boundary particles).
Scene default_dental_scene(const DentalSceneParams& params = {});

// The same on a scanned tooth: the mesh (mm) loaded, checked and repaired, its long axis found,
// the default Class I cavity carved and lined. Throws MeshError or CavityError with the reason.
Scene dental_scene_from_mesh(const std::filesystem::path& mesh_file, const DentalSceneParams& params = {});

// ---- the tooth and its cavity as a user chooses them (the command line, dental scene files) -----

// ToothSpec (which tooth, its axes, its cavity) and prepare_tooth() are in dentsph/tooth.hpp.

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
// A cavity number given by a user (a scene file's field, a command-line option), checked and
// set by set_cavity_value: the one validation both read.
struct CavityValueCheck {
  enum class Outcome {
    set,            // accepted and set
    needs_class_2,  // a proximal box's number on a Class I cavity: the fix (choose class2) is the
                    // caller's to word, in its own syntax
    refused,        // not accepted: `problem` ("must be > 0 mm, got -1") and `fix` ("give ...")
  };
  Outcome outcome = Outcome::set;
  std::string problem, fix;
};
// Sets `field` of `params` to `value` (in the field's unit) unless it is refused; a proximal box's
// number needs params.kind class_2 already chosen.
CavityValueCheck set_cavity_value(CavityParams& params, const CavityField& field, real value);

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
Scene procedure_or_built_in(const ToothScene& tooth, const std::filesystem::path& file,
                            const DentalSceneParams& params = {});
// The built-in procedure on the built-in crown: what `dentsph run` runs.
Scene default_dental_procedure(const DentalSceneParams& params = {});
// What `dentsph run` runs without a scene file: the procedure file (empty: the built-in one) on
// the tooth of `tooth` (by default the built-in crown with its Class I cavity).
Scene dental_run_scene(const ToothSpec& tooth, const std::filesystem::path& procedure_file,
                       const DentalSceneParams& params = {});

}  // namespace dentsph
