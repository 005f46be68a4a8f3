// A scripted sequence of inputs for the viewer (--script FILE): what a user would do with the
// mouse and keys, each at a simulation step, so that a scripted session runs the same simulation
// however fast frames are drawn. Format (JSON):
//   {"actions": [{"step": 0, "action": "move", "position_mm": [0, 0, 2]},
//                {"step": 400, "action": "dispense"},
//                {"step": 600, "action": "press"}, {"step": 1400, "action": "release"},
//                {"step": 1500, "action": "switch_tool", "tool": "flat_plugger"},
//                {"step": 1600, "action": "colour_by", "mode": "pressure"},
//                {"step": 2000, "action": "light_on"}, {"step": 2800, "action": "light_off"},
//                {"step": 2900, "action": "load_preset", "preset": "packable", "temperature_c": 37},
//                {"step": 3000, "action": "end"}]}
// Positions are of the tool's tip, in mm, in the tooth frame (dental scenes: origin on the long
// axis at the occlusal surface, z up the axis) or in the world (other scenes).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph::viewer {

struct ScriptAction {
  // light_on, light_off: the curing light over the cavity (the L key). load_preset: the scene
  // filled with a paste preset and reset (the Material panel's chooser).
  enum class Kind {
    move, press, release, dispense, switch_tool, pause, resume, reset, colour_by, light_on, light_off, load_preset, end
  };
  std::uint64_t step = 0;
  Kind kind = Kind::move;
  Vec3 position_mm;   // move
  std::string name;   // switch_tool: the instrument; colour_by: the mode; load_preset: the preset
  double temperature_c = 23;  // load_preset
};

struct InputScript {
  std::string source;
  std::vector<ScriptAction> actions;  // in step order
  std::uint64_t end_step() const { return actions.empty() ? 0 : actions.back().step; }
};

// Reads and checks a script; throws SceneError "<file>: <field>: <problem>; <fix>".
InputScript load_input_script(const std::filesystem::path& file);
InputScript parse_input_script(const std::string& json_text, const std::string& source);

}  // namespace dentsph::viewer
