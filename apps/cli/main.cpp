// dentsph: the command-line program. Subcommands: run (an offline run of a scene, or the haptic
// runtime with --realtime), replay (a realtime run's recording), validate (check a scene without
// running it), bench (steps per second), report (the tutor's report), material-test (virtual
// material tests).
#include <cstdio>
#include <exception>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <fstream>
#include <limits>
#include <thread>
#include <vector>

#include "backend_option.hpp"
#include "dental_options.hpp"
#include "dentsph/bench.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/limits.hpp"
#include "dentsph/run.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/solver.hpp"
#include "material_test.hpp"
#include "option_checks.hpp"
#include "output_dir.hpp"
#include "progress.hpp"
#include "realtime.hpp"
#include "report_command.hpp"

namespace {

using namespace dentsph;

void print_scene(const Scene& sc, const State& st) {
  fmt::print("scene      {} ({})\n", sc.name, sc.source);
  if (sc.tooth)
    fmt::print("cavity     {}; {}\n", cavity_description(sc.tooth->params()), sc.tooth->report().summary());
  fmt::print("particles  {} material, {} boundary, {} tool\n", st.count(Role::material), st.count(Role::boundary),
             st.count(Role::tool));
  fmt::print("kernel     h = {:.4g} m, adhesion A = {:.4g} m, B = {:.4g} m, eps = {}, zeta = {}\n", sc.model.kernel.h,
             sc.model.adhesion.A, sc.model.adhesion.B, sc.model.adhesion.eps, sc.model.adhesion.zeta);
  fmt::print("grid       {} x {} x {} cells of {:.4g} m\n", sc.model.grid.dims[0], sc.model.grid.dims[1],
             sc.model.grid.dims[2], sc.model.grid.cell_size);
  const StabilityLimits l = stability_limits(sc.model, st);
  const StepSolver& solver = solver_properties(sc.model.solver);
  fmt::print("solver     {} ({})\n", solver.name(), solver.description());
  fmt::print("time step  {}\n", solver.time_step_report(sc.model, l, scene_tool_speed(sc)));
}

int cmd_validate(const std::string& file) {
  const Scene sc = load_scene(file);
  const State st = make_state(sc);
  print_scene(sc, st);
  check_time_step(sc, st, false);
  fmt::print("ok: {} is a valid scene\n", file);
  return 0;
}

int cmd_bench(BenchOptions opt, const std::string& json_file, bool quick) {
  if (quick) {
    opt.sweep = {{8, 1}, {12, 1}, {16, 1}, {16, 2}};
    opt.cuda_sweep_sides = {8, 16, 32};
    opt.repeats = 3;
    opt.seconds_per_run = 0.1;
  }
  const BenchResult r = run_benchmarks(opt, [](const std::string& line) { spdlog::info("{}", line); });
  fmt::print("\n{}", bench_table(r));
  if (!json_file.empty()) {
    std::ofstream out(json_file);
    out << bench_json(r) << "\n";
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write the benchmark results", json_file));
    fmt::print("wrote {}\n", json_file);
  }
  return 0;
}

// --steps and --duration: at most limits::max_run_steps steps (the scene's own run.duration was
// checked when it was read).
void check_run_length(const Scene& sc, const RunOptions& opt) {
  if (opt.steps > limits::max_run_steps)
    throw std::invalid_argument(fmt::format("--steps {}: over the limit of {} steps of one run; give fewer steps",
                                            opt.steps, limits::max_run_steps));
  if (opt.steps == 0 && opt.duration > 0)
    if (const std::string problem = limits::run_length_problem(opt.duration, sc.model.dt); !problem.empty())
      throw std::invalid_argument(fmt::format("--duration {}: {}; give at most {:.4g} s", opt.duration, problem,
                                              double(limits::max_run_steps) * sc.model.dt));
}

// The scene of a scene file, or without one the filling procedure the dental options describe;
// --solver (when given) chooses its step over the scene's simulation.solver, and without it a GPU
// backend takes the paper's step (choose_solver), saying so (also under --quiet: not progress).
Scene scene_of(const std::string& file, const cli::DentalOptions& dental, const std::string& solver, Backend backend) {
  Scene sc = !file.empty() ? load_scene(file) : dental.procedure_scene();
  const std::string notice = choose_solver(sc, solver, backend != Backend::cpu);
  if (!notice.empty()) fmt::print("{}\n", notice);
  return sc;
}

int cmd_run(const std::string& file, const cli::DentalOptions& dental, const std::string& solver,
            const std::string& pressure_solve, std::optional<double> viscous_pressure, RunOptions opt, bool quiet,
            cli::RealtimeCommand& rt, const cli::SessionOptions& session) {
  // No scene file: a filling procedure (the built-in one or --procedure) on the built-in molar
  // crown or on the given scanned tooth, with the cavity of the options.
  Scene sc = scene_of(file, dental, solver, opt.backend);
  if (const std::optional<PressureSolve> ps = pressure_solve_from_name(pressure_solve)) {
    sc.params.iisph.pressure_solve = *ps;
    sc.model.iisph.pressure_solve = *ps;
  }
  if (viscous_pressure) {
    sc.params.iisph.viscous_pressure = *viscous_pressure;
    sc.model.iisph.viscous_pressure = *viscous_pressure;
  }
  session.apply(sc);
  // The outputs' folder, made and written once before anything runs: a run never ends by losing them.
  if (rt.enabled())
    cli::prepare_output_dir(opt.out_dir, "--out", {"recording"});
  else
    cli::prepare_output_dir(opt.out_dir, "--out");
  if (!quiet) print_scene(sc, make_state(sc));
  std::fflush(stdout);  // before the progress on stderr
  if (rt.enabled()) return rt.run(sc, opt, quiet);
  if (opt.steps == 0 && opt.duration <= 0 && sc.duration <= 0)
    throw std::invalid_argument(fmt::format(
        "{}: no run length: give --steps N or --duration SECONDS, or set run.duration in the scene", sc.source));
  check_run_length(sc, opt);
  if (!quiet) opt.on_progress = cli::ProgressReporter();
  const RunSummary s = run_offline(sc, opt);
  fmt::print("\n{} steps ({:.4g} s simulated) in {:.2f} s: {:.0f} steps/s\n", s.steps, s.sim_time_s, s.wall_time_s,
             s.steps_per_second);
  fmt::print("bonds: {} now, {} formed, {} broken, {} overflowed\n", s.bonds_current, s.bonds.formed,
             s.bonds.broken, s.bonds.overflowed);
  fmt::print("peak tool force: {:.4g} N simulated, {:.4g} N on a haptic device (force scale {:.4g})\n",
             s.peak_tool_force_N, s.peak_tool_force_N * s.force_scale, s.force_scale);
  if (const SolverStatistics& st = s.solver_statistics; st.recorded)
    fmt::print("pressure solve: {:.1f} iterations a step (at most {}), density error mean {:.3g}% (max {:.3g}%); "
               "{} of {} steps ({:.1f}%) stopped on the iteration budget, at a residual of up to {:.3g}%\n"
               "compression measured at a step's start: mean {:.3g}% (a step's at most {:.3g}%, a particle's {:.3g}%)\n"
               "viscosity solve: {:.1f} iterations a step (at most {}), relative residual mean {:.3g} (max {:.3g})\n",
               st.iterations_mean(), st.iterations_max, 100 * st.density_error_mean(), 100 * st.density_error_max,
               st.on_budget_steps, st.steps, st.steps > 0 ? 100.0 * double(st.on_budget_steps) / double(st.steps) : 0.0,
               100 * st.on_budget_residual_max, 100 * st.compression_mean(), 100 * st.compression_mean_max,
               100 * st.compression_max, st.viscosity_iterations_mean(), st.viscosity_iterations_max,
               st.viscosity_residual_mean(),
               st.viscosity_residual_max);
  if (const SolverStatistics& st = s.solver_statistics; st.recorded && s.viscous_pressure > 0)
    fmt::print("viscous pressure: step {:.3g}, at most {:.4g} kPa\n", s.viscous_pressure, st.viscous_pressure_max / 1e3);
  if (const SolverStatistics& st = s.solver_statistics; st.recorded && st.rheology_iterations_max > 0)
    fmt::print("rheology: {:.2f} Picard iterations a step (at most {}), effective viscosity {:.3g} to {:.3g} Pa s\n",
               st.rheology_iterations_mean(), st.rheology_iterations_max, st.viscosity_min, st.viscosity_max);
  if (!s.assessment_report.empty()) fmt::print("\nassessment of the filling:\n{}", s.assessment_report);
  if (!s.grading_report.empty()) fmt::print("\nthe surface graded as a tutor grades a restoration:\n{}", s.grading_report);
  if (s.curing)
    fmt::print("\nlight curing: {:.4g} s of light, {:.4g} s of it in {} updates at rest\n{}", s.light_on_s,
               s.cure_at_rest_s, s.cure_updates_at_rest, s.cure_report);
  if (!opt.out_dir.empty()) fmt::print("report for a tutor: {}\n", (opt.out_dir / "report.html").string());
  if (s.force_violation_steps > 0)
    fmt::print("warning: dt exceeded the force stability limit in {} steps (first at t = {:.4g} s; smallest limit "
               "{:.3g} s)\n",
               s.force_violation_steps, s.first_force_violation_t, s.limits.force);
  if (!opt.out_dir.empty())
    fmt::print("wrote {}: summary.json, tool_force.csv, particles.pvd ({} snapshots; open it in ParaView){}\n",
               opt.out_dir.string(), s.snapshots,
               s.surfaces > 0 ? fmt::format(", paste_surface.pvd (the paste's surface beside each; {:.1f} s to build)",
                                            s.surface_seconds)
                              : std::string());
  if (s.status != "completed") {
    fmt::print(stderr, "error: the run diverged: {}\n", s.message);
    return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"dentsph: SPH simulation of dental filling material with haptic force output"};
  app.require_subcommand(1);

  std::string run_scene, out_dir = "out";
  RunOptions opt;
  bool quiet = false;
  CLI::App* run = app.add_subcommand("run", "Run a scene offline and write snapshots, tool force and a summary");
  auto* scene_opt =
      run->add_option("scene", run_scene, "Scene file (JSON); none: the built-in filling procedure")->check(CLI::ExistingFile);
  cli::DentalOptions run_dental;
  run_dental.add_options(*run, scene_opt, true);
  auto* steps = run->add_option("--steps", opt.steps, "Number of steps")->check(CLI::PositiveNumber);
  run->add_option("--duration", opt.duration, "Simulated seconds (instead of --steps); with --realtime: wall seconds")
      ->check(cli::finite_positive())  // its limit: the scene's steps, checked with the scene
      ->excludes(steps);
  run->add_option("--out", out_dir, "Output folder")->capture_default_str();
  run->add_flag("--allow-unstable", opt.allow_unstable, "Run even when dt is over a stability limit");
  run->add_flag("-q,--quiet", quiet, "No progress output");
  opt.threads = int(std::max(1u, std::thread::hardware_concurrency()));
  run->add_option("--threads", opt.threads, "Threads for the parallel stages")->check(CLI::Range(1, 1024))->capture_default_str();
  cli::RealtimeCommand realtime;
  realtime.add_options(*run);
  cli::SessionOptions session;
  session.add_options(*run);
  cli::ReportCommand report;
  report.add_subcommand(app);
  std::string run_backend = "cpu", bench_backend = "cpu", replay_backend = "cpu";
  cli::add_backend_option(*run, run_backend);
  // The registered solvers (solver.hpp), each with what it is.
  std::vector<std::string> solvers, described;
  for (const SolverEntry& e : registered_solvers()) {
    solvers.push_back(e.name);
    described.push_back(fmt::format("{} ({})", e.name, solver_properties(e.key).description()));
  }
  const std::string solver_help =
      fmt::format("The step: {}; default: the scene's simulation.solver", fmt::join(described, " or "));
  std::string run_solver, replay_solver, bench_solver;
  run->add_option("--solver", run_solver, solver_help)->check(CLI::IsMember(solvers));
  std::string run_pressure_solve;
  run->add_option("--pressure-solve", run_pressure_solve,
                  "The iisph solver's pressure solve: jacobi (relaxed Jacobi) or cg (projected conjugate gradients, "
                  "docs/model.md); default: the scene's simulation.iisph.pressure_solve")
      ->check(CLI::IsMember({"jacobi", "cg"}));
  std::optional<double> run_viscous_pressure;
  run->add_option("--viscous-pressure", run_viscous_pressure,
                  "The iisph solver's viscous pressure step, 0 to 1: a viscous paste kept at its volume (0.5 "
                  "suggested; docs/model.md, \"The viscous pressure\"); default: the scene's "
                  "simulation.iisph.viscous_pressure (0.5 for a --material preset, otherwise 0, none)")
      ->check(CLI::Range(0.0, 1.0));

  BenchOptions bench_opt;
  std::string bench_json_file;
  bool bench_quick = false;
  CLI::App* bench = app.add_subcommand("bench", "Measure steps per second: the built-in dental scene and a sweep over particle counts");
  bench->add_option("--threads", bench_opt.threads, "Thread counts to measure (e.g. --threads 1 2)")->capture_default_str();
  bench->add_option("--json", bench_json_file, "Also write the results as JSON to this file");
  bench->add_option("--repeats", bench_opt.repeats, "Runs per configuration (the median is reported)")->check(CLI::Range(1, 100))->capture_default_str();
  bench->add_flag("--quick", bench_quick, "A short sweep (up to two cups of 16^3 material particles, 15k particles; blocks up to 32^3 with cuda; 3 repeats)");
  bench->add_option("--grid-reach", bench_opt.sweep_grid_reach, "The sweep's grid: cells of h / N searched N deep")
      ->check(CLI::Range(1, 3))
      ->capture_default_str();
  cli::add_backend_option(*bench, bench_backend,
                          "cpu (thread counts), or cuda: the sweep then reaches 2 million particles (cuda-emulation: "
                          "the GPU's algorithm on the CPU)");
  bench->add_option("--solver", bench_solver,
                    fmt::format("The step the built-in dental scene and the sweep run: {} (default: paper)", solver_choices()))
      ->check(CLI::IsMember(solvers));

  std::string replay_dir, replay_scene;
  int replay_threads = 1;
  CLI::App* replay = app.add_subcommand("replay", "Replay a realtime run's recording into its scene and compare the tool forces");
  replay->add_option("recording", replay_dir, "Recording folder (OUT/recording of dentsph run --realtime)")
      ->required()
      ->check(CLI::ExistingDirectory);
  auto* replay_scene_opt =
      replay->add_option("scene", replay_scene, "The scene that was run (none: the filling procedure that was run)")
          ->check(CLI::ExistingFile);
  cli::DentalOptions replay_dental;
  replay_dental.add_options(*replay, replay_scene_opt, true);
  replay->add_option("--threads", replay_threads, "Threads for the parallel stages")->check(CLI::Range(1, 1024));
  cli::add_backend_option(*replay, replay_backend,
                          "Where the replay steps: the recording's backend reproduces its forces bit for bit, another "
                          "agrees within the backends' parity tolerance");
  std::string replay_out;
  replay->add_option("--out", replay_out, "Also write the replay as a run folder with its report (report.html)");
  replay->add_option("--solver", replay_solver, solver_help + " (give the one the run used)")->check(CLI::IsMember(solvers));

  std::string validate_scene;
  CLI::App* validate = app.add_subcommand("validate", "Check a scene file without running it");
  validate->add_option("scene", validate_scene, "Scene file (JSON)")->required();

  cli::MaterialTestCommand material_test;
  material_test.add_to(app);

  // A command line CLI11 refuses (a missing scene file, an unknown option, a value out of range)
  // exits 2 as every other refusal does (CLI11's own codes are 100 and up); --help exits 0.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    if (*run) {
      if (out_dir.empty()) cli::prepare_output_dir(out_dir, "--out");  // refused: writes nothing
      opt.out_dir = out_dir;
      opt.backend = parse_backend(run_backend);
      session.check(opt.out_dir);  // the store, before the session: never lost at its end
      const int rc = cmd_run(run_scene, run_dental, run_solver, run_pressure_solve, run_viscous_pressure, opt, quiet, realtime, session);
      if (rc == 0) session.record(opt.out_dir);
      return rc;
    }
    if (*validate) return cmd_validate(validate_scene);
    if (report.chosen()) return report.run();
    if (material_test.chosen()) return material_test.run();
    bench_opt.backend = parse_backend(bench_backend);
    if (!bench_solver.empty()) bench_opt.solver = *solver_from_name(bench_solver);
    if (*replay) {
      // The step is chosen by replay_recording: --solver, or else the recording's; the paste, by
      // --material, or else the recording's.
      if (replay_scene.empty()) {
        const Recording rec = load_recording(replay_dir);
        replay_dental.take_material(rec.material, rec.material_temperature_c);
      }
      return cli::replay_recording(scene_of(replay_scene, replay_dental, "", Backend::cpu), replay_dir, replay_threads,
                                   parse_backend(replay_backend), replay_out, replay_solver);
    }
    if (*bench) return cmd_bench(bench_opt, bench_json_file, bench_quick);
  } catch (const std::exception& e) {
    return cli::failed(e);
  }
  return 0;
}
