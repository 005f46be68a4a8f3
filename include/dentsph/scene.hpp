// Scenes: a JSON file (docs/scene-format.md) or a built-in description turned into a Model, the
// initial particles and the tool's trajectory. Every field is checked; errors name the file, the
// field and the fix.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dentsph/curing_light.hpp"
#include "dentsph/lattice.hpp"
#include "dentsph/model.hpp"
#include "dentsph/pose.hpp"
#include "dentsph/state.hpp"
#include "dentsph/tooth.hpp"

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
  // m/s, the fastest any of the points `anchors` (tool frame) moves from one keyframe to the next
  // (its chord over the interval's time); 0 without two keyframes.
  real max_speed(const std::vector<Vec3>& anchors) const;
};

// Something that happens to a run at a time: an increment of material dropped in, another
// instrument taken up, or the curing light turned on for a while. Resolved when the scene is read:
// the runner only applies it (a cure event changes no particle: ActiveLights says when its light is
// on, include/dentsph/active_lights.hpp).
struct ProcedureEvent {
  enum class Kind { dispense, switch_tool, cure };
  Kind kind = Kind::dispense;
  real t = 0;                            // s, applied before the first step at or after t
  std::vector<ParticleInit> particles;   // dispense: the increment (world frame);
                                         // switch_tool: the new tool's particles (tool frame)
  std::string tool;                      // switch_tool: the instrument's name
  real tool_spacing = 0;                 // switch_tool: the spacing tool_by_name made it at (m)
  // dispense: when `count` > 0, `particles` are candidate sites in order of preference and the
  // increment is the first `count` of them that keep `clearance` (m) from the material already
  // there: an increment laid on the previous one, whose shape after compaction a procedure file
  // cannot know. Fewer when fewer are free.
  std::size_t count = 0;
  real clearance = 0;
  // cure: the light (world frame), on from t for `duration` seconds.
  CuringLight light;
  real duration = 0;
};

struct OutputSettings {
  real snapshot_interval = 0.01;  // s of simulated time between particle snapshots (0: none)
  bool vtk = true;                // write .vtu snapshots and the .pvd index
  // With vtk, in a scene whose paste has a spacing (the dental scenes): the paste's surface
  // (dentsph/surface.hpp) beside each snapshot, paste_surface/step_N.vtp indexed by paste_surface.pvd.
  bool surface = true;
};

struct Scene {
  std::string name;
  std::string source;                    // file the scene came from, or "built-in"
  ModelParams params;                    // as given (and defaulted)
  Model model;                           // make_model(params)
  std::vector<ParticleInit> particles;   // material and boundary in world frame; tool in tool frame
  ToolTrajectory tool;                   // empty keyframes when the scene has no tool
  std::vector<ProcedureEvent> events;    // in time order
  OutputSettings output;
  real duration = 0;                     // s, default run length ("run.duration"); 0 if not given
  std::optional<PreparedTooth> tooth;    // dental scenes: the prepared tooth, for the assessment
  real material_spacing = 0;             // m, dental scenes: the paste's lattice spacing
  // N rendered on a haptic device per N of tool force in the simulation. The simulated paste is
  // soft (the tool force is of the order of 1e-4 N); this maps it to what a hand should feel. The
  // haptic runtime uses it as its default scale; the leak test presses with the device's largest
  // force divided by it.
  real force_scale = 1;
  // The paste preset the scene is filled with (paste_presets.hpp, `run --material`); empty: the
  // scene's own paste.
  std::string paste_preset;
  real paste_temperature_c = 23;  // C, the preset's temperature
  // Who ran it and which exercise it is, when a scene file or the command line says (the
  // report's title, the session store's index; docs/report.md).
  std::string student, exercise;
  // Dental scenes: dt is the solver's dental time step (dental_time_step), so choosing another
  // solver (select_solver) chooses its time step too. Scene files give dt themselves.
  bool dt_follows_solver = false;
  // Dental scenes: the first instrument's name and the spacing tool_by_name made it at (m), so that
  // choosing another solver makes it again as that solver runs it. Empty: a scene file's blocks.
  std::string instrument;
  real instrument_spacing = 0;
};

// Chooses the step that runs the scene (the command line's --solver over the scene's
// simulation.solver) and rebuilds its Model; a dental scene takes the solver's dental time step,
// and the instruments made by name are made again as the solver runs them (shape_instruments).
void select_solver(Scene& scene, Solver solver);
// The command line's choice: the solver it names (`named`, empty: none; a replay passes its
// recording's) over the scene's; without one, a run on a GPU backend (which has the paper's step
// only) takes the paper's step, and the line returned says so (empty otherwise). A named iisph
// solver on a GPU is refused by make_stepper.
std::string choose_solver(Scene& scene, const std::string& named, bool gpu_backend);
// Makes the scene's named instruments (its first one, Scene::instrument, and those its switch_tool
// events take up) as scene.model.solver runs them (tool_by_name), with the masses and materials
// they have. select_solver calls it (the scene builders make them for the scene's solver).
void shape_instruments(Scene& scene);
// A dental scene run by the iisph solver: its Model gets the prepared tooth's wall field
// (wall_field.hpp: sampled at half the paste's spacing over its boundary particles' box grown by h
// and its whole domain, in cells large enough for at most 2 million corners; clearance a quarter
// spacing). Other
// scenes and solvers: none. select_solver calls it.
void attach_walls(Scene& scene);
// The prepared tooth's wall field as attach_walls makes it (whatever the solver; null for a scene
// without a tooth or boundary particles): the iisph solver's walls and the hard contact's tooth
// (contact.hpp), the latter over the whole tooth (`whole_tooth`: the instrument meets the crown
// anywhere, not only around the cavity where paste may be).
std::shared_ptr<const WallField> tooth_wall_field(const Scene& scene, bool whole_tooth = false);
// m/s, the fastest any tool particle moves between the scene's keyframes (the first instrument's
// and those a switch_tool event takes up): what the velocity CFL limit of the iisph solver is
// checked against before a run.
real scene_tool_speed(const Scene& scene);
// A dental scene whose dt follows its solver (Scene::dt_follows_solver) takes the solver's dental
// time step (dental_time_step) or, where the solver's step is limited by the tool's speed
// (StepSolver::tool_speed_limit: the iisph solver's velocity CFL limit), the limit at the scene's
// fastest tool speed where that is smaller (rounded down to 10 us), so that a procedure with a fast
// instrument runs instead of being refused; the Model's dt with it. Other scenes: unchanged.
// select_solver and the procedure builder call it.
void fit_dental_time_step(Scene& scene);

// Reads and checks a scene file. Throws SceneError.
Scene load_scene(const std::filesystem::path& file);
// Parses scene JSON text; `source` names it in error messages. Throws SceneError.
Scene parse_scene(const std::string& json_text, const std::string& source);

// The initial state of a scene: tool at its first keyframe, particles added. Every particle's
// material must be in scene.model.materials (std::invalid_argument otherwise).
State make_state(const Scene& scene);
// Adds to scene.model.materials the values of every particle (the scene's and its events') that
// names no entry and whose values no entry has (for scenes built in code), and the default paste and
// instrument material (kDefaultPaste, kDefaultInstrument) where the scene has no such particle and
// names none.
void intern_scene_materials(Scene& scene);

// Applies a procedure event to a state between steps (adds the increment, numbered as the next
// one in state.cure, or replaces the tool particles, which then follow the tool pose; a cure event
// changes nothing here).
void apply_event(const Scene& scene, State& state, const ProcedureEvent& event);

}  // namespace dentsph
