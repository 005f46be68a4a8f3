// A synthetic run folder for the report's tests: summary.json, tool_force.csv and
// procedure.json written by the test, with the numbers the test chooses.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace dentsph::report::testing {

inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path d = std::filesystem::temp_directory_path() / ("dentsph_report_" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline nlohmann::json summary(double fill, int voids, double overfill, double peak_N, double mean_N) {
  return {{"scene", "synthetic"},
          {"status", "completed"},
          {"steps", 100},
          {"sim_time_s", 0.01},
          {"wall_time_s", 0.5},
          {"steps_per_second", 200.0},
          {"threads", 1},
          {"particles", {{"material", 900}, {"boundary", 1500}, {"tool", 42}, {"total", 2442}}},
          {"tool", {{"force_scale", 15000.0}, {"peak_force_N", peak_N / 15000}, {"peak_device_force_N", peak_N}}},
          {"session", {{"student", "A. Student"}, {"exercise", "class I"}, {"finished_at", "2026-01-02T03:04:05Z"}}},
          {"assessment",
           {{"fill_fraction", fill},
            {"void_count", voids},
            {"void_volume_mm3", voids * 0.125},
            {"voids", voids ? nlohmann::json::array({{{"centre_mm", {0.5, 0.0, -1.75}},
                                                       {"volume_mm3", 0.125},
                                                       {"wall_distance_mm", 0.25},
                                                       {"against", "floor"}}})
                            : nlohmann::json::array()},
            {"overfill_mm3", overfill},
            {"leaked_particles", 0},
            {"lost_particles", 0},
            {"cavity_volume_mm3", 32.5},
            {"peak_device_force_N", peak_N},
            {"mean_device_force_N", mean_N}}}};
}

// A folder with `s` as its summary, 200 steps of a force rising to peak_N / force_scale and
// two procedure events (an increment and a switch of instrument).
inline std::filesystem::path write_folder(const std::string& name, const nlohmann::json& s) {
  const std::filesystem::path d = fresh_dir(name);
  std::ofstream(d / "summary.json") << s.dump(2) << "\n";
  std::ofstream csv(d / "tool_force.csv");
  csv << "t,fx,fy,fz,tx,ty,tz\n";
  const double peak = s["tool"]["peak_device_force_N"].get<double>() / 15000;
  for (int k = 0; k < 200; ++k) csv << k * 5e-5 << ",0,0," << peak * k / 199.0 << ",0,0,0\n";
  const nlohmann::json procedure = {
      {"dt_s", 5e-5},
      {"events", {{{"step", 0}, {"t_s", 0.0}, {"kind", "dispense"}, {"source", "procedure"}, {"particles", 400}},
                  {{"step", 120}, {"t_s", 0.006}, {"kind", "switch_tool"}, {"source", "procedure"}, {"tool", "flat_plugger"}}}},
      {"increments", {{{"index", 1}, {"particles", 400}, {"thickness_median_mm", 0.75}, {"thickness_p90_mm", 0.875}}}}};
  std::ofstream(d / "procedure.json") << procedure.dump(2) << "\n";
  return d;
}

}  // namespace dentsph::report::testing
