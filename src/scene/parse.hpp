// The scene parser's parts, one concept per file: materials_json.cpp (materials, roles and
// per-block overrides), block_json.cpp (a block of particles), tool_json.cpp (the tool and its
// keyframes), scene_json.cpp (the top level, simulation settings and the Model).
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dentsph/model.hpp"
#include "dentsph/paste_presets.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/scene_reader.hpp"
#include "dentsph/state.hpp"
#include "scene/budget.hpp"
#include "scene/shapes.hpp"

namespace dentsph::scene {

// ---- files and the top level (scene_json.cpp) ---------------------------------------------------

// A file's text; a missing or unreadable one is a SceneError naming it and `what` it should be
// ("the scene file").
std::string read_text_file(const std::filesystem::path& file, std::string_view what);
// "haptics" of the top level ({"force_scale"}) into `scene`, keeping its default when absent.
void read_haptics(const Reader& root, Scene& scene);
// The optional "student" and "exercise" of the top level (the report's and the session store's).
void read_session_names(const Reader& root, Scene& scene);

// ---- dental scene files (dental_scene_json.cpp) -------------------------------------------------

// A scene file with a "tooth", "cavity" or "procedure" field is a dental scene: a procedure on a
// tooth with a cavity, which builds its own particles.
bool is_dental_scene(const Reader& root);
// "solver" of a "simulation" object: "paper" or "iisph", `fallback` where absent (scene files and
// dental scenes: paper); anything else names the field and the choices.
Solver read_solver(const Reader& simulation, Solver fallback);
// "iisph" of `simulation`, the iisph solver's settings over `defaults` (stiffness, max_iterations,
// density_error, omega, viscosity_iterations, cfl, gradient), checked (check_iisph_params) naming the field.
IisphParams read_iisph(const Reader& simulation, IisphParams defaults);
// Reads one; paths in it are relative to the folder of root.source().
Scene parse_dental_scene(const Reader& root);
// "material" of a dental scene or a procedure: a paste preset's name, or {"preset": name,
// "temperature_c": C} (docs/model.md, "Presets"); none: the paper's paste. Refusals name the field.
std::optional<PastePreset> read_paste_preset(const Reader& root);
// A "cavity" object into CavityParams (missing fields keep the defaults).
CavityParams read_cavity(const Reader& cavity);

// ---- materials (materials_json.cpp) ------------------------------------------------------------

// The scene's named materials and the default material of each role ("roles").
struct SceneMaterials {
  std::map<std::string, Material, std::less<>> by_name;
  std::optional<Material> role_default[3];  // indexed by Role
  std::string role_name[3];                 // the names "roles" gave (empty where it gave none)

  const std::optional<Material>& default_for(Role r) const { return role_default[int(r)]; }
  // The material called `name`, or a SceneError at field `key` of `at` listing the known ones.
  const Material& lookup(const Reader& at, std::string_view key, const std::string& name) const;
};

// Reads "materials" (required) and "roles" (optional) of the top level.
SceneMaterials parse_materials(const Reader& root);

// Where a block's material comes from when it gives none: the material and the field that set
// it ("roles.boundary", "tool.material"), for messages.
struct MaterialDefault {
  std::optional<Material> material;
  std::string from;
};

// The material of the object read by `owner`: its "material" field (a name, or an inline object
// overriding a base that defaults to `fallback`), else `fallback`.
Material resolve_material(const Reader& owner, const SceneMaterials& table,
                          const MaterialDefault& fallback);

// ---- blocks (block_json.cpp) --------------------------------------------------------------------

struct BlockContext {
  Role role;  // Role::tool for the tool's blocks (which have no "role" field)
  const SceneMaterials& materials;
  MaterialDefault fallback;    // the role's material
  const KernelCoeffs& kernel;  // h and the poly6 constants, for the default particle mass
  ParticleBudget* budget = nullptr;  // counts the block's particles before they are made
};

// The role of a world block ("material" or "boundary"), from its "role" field.
Role parse_role(const Reader& block);

// One block as read and checked, its particles counted in the context's budget but not yet made.
struct BlockPlan {
  Shape shape;
  real spacing = 0;
  ParticleInit proto;  // role, material, mass and velocity of every particle
};

// Reads and checks one block (its particles counted in ctx.budget, not yet made).
BlockPlan plan_block(const Reader& block, const BlockContext& ctx);
// The particles of a block, in the block's frame (world, or the tool frame for tool blocks).
std::vector<ParticleInit> make_block(const BlockPlan& plan);
// The particles of blocks, in order.
std::vector<ParticleInit> make_blocks(const std::vector<BlockPlan>& plans);

// ---- tool (tool_json.cpp) -----------------------------------------------------------------------

struct ToolPart {
  std::vector<BlockPlan> blocks;        // tool frame, Role::tool (make_blocks makes them)
  ToolTrajectory trajectory;
  std::vector<ProcedureEvent> events;   // "events": dispense and switch_tool, in time order
};

// Reads the "tool" object, counting its particles and its events' in `budget`.
// `solver`: the step that runs the scene (its switch_tool events' instruments are made for it).
ToolPart parse_tool(const Reader& tool, const SceneMaterials& materials, const KernelCoeffs& kernel,
                    ParticleBudget& budget, Solver solver);

// Where the keyframes and events of a file land. A scene file gives world metres (the default);
// a procedure file (dental_procedure.cpp) gives millimetres in a tooth's frame.
struct Placement {
  const char* length_unit = "m";  // in the fields' hints
  real length_scale = 1;          // m per file length unit
  std::function<Pose(const Pose&)> to_world;  // file pose -> world pose; empty: identity
  // Reads a "dispense" object `d` (checking it) into the event's particles (and count and
  // clearance); empty: the scene file's sphere of lattice points ({"volume", "at", "spacing"},
  // roles.material).
  std::function<void(const Reader& d, ProcedureEvent& event)> dispense;
  // Counts every event's particles before they are made (the dispense function counts its own).
  ParticleBudget* budget = nullptr;
  // The step that runs the scene: a switch_tool event's instrument is made as it runs it (tool_by_name).
  Solver solver = Solver::paper;
};

// "keyframes" of `owner`: at least one, times strictly increasing, each placed by `placement`.
ToolTrajectory read_trajectory(const Reader& owner, const Placement& placement);

// "events" of `owner` (dispense, switch_tool) in time order. `materials` gives roles.material
// for a scene file's dispense; the instruments are of `tool_material`.
std::vector<ProcedureEvent> read_events(const Reader& owner, const Placement& placement,
                                        const SceneMaterials* materials, const Material& tool_material,
                                        const KernelCoeffs& kernel);

}  // namespace dentsph::scene
