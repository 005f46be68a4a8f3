// dentsph-viewer: see the tooth, move the tool, fill the cavity, watch the forces.
#include <csignal>
#include <cstdio>
#include <thread>

#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "backend_option.hpp"
#include "colour_map.hpp"
#include "dental_options.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics.hpp"
#include "dentsph/haptics/viewer_report.hpp"
#include "dentsph/io/summary.hpp"
#include "dentsph/paste_presets.hpp"
#include "dentsph/run.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/solver.hpp"
#include "input_script.hpp"
#include "option_checks.hpp"
#include "realtime.hpp"
#include "sim_session.hpp"
#include "viewer_app.hpp"

namespace {

// What a run of the viewer did, for scripts and tests; and its report for a tutor beside it.
void write_summary(const std::string& file, const dentsph::viewer::ViewerResult& r,
                   const std::optional<dentsph::RealtimeResult>& realtime, const dentsph::Scene& scene,
                   const std::vector<dentsph::viewer::SimSession::ForceSample>& forces) {
  using nlohmann::json;
  std::uint32_t material = 0;
  for (dentsph::Role role : r.last.role) material += role == dentsph::Role::material;
  json j = {{"frames", r.frames},
            {"fps_median", r.fps_median},
            {"frame_p50_ms", r.frame_p50_ms},
            {"frame_p99_ms", r.frame_p99_ms},
            {"closed_by_user", r.closed_by_user},
            {"timed_out", r.timed_out},
            {"sim", {{"steps", r.sim_steps}, {"steps_per_second", r.sim_steps_per_second}, {"time_s", r.last.time}}},
            {"surfaces_built", r.surfaces_built},
            {"surface_frames_due", r.surface_frames_due},
            {"surface_frames_late", r.surface_frames_late},
            {"backend", r.last.backend},
            {"particles", {{"material", material}, {"total", r.last.role.size()}}},
            {"tool", r.last.tool_name}};
  // The paste the session ended with (the Material panel's preset chooser may have changed it).
  j["material"] = scene.paste_preset.empty()
                      ? json()
                      : json{{"preset", scene.paste_preset}, {"temperature_c", scene.paste_temperature_c}};
  j["force_scale"] = scene.force_scale;
  {
    // Where the instrument is at the end (its tool frame's origin, the tip of the dental
    // instruments), in the frame of the script's moves: the tooth's, mm; world mm without a tooth.
    const dentsph::Vec3 p = r.last.tool_pose.position;
    const dentsph::Vec3 mm = (scene.tooth ? scene.tooth->frame().to_local(p) : p) * 1e3;
    j["tool_position_mm"] = {mm.x, mm.y, mm.z};
  }
  if (r.last.assessment) j["assessment"] = json::parse(dentsph::assessment_json(*r.last.assessment));
  if (realtime) j["realtime"] = json::parse(dentsph::realtime_json(*realtime));
  if (!r.last.message.empty()) j["message"] = r.last.message;
  {
    std::ofstream out(file);
    out << j.dump(2) << "\n";
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the summary (--summary)", file));
  }
  std::vector<dentsph::Vec3> positions(r.last.xyz.size() / 3);
  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = {r.last.xyz[3 * i], r.last.xyz[3 * i + 1], r.last.xyz[3 * i + 2]};
  // The viewer's own loop keeps the tool force of every step: the report plots it (under a device
  // the recording has it).
  const std::filesystem::path dir = dentsph::viewer_report_dir(file);
  std::filesystem::remove(dir / "tool_force.csv");  // an earlier session's, in a folder used again
  if (!realtime && !forces.empty()) {
    std::filesystem::create_directories(dir);
    dentsph::io::ToolForceCsv csv(dir / "tool_force.csv");
    for (const auto& f : forces) csv.add(f.t, f.wrench);
  }
  const auto report = dentsph::write_viewer_report(file, scene, positions, r.last.role, j,
                                                           realtime ? &*realtime : nullptr);
  fmt::print("wrote {}\n", report.string());
}

}  // namespace

