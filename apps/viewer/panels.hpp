// The viewer's panels (Dear ImGui): simulation controls, display, material parameters with their
// stability limits, the tool force over time, the filling's assessment and the loops' rates.
// They read a snapshot and the UI state and return the commands the user gave.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "colour_map.hpp"
#include "sim_session.hpp"

namespace dentsph::viewer {

struct FrameStats {
  double fps = 0;             // frames per second over the last second
  double frame_p50_ms = 0, frame_p99_ms = 0;
  std::uint64_t frames = 0;
};

struct UiState {
  ColourBy colour_by = ColourBy::role;
  bool auto_range = true;
  Range range;
  bool show_boundary = true;
  bool cut = false;           // section through the tooth (half of it cut away)
  bool surface = false;       // the paste as its surface (dentsph/surface.hpp) instead of particles
  bool paused = false;
  int tool_index = 0;
  MaterialEdit material;      // being edited
  bool material_loaded = false;
  int preset_index = 0;       // the chooser: 0 the scene's own paste, k the k-th of paste_preset_names()
  float preset_temperature_c = 23;
  std::string loaded_preset;  // the snapshot's preset the edit fields were loaded from
  double loaded_temperature_c = 23;
  std::deque<float> force_history;  // N, |F| per snapshot, newest last
  std::string last_message;
};

// Draws every panel; appends what the user asked for to `commands`.
void draw_panels(const Snapshot& snap, UiState& ui, const FrameStats& stats, const std::vector<std::string>& tools,
                 std::vector<Command>& commands);

}  // namespace dentsph::viewer
