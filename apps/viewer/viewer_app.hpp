// The viewer's render loop: a GLFW window with OpenGL 3.3 core, the scene drawn from the
// simulation's snapshots, the mouse and keys as a stand-in haptic device, the panels, scripted
// input and screenshots. The simulation runs on its own thread (SimSession); this loop only reads
// its snapshots and posts commands, so a slow frame never slows the simulation.
#pragma once

#include <atomic>
#include <filesystem>
#include <optional>
#include <string>

#include "dentsph/assess.hpp"
#include "input_script.hpp"
#include "sim_session.hpp"

namespace dentsph::viewer {

struct ViewerOptions {
  int width = 1280, height = 800;
  std::filesystem::path screenshot;  // written after `frames` frames (and the script's end), then exit
  std::uint64_t frames = 0;          // 0: run until the window is closed
  std::optional<InputScript> script;
  double timeout_s = 0;              // > 0: give up (exit code 4) when the frames take longer
  std::string colour_by = "role";
  bool cut = false;
  bool surface = false;              // the paste drawn as its surface (key S toggles)
  bool vsync = true;
  double max_fps = 60;               // frames per second at most (0: no limit): software OpenGL draws on
                                     // the same cores the simulation uses, so the render loop sleeps
};

struct ViewerResult {
  std::uint64_t frames = 0;
  double fps_median = 0;                   // of per-second frame counts
  double frame_p50_ms = 0, frame_p99_ms = 0;
  double sim_steps_per_second = 0;         // the simulation's last measured rate
  std::uint64_t sim_steps = 0;
  std::uint64_t surfaces_built = 0;        // the paste's surfaces built for the surface view
  // The surface view's frames due the surface of the frame before's paste (it moved), and those of
  // them that drew an older one (PasteSurfaceView::frames_due, frames_late).
  std::uint64_t surface_frames_due = 0, surface_frames_late = 0;
  bool closed_by_user = false;             // window closed (or SIGINT / SIGTERM) before the end
  bool timed_out = false;
  Snapshot last;                           // the simulation when the loop ended
};

// Opens the window and runs until it is closed, or the frames (and the script) are done.
// Throws std::runtime_error when no window can be opened (no display, no OpenGL 3.3).
ViewerResult run_viewer(SimSession& session, const ViewerOptions& options);

// Set from a signal handler: the loop closes the window at its next frame.
void request_close();

}  // namespace dentsph::viewer
