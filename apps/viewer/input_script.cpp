// Input scripts (input_script.hpp), read with the scene files' checked reader.
#include "input_script.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "colour_map.hpp"
#include "dentsph/limits.hpp"
#include "dentsph/paste_presets.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/scene_reader.hpp"
#include "dentsph/tools.hpp"

namespace dentsph::viewer {

namespace {

struct KindName {
  ScriptAction::Kind kind;
  std::string_view name;
};
constexpr KindName kKinds[] = {{ScriptAction::Kind::move, "move"},         {ScriptAction::Kind::press, "press"},
                               {ScriptAction::Kind::release, "release"},   {ScriptAction::Kind::dispense, "dispense"},
                               {ScriptAction::Kind::switch_tool, "switch_tool"}, {ScriptAction::Kind::pause, "pause"},
                               {ScriptAction::Kind::resume, "resume"},     {ScriptAction::Kind::reset, "reset"},
                               {ScriptAction::Kind::colour_by, "colour_by"}, {ScriptAction::Kind::light_on, "light_on"},
                               {ScriptAction::Kind::light_off, "light_off"}, {ScriptAction::Kind::load_preset, "load_preset"},
                               {ScriptAction::Kind::end, "end"}};

// Each reset or load_preset builds the scene again (milliseconds to a second on a molar): 10,000
// of them took 50 s for 97 steps.
constexpr std::size_t kMaxScriptRebuilds = 100;

}  // namespace

InputScript parse_input_script(const std::string& json_text, const std::string& source) {
  // The scene files' JSON reading: a syntax error, or a number beyond a double's range (1e8880),
  // is a SceneError naming the line and column.
  const scene::Json doc = scene::parse_json(json_text, source);
  const scene::Reader top(doc, "", source, "an input script");
  top.only({"actions"});
  const scene::Json& actions = top.array("actions", "the list of actions, e.g. [{\"step\": 0, \"action\": \"dispense\"}]");
  InputScript script;
  script.source = source;
  std::vector<std::string_view> names;
  for (const KindName& k : kKinds) names.push_back(k.name);
  if (actions.size() > limits::max_events)
    top.fail("actions", fmt::format("{} actions, over the limit of {} (README, \"Resource limits\")", actions.size(),
                                    limits::max_events),
             "split the script, or drop repeated actions");
  std::size_t rebuilds = 0;                 // reset and load_preset actions: each builds the scene again
  constexpr std::size_t none = ~std::size_t{0};
  std::size_t paused_by = none;             // the pause in force (no resume at its step yet)
  for (std::size_t i = 0; i < actions.size(); ++i) {
    const scene::Reader a = top.element(actions, "actions", i, "an action");
    a.only({"step", "action", "position_mm", "tool", "mode", "preset", "temperature_c"});
    ScriptAction act;
    act.step = std::uint64_t(a.integer("step", "the simulation step it happens at, e.g. 400", 0, std::int64_t(1) << 40));
    const std::string kind = a.string("action", "what happens: move, press, release, dispense, switch_tool, pause, "
                                                "resume, reset, colour_by, light_on, light_off, load_preset or end");
    bool known = false;
    for (const KindName& k : kKinds)
      if (kind == k.name) {
        act.kind = k.kind;
        known = true;
      }
    if (!known) {
      const std::string_view near = scene::closest(kind, names);
      a.fail("action", fmt::format("'{}' is not an action", kind),
             near.empty() ? "use one of move, press, release, dispense, switch_tool, pause, resume, reset, colour_by, light_on, "
                                           "light_off, load_preset, end"
                          : fmt::format("did you mean '{}'?", near));
    }
    if (!script.actions.empty() && act.step < script.actions.back().step)
      a.fail("step", fmt::format("{} is before the previous action's step {}", act.step, script.actions.back().step),
             "list the actions in step order");
    // The simulation does not step while paused, and a script runs unattended: an action after the
    // pause's step would wait for ever (until --timeout).
    if (paused_by != none && act.step > script.actions[paused_by].step)
      a.fail("step",
             fmt::format("{} comes after the pause at step {} (actions[{}]), and the simulation does not step while "
                         "paused, so it would never come",
                         act.step, script.actions[paused_by].step, paused_by),
             fmt::format("add a resume at step {}, or end the script there", script.actions[paused_by].step));
    if (act.kind == ScriptAction::Kind::pause) paused_by = i;
    if (act.kind == ScriptAction::Kind::resume) paused_by = none;
    if ((act.kind == ScriptAction::Kind::reset || act.kind == ScriptAction::Kind::load_preset) &&
        ++rebuilds > kMaxScriptRebuilds)
      a.fail("action",
             fmt::format("more than {} reset and load_preset actions, each of which builds the scene again",
                         kMaxScriptRebuilds),
             "reset less often: a script is a session, not a benchmark of resets");
    switch (act.kind) {
      case ScriptAction::Kind::move:
        act.position_mm = a.vec3("position_mm", "the tool tip's position in mm, e.g. [0, 0, 2]");
        break;
      case ScriptAction::Kind::switch_tool:
        act.name = a.string("tool", "the instrument: ball_burnisher, flat_plugger or condenser");
        try {
          (void)tool_by_name(act.name, 3e-4, Solver::paper);
        } catch (const std::exception& e) {
          a.fail("tool", e.what(), "use ball_burnisher, flat_plugger or condenser");
        }
        break;
      case ScriptAction::Kind::colour_by:
        act.name = a.string("mode", "role, pressure, density, speed, bonds or conversion");
        try {
          (void)colour_by_from_name(act.name);
        } catch (const std::exception& e) {
          a.fail("mode", e.what(), "use role, pressure, density, speed, bonds or conversion");
        }
        break;
      case ScriptAction::Kind::load_preset: {
        act.name = a.string("preset", fmt::format("the paste preset: {}", fmt::join(paste_preset_names(), ", ")));
        act.temperature_c = a.number_or("temperature_c", 23, "the paste's temperature in C, 10 to 70");
        try {
          (void)paste_preset(act.name, act.temperature_c);
        } catch (const std::exception& e) {
          a.fail(std::string(e.what()).find("temperature") != std::string::npos ? "temperature_c" : "preset", e.what(),
                 fmt::format("use one of {} at 10 to 70 C", fmt::join(paste_preset_names(), ", ")));
        }
        break;
      }
      default:
        break;
    }
    script.actions.push_back(act);
  }
  return script;
}

InputScript load_input_script(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in)
    scene::fail(file.string(), "(file)", "cannot be opened", "check the path of --script");
  std::stringstream text;
  text << in.rdbuf();
  return parse_input_script(text.str(), file.string());
}

}  // namespace dentsph::viewer
