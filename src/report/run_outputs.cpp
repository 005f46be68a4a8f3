// The end of a run's outputs (run_outputs.hpp).
#include "report/run_outputs.hpp"

#include <chrono>
#include <ctime>
#include <fstream>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/io/summary.hpp"
#include "dentsph/report/session_report.hpp"
#include "dentsph/surface_grade.hpp"
#include "io/preview.hpp"
#include "report/grading_picture.hpp"

namespace dentsph::report {

namespace {

nlohmann::json read_summary(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the run's summary", file.string()));
  return nlohmann::json::parse(in);
}

std::string utc_now() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

void write_summary(const std::filesystem::path& file, const nlohmann::json& j) {
  std::ofstream out(file);
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the summary", file.string()));
}

void pictures(const std::filesystem::path& dir, const Scene& scene, std::span<const Vec3> positions,
              std::span<const Role> roles, const nlohmann::json& summary, const SurfaceMesh& surface, real spacing) {
  PictureOptions o;
  o.spacing = spacing;
  if (summary.contains("assessment") && summary["assessment"].contains("voids"))
    for (const nlohmann::json& v : summary["assessment"]["voids"]) {
      const auto c = v.value("centre_mm", nlohmann::json::array());
      if (c.size() != 3 || !c[0].is_number() || !c[1].is_number() || !c[2].is_number()) continue;
      o.markers.push_back(scene.tooth->frame().to_world(Vec3{c[0].get<double>(), c[1].get<double>(), c[2].get<double>()} * 1e-3));
      o.marker_radii.push_back(std::cbrt(3 * v.value("volume_mm3", 0.0) / (4 * 3.14159265358979)) * 1e-3);
    }
  // The paste as its surface, and as particles (the report's second view).
  PictureOptions with_surface = o;
  with_surface.paste_surface = &surface;
  write_tooth_pictures(dir, *scene.tooth, positions, colour_by_role(roles, /*paste=*/false), with_surface);
  write_tooth_pictures(dir, *scene.tooth, positions, colour_by_role(roles), o, /*particles=*/true);
}

// A dental scene's end: the paste's surface (the paste within the model's domain: a diverged run's
// flung paste has none), graded against the tooth into the summary's "grading", and the pictures.
std::string surface_outputs(const std::filesystem::path& dir, const Scene& scene, std::span<const Vec3> positions,
                            std::span<const Role> roles) {
  if (!scene.tooth) return "";
  const real spacing = scene.material_spacing > 0 ? scene.material_spacing : default_tooth_spacing;
  const SurfaceMesh surface =
      particle_surface(paste_within(positions, roles, scene.model.domain_min, scene.model.domain_max), spacing);
  GradeParams gp;
  gp.spacing = spacing;
  const std::filesystem::path file = dir / "summary.json";
  nlohmann::json j = read_summary(file);
  const auto t0 = std::chrono::steady_clock::now();
  const SurfaceGrade grade = grade_surface(*scene.tooth, surface, gp);
  j["grading"] = nlohmann::json::parse(surface_grade_json(grade));
  j["grading"]["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_summary(file, j);
  write_grading_picture(dir, grade);
  pictures(dir, scene, positions, roles, j, surface, spacing);
  return surface_grade_report(grade);
}

}  // namespace

void stamp_summary(const std::filesystem::path& dir, const Scene& scene) {
  const std::filesystem::path file = dir / "summary.json";
  nlohmann::json j = read_summary(file);
  nlohmann::json session = {{"finished_at", utc_now()}};
  if (!scene.student.empty()) session["student"] = scene.student;
  if (!scene.exercise.empty()) session["exercise"] = scene.exercise;
  j["session"] = session;
  write_summary(file, j);
}

std::string finish_run(const std::filesystem::path& dir, const Scene& scene, std::span<const Vec3> positions,
                       std::span<const Role> roles, const ProcedureLog& log) {
  stamp_summary(dir, scene);
  std::string graded = surface_outputs(dir, scene, positions, roles);
  write_procedure_json(dir / "procedure.json", scene, log, {});
  write_session_report(dir);
  return graded;
}

std::string end_run(const std::filesystem::path& dir, const Scene& scene, const State& state, const RunSummary& summary,
                    const ProcedureLog& log) {
  io::write_summary(dir / "summary.json", summary);
  io::write_preview_png(dir / "preview.png", state, -scene.model.gravity, scene.model.kernel.h);
  stamp_summary(dir, scene);
  // Paste that has set (now wall) is drawn as paste.
  std::vector<Role> roles(state.role.begin(), state.role.end());
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.is_paste(i)) roles[i] = Role::material;
  std::string graded = surface_outputs(dir, scene, state.pos, roles);
  write_procedure_json(dir / "procedure.json", scene, log, log.thickness(scene, state));
  write_session_report(dir);
  return graded;
}

}  // namespace dentsph::report