int main(int argc, char** argv) {
  using namespace dentsph;
  CLI::App app{"dentsph-viewer: the dental filling simulation in a window. The mouse moves the tool (left drag; "
               "wheel for depth; space presses), D dispenses an increment, P pauses, N steps, R resets, T switches "
               "the tool, C changes the colouring, X cuts a section, B hides the boundary particles"};
  std::string scene_file, script_file, screenshot;
  viewer::ViewerOptions vo;
  viewer::SessionOptions so;
  so.threads = int(std::max(1u, std::thread::hardware_concurrency() > 1 ? std::thread::hardware_concurrency() - 1 : 1u));
  auto* scene_opt = app.add_option("scene", scene_file, "Scene file (JSON); none: the built-in dental scene")
                        ->check(CLI::ExistingFile);
  cli::DentalOptions dental;
  dental.add_options(app, scene_opt, false);
  app.add_option("--screenshot", screenshot, "Write a PNG of the window after --frames frames, then exit");
  app.add_option("--frames", vo.frames, "Frames to draw before the screenshot (or before exiting)");
  app.add_option("--script", script_file, "A sequence of inputs to replay (JSON; see docs/viewer.md)")
      ->check(CLI::ExistingFile);
  app.add_option("--width", vo.width, "Window width in pixels")->check(CLI::Range(64, 8192))->capture_default_str();
  app.add_option("--height", vo.height, "Window height in pixels")->check(CLI::Range(64, 8192))->capture_default_str();
  app.add_option("--threads", so.threads, "Threads of the simulation step")->check(CLI::Range(1, 1024))->capture_default_str();
  std::string backend = "cpu";
  cli::add_backend_option(app, backend);
  std::string solver;
  std::vector<std::string> solvers;  // the registered solvers (solver.hpp)
  for (const SolverEntry& e : registered_solvers()) solvers.push_back(e.name);
  app.add_option("--solver", solver,
                 fmt::format("The step: {} (docs/model.md, \"Solvers\"); default: the scene's simulation.solver",
                             solver_choices()))
      ->check(CLI::IsMember(solvers));
  app.add_option("--colour-by", vo.colour_by, "role, pressure, density, speed, bonds or conversion (the paste's degree of conversion under the curing light)")->capture_default_str();
  app.add_flag("--section", vo.cut, "Start with the section view (half of the tooth cut away)");
  app.add_flag("--surface", vo.surface, "Start with the paste drawn as its surface (key S toggles it and its particles)");
  app.add_flag("--paused", so.start_paused, "Start paused");
  app.add_option("--timeout", vo.timeout_s, "Give up after this many seconds (exit code 4); 0: never")
      ->check(cli::finite_range(0, 1e6));
  std::string summary_file;
  app.add_option("--summary", summary_file, "Write the frame and simulation rates and the final assessment as JSON");
  cli::RealtimeCommand device;
  device.add_device_options(app);
  bool no_vsync = false;
  app.add_flag("--no-vsync", no_vsync, "Do not wait for the display's refresh");
  app.add_option("--max-fps", vo.max_fps, "Frames per second at most; 0: as fast as possible (to measure)")
      ->check(cli::finite_range(0, 10000))
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // a refused command line exits 2, as every refusal (CLI11's codes are 100 and up)
  }
  vo.vsync = !no_vsync;
  if (!screenshot.empty() && vo.frames == 0) vo.frames = 1;
  vo.screenshot = screenshot;

  // Closing (SIGINT, SIGTERM) is asked for from here on: the scene, the simulation and the contact
  // field take seconds to build, and a signal then ended the viewer with no word (status 143); now
  // its first frame closes it cleanly.
  std::signal(SIGINT, [](int) { viewer::request_close(); });
  std::signal(SIGTERM, [](int) { viewer::request_close(); });
  try {
    (void)viewer::colour_by_from_name(vo.colour_by);
    if (!script_file.empty()) vo.script = viewer::load_input_script(script_file);
    Scene sc = !scene_file.empty() ? load_scene(scene_file) : dental.filled_scene();
    so.backend = parse_backend(backend);
    if (const std::string notice = choose_solver(sc, solver, so.backend != Backend::cpu); !notice.empty())
      fmt::print("{}\n", notice);
    const bool with_device = app.count("--device") > 0;
    RealtimeOptions ro;
    std::unique_ptr<Device> dev;
    if (with_device) {
      ro = device.options(sc, 0, so.threads, false, {});
      dev = device.make_device(sc, ro, false);
    }
    if (scene_file.empty())  // the Material panel's preset chooser: the same scene with another paste
      so.rebuild = [&dental, &solver, gpu = so.backend != Backend::cpu](const std::string& name, double temperature_c) {
        Scene rebuilt = dental.filled_scene(name.empty() ? std::nullopt
                                                         : std::optional<PastePreset>(paste_preset(name, temperature_c)));
        (void)choose_solver(rebuilt, solver, gpu);
        return rebuilt;
      };
    viewer::SimSession session(std::move(sc), so);
    if (dev) session.use_device(std::move(dev), ro);
    const viewer::ViewerResult r = viewer::run_viewer(session, vo);
    fmt::print("viewer: {} frames, {:.1f} fps (median), frame time p50 {:.2f} ms, p99 {:.2f} ms; simulation {} steps, "
               "{:.0f} steps/s\n",
               r.frames, r.fps_median, r.frame_p50_ms, r.frame_p99_ms, r.sim_steps, r.sim_steps_per_second);
    if (!screenshot.empty() && !r.closed_by_user && !r.timed_out) fmt::print("wrote {}\n", screenshot);
    if (session.realtime_result()) fmt::print("\n{}", realtime_report(*session.realtime_result()));
    if (!summary_file.empty()) write_summary(summary_file, r, session.realtime_result(), session.scene(), session.force_log());
    if (r.closed_by_user) fmt::print("viewer: closed before the end; the simulation stopped cleanly\n");
    if (r.timed_out) {
      fmt::print(stderr, "error: gave up after {:.0f} s (--timeout) before the frames and the script were done\n",
                 vo.timeout_s);
      return 4;
    }
  } catch (const std::exception& e) {
    return cli::failed(e);
  }
  return 0;
}
