// A viewer session's report (viewer_report.hpp).
#include "dentsph/haptics/viewer_report.hpp"

#include <fstream>

#include <fmt/format.h>

#include "dentsph/dental.hpp"
#include "dentsph/haptics/replay.hpp"
#include "report/run_outputs.hpp"

namespace dentsph {

std::filesystem::path viewer_report_dir(const std::filesystem::path& summary_file) {
  return summary_file.parent_path() / (summary_file.stem().string() + "_report");
}

std::filesystem::path write_viewer_report(const std::filesystem::path& summary_file, const Scene& scene,
                                          std::span<const Vec3> positions, std::span<const Role> roles,
                                          const nlohmann::json& v, const RealtimeResult* rt) {
  const std::filesystem::path dir = viewer_report_dir(summary_file);
  std::filesystem::create_directories(dir);
  const nlohmann::json sim = v.value("sim", nlohmann::json::object());
  std::uint32_t counts[3] = {0, 0, 0};
  for (Role r : roles) ++counts[int(r)];
  const double force_scale = rt ? rt->recording.force_scale : double(scene.force_scale);
  nlohmann::json s = {{"scene", scene.name},
                      {"status", v.contains("message") && rt && rt->run.status != "completed" ? rt->run.status : "completed"},
                      {"steps", sim.value("steps", std::uint64_t(0))},
                      {"sim_time_s", sim.value("time_s", 0.0)},
                      {"wall_time_s", rt ? rt->run.wall_time_s : 0.0},
                      {"steps_per_second", sim.value("steps_per_second", 0.0)},
                      {"threads", rt ? rt->run.threads : 1},
                      {"particles", {{"material", counts[0]}, {"boundary", counts[1]}, {"tool", counts[2]},
                                     {"total", roles.size()}}},
                      {"tool", {{"force_scale", force_scale}}},
                      {"viewer", {{"frames", v.value("frames", 0)}, {"fps_median", v.value("fps_median", 0.0)}}}};
  if (rt)
    s["tool"]["peak_device_force_N"] = rt->run.peak_tool_force_N * force_scale;
  else if (v.contains("assessment"))
    s["tool"]["peak_device_force_N"] = v["assessment"].value("peak_device_force_N", 0.0);
  if (v.contains("assessment")) s["assessment"] = v["assessment"];
  if (scene.tooth) s["cavity"] = nlohmann::json::parse(cavity_json(*scene.tooth));
  if (rt) s.update(nlohmann::json::parse(realtime_json(*rt)));
  {
    std::ofstream out(dir / "summary.json");
    out << s.dump(2) << "\n";
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the report's summary", (dir / "summary.json").string()));
  }
  if (rt) save_recording(dir / "recording", rt->recording);
  std::uint32_t initial = 0;
  for (const ParticleInit& p : scene.particles) initial += p.role == Role::material;
  report::finish_run(dir, scene, positions, roles,
                     rt ? report::log_of_recording(scene, rt->recording) : report::ProcedureLog(initial));
  return dir / "report.html";
}

}  // namespace dentsph
