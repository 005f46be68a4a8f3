#include "dentsph/io/summary.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace dentsph::io {

namespace {

// JSON has no infinity: an absent limit is written as null.
nlohmann::json seconds(real v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

std::string summary_json(const RunSummary& s) {
  nlohmann::json j;
  j["scene"] = s.scene;
  // The paste preset the scene was filled with (`run --material`) and its temperature, null for the
  // scene's own paste.
  j["material"] = s.paste_preset.empty() ? nlohmann::json(nullptr)
                                         : nlohmann::json{{"preset", s.paste_preset}, {"temperature_c", s.paste_temperature_c}};
  j["status"] = s.status;
  if (!s.message.empty()) j["message"] = s.message;
  j["steps"] = s.steps;
  j["sim_time_s"] = s.sim_time_s;
  j["wall_time_s"] = s.wall_time_s;
  j["steps_per_second"] = s.steps_per_second;
  j["backend"] = s.backend;
  j["threads"] = s.threads;
  j["particles"] = {{"material", s.material}, {"boundary", s.boundary}, {"tool", s.tool},
                    {"total", s.material + s.boundary + s.tool}};
  j["bonds"] = {{"current", s.bonds_current},
                {"formed", s.bonds.formed},
                {"broken", s.bonds.broken},
                {"overflowed", s.bonds.overflowed}};
  j["solver"] = {{"name", solver_name(s.solver)}};
  // The figures its solver recorded over the run (none for the paper's step).
  if (const SolverStatistics& st = s.solver_statistics; st.recorded)
    j["solver"].update({{"pressure_solve", pressure_solve_name(s.pressure_solve)},
                        {"gradient", gradient_name(s.gradient)},
                        {"density_kernel", density_kernel_name(s.density_kernel)},
                        {"pressure_iterations", {{"mean", st.iterations_mean()}, {"max", st.iterations_max}}},
                        {"density_error", {{"mean", st.density_error_mean()}, {"max", st.density_error_max}}},
                        // The compression measured at each step's start (not the solve's prediction).
                        {"compression", {{"mean", st.compression_mean()},
                                         {"mean_max", st.compression_mean_max},
                                         {"particle_max", st.compression_max}}},
                        // The viscous pressure's step (0: none) and the largest it reached.
                        {"viscous_pressure", {{"step", s.viscous_pressure}, {"max_Pa", st.viscous_pressure_max}}},
                        {"pressure_residual_max", st.pressure_residual_max},
                        // The largest density error a particle was left with (the cg solve; 0: not measured).
                        {"pressure_max_error", st.pressure_max_error},
                        // Steps whose solve stopped on its budget, not its tolerance, and how far off.
                        {"pressure_on_budget", {{"steps", st.on_budget_steps},
                                                {"share", st.steps > 0 ? double(st.on_budget_steps) / double(st.steps) : 0.0},
                                                {"residual_max", st.on_budget_residual_max}}},
                        // Steps whose solves stopped at the step's deadline (realtime runs), and how far off.
                        {"on_deadline", {{"steps", st.on_deadline_steps},
                                         {"share", st.steps > 0 ? double(st.on_deadline_steps) / double(st.steps) : 0.0},
                                         {"residual_max", st.on_deadline_residual_max}}},
                        {"viscosity", {{"iterations", st.viscosity_iterations_mean()},
                                       {"iterations_max", st.viscosity_iterations_max},
                                       {"residual_mean", st.viscosity_residual_mean()},
                                       {"residual_max", st.viscosity_residual_max},
                                       // A non-Newtonian material's Picard iterations and viscosities (0 without one).
                                       {"rheology", {{"iterations", st.rheology_iterations_mean()},
                                                     {"iterations_max", st.rheology_iterations_max},
                                                     {"viscosity_min_Pa_s", st.viscosity_min},
                                                     {"viscosity_max_Pa_s", st.viscosity_max}}}}},
                        {"wall_projections", {{"particles", st.wall_projections}, {"steps", st.wall_projection_steps}}},
                        {"substepped", {{"steps", st.substepped_steps}, {"most", st.substeps_max}}},
                        {"held_outside_domain", st.held_outside_domain}});
  j["stability"] = {{"dt_s", s.dt},
                    {"limits_s", {{"acoustic", seconds(s.limits.acoustic)},
                                  {"viscous", seconds(s.limits.viscous)},
                                  {"force_min", seconds(s.limits.force)}}},
                    {"violations", {{"acoustic", s.acoustic_violated},
                                    {"viscous", s.viscous_violated},
                                    {"force_steps", s.force_violation_steps},
                                    {"first_force_violation_t_s", s.first_force_violation_t >= 0
                                                                      ? nlohmann::json(s.first_force_violation_t)
                                                                      : nlohmann::json(nullptr)}}},
                    {"forced", s.forced}};
  j["tool"] = {{"peak_force_N", s.peak_tool_force_N},
               {"force_scale", s.force_scale},
               {"peak_device_force_N", s.peak_tool_force_N * s.force_scale}};
  j["snapshots"] = s.snapshots;
  if (s.surfaces > 0) j["paste_surface"] = {{"surfaces", s.surfaces}, {"seconds", s.surface_seconds}};
  j["events_applied"] = s.events_applied;
  if (!s.cavity_json.empty()) j["cavity"] = nlohmann::json::parse(s.cavity_json);
  if (!s.assessment_json.empty()) j["assessment"] = nlohmann::json::parse(s.assessment_json);
  if (s.curing) {
    nlohmann::json c = s.cure_json.empty() ? nlohmann::json::object() : nlohmann::json::parse(s.cure_json);
    c["light_on_s"] = s.light_on_s;
    c["at_rest_s"] = s.cure_at_rest_s;
    c["updates_at_rest"] = s.cure_updates_at_rest;
    j["cure"] = c;
  }
  if (!s.realtime_json.empty()) j.update(nlohmann::json::parse(s.realtime_json));
  return j.dump(2);
}

void write_summary(const std::filesystem::path& file, const RunSummary& s) {
  std::ofstream out(file);
  out << summary_json(s) << "\n";
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the summary", file.string()));
}

ToolForceCsv::ToolForceCsv(const std::filesystem::path& file) : f_(std::fopen(file.c_str(), "w")) {
  if (!f_) throw std::runtime_error(fmt::format("{}: cannot open for writing", file.string()));
  std::fputs("t,fx,fy,fz,tx,ty,tz\n", f_);
}

ToolForceCsv::~ToolForceCsv() {
  if (f_) std::fclose(f_);
}

void ToolForceCsv::add(real t, const ToolWrench& w) {
  fmt::print(f_, "{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", t, w.force.x, w.force.y, w.force.z, w.torque.x,
             w.torque.y, w.torque.z);
}

}  // namespace dentsph::io
