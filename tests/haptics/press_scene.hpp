// A small scene for the runtime's tests: a ball tool (radius 2 cm) above a block of paste
// (8 x 8 x 4 cm) in an open box; about a thousand particles, so that one thread keeps up with
// real time. Its keyframes press the tool 4 cm down over 0.4 s, hold 0.3 s and lift over 0.4 s.
#pragma once

#include <string>

#include "dentsph/scene.hpp"

namespace dentsph::testing {

inline std::string press_scene_json(const std::string& keyframes = R"([
      {"t": 0.0, "position": [0, 0, 0.09]},
      {"t": 0.4, "position": [0, 0, 0.05]},
      {"t": 0.7, "position": [0, 0, 0.05]},
      {"t": 1.1, "position": [0, 0, 0.09]}])") {
  const std::string json = R"({
  "name": "haptic_press",
  "simulation": {"dt": 5e-4, "h": 0.02, "gravity": [0, 0, -9.81]},
  "adhesion": {"A": 0.012, "B": 0.03, "eps": 3, "zeta": 2},
  "materials": {
    "paste": {"viscosity": 0.5, "stiffness": 60, "rest_density": 1000, "adhesion": 200},
    "wall": {"viscosity": 0.5, "stiffness": 200, "rest_density": 1000, "adhesion": 0},
    "instrument": {"viscosity": 0.5, "stiffness": 200, "rest_density": 1000, "adhesion": 0}
  },
  "roles": {"material": "paste", "boundary": "wall", "tool": "instrument"},
  "blocks": [
    {"role": "material", "shape": "box", "min": [-0.04, -0.04, 0.0], "max": [0.04, 0.04, 0.04], "spacing": 0.01},
    {"role": "boundary", "shape": "container", "min": [-0.04, -0.04, 0.0], "max": [0.04, 0.04, 0.07],
     "layers": 1, "open_top": true, "spacing": 0.01}
  ],
  "tool": {
    "blocks": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.02, "spacing": 0.01}],
    "keyframes": )" + keyframes + R"(
  },
  "output": {"snapshot_interval": 0, "vtk": false},
  "run": {"duration": 1.2}
})";
  return json;
}

inline Scene press_scene(const std::string& keyframes) { return parse_scene(press_scene_json(keyframes), "press_scene"); }
inline Scene press_scene() { return parse_scene(press_scene_json(), "press_scene"); }

}  // namespace dentsph::testing
