// A run's output folder as the report reads it: summary.json (required), the force over time
// (tool_force.csv, or a realtime session's recording/steps.csv and haptic.csv), the procedure's
// events and increments (procedure.json, or the recording's events.csv), and the pictures.
// Everything the report shows comes from these files, so a run and `dentsph report` write the
// same report.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dentsph::report {

// A folder that is not a readable run folder. what() names the folder or file, the problem
// and the fix.
class SessionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A force curve for the plot, in device N against s.
struct Series {
  std::string label;
  std::vector<double> t, f;
};

struct Marker {
  double t = 0;       // s, on the plot's time axis
  std::string kind;   // "dispense" or "switch_tool"
  std::string label;  // for a person: "increment 2", "flat_plugger"
};

struct SessionFolder {
  std::filesystem::path dir;
  nlohmann::json summary;        // summary.json as written
  nlohmann::json procedure;      // procedure.json, or null
  bool realtime = false;         // summary.json has a "haptic" section
  std::string time_axis;         // "simulated time (s)" or "session time (s)"
  std::vector<Series> forces;    // device N
  std::vector<Marker> markers;
  std::vector<std::uint8_t> cut_png, top_png;  // the pictures (empty when absent)
  std::vector<std::uint8_t> cut_particles_png, top_particles_png;  // the same with the paste's particles
  std::vector<std::uint8_t> preview_png;       // preview.png, shown when there are no pictures
  std::vector<std::uint8_t> grading_svg;       // grading.svg, the surface against the intact tooth
};

// Reads `dir`. Throws SessionError for a missing folder, a missing or broken summary.json, or a
// broken force or procedure file (naming the file, the line and the fix).
SessionFolder read_session(const std::filesystem::path& dir);

// At most `buckets` pairs of points keeping each bucket's lowest and highest value in time
// order, so that a long curve stays small without losing its peaks.
Series decimate(const Series& s, std::size_t buckets);

}  // namespace dentsph::report
