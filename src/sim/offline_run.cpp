// The offline run loop: tool pose from the trajectory, one step, outputs, stability bookkeeping.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "dentsph/assess.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/run.hpp"
#include "dentsph/step.hpp"
#include "io/preview.hpp"
#include "io/summary.hpp"
#include "io/vtk_writer.hpp"

namespace dentsph {

StabilityLimits check_time_step(const Scene& scene, const State& state, bool allow_unstable) {
  const StabilityLimits l = stability_limits(scene.model, state);
  const real dt = scene.model.dt;
  if (scene.model.solver == Solver::iisph) {
    // The velocity CFL condition, against the fastest the scene's tool moves (the material moves
    // with it or slower; a device's hand is checked as it goes, by the force limit entry).
    const real v = scene_tool_speed(scene), limit = velocity_time_step_limit(scene.model, v);
    if (dt > limit && !allow_unstable)
      throw UnstableTimeStep(fmt::format(
          "{}: simulation.dt: {:.3g} s is over the iisph solver's velocity CFL limit of {:.3g} s (cfl {:.3g} * h {:.3g} m "
          "/ {:.3g} m/s, the tool's fastest speed between its keyframes); set simulation.dt to at most {:.3g}, slow "
          "the tool, or pass --allow-unstable to run anyway",
          scene.source, dt, limit, scene.model.iisph.cfl, scene.model.kernel.h, v, limit));
    return l;
  }
  const real limit = std::min(l.acoustic, l.viscous);
  if (dt > limit && !allow_unstable) {
    const char* which = l.acoustic <= l.viscous ? "acoustic (lambda h / sqrt(max stiffness))"
                                                : "viscous (0.125 h^2 rest_density / viscosity)";
    throw UnstableTimeStep(fmt::format(
        "{}: simulation.dt: {:.3g} s is over the {} stability limit of {:.3g} s (acoustic {:.3g} s, viscous {:.3g} s); "
        "set simulation.dt to at most {:.3g}, lower the stiffest material's stiffness or viscosity, choose the "
        "iisph solver (simulation.solver, --solver iisph), or pass --allow-unstable to run anyway",
        scene.source, dt, which, limit, l.acoustic, l.viscous, limit));
  }
  return l;
}

namespace {

// Particle snapshots every `interval` s of simulated time, indexed by a .pvd file.
class SnapshotWriter {
 public:
  SnapshotWriter(const std::filesystem::path& dir, real interval)
      : dir_(dir), interval_(interval), index_(dir / "particles.pvd") {
    std::filesystem::create_directories(dir_ / "particles");
  }
  bool due(const State& s) const { return interval_ > 0 && s.time + 1e-12 >= next_; }
  void maybe_write(const State& s, bool force = false) {
    if (!force && !due(s)) return;
    const std::string name = fmt::format("particles/step_{:08d}.vtu", s.steps);
    io::write_vtu(dir_ / name, s);
    index_.add(s.time, name);
    next_ = s.time + interval_;
  }
  std::size_t count() const { return index_.size(); }

 private:
  std::filesystem::path dir_;
  real interval_;
  real next_ = 0;
  io::PvdIndex index_;
};

}  // namespace

RunSummary run_offline(const Scene& scene, const RunOptions& opt) {
  State state = make_state(scene);
  RunSummary sum;
  sum.scene = scene.name;
  sum.force_scale = scene.force_scale;
  sum.threads = opt.threads;
  sum.dt = scene.model.dt;
  sum.solver = scene.model.solver;
  sum.limits = check_time_step(scene, state, opt.allow_unstable);
  sum.acoustic_violated = sum.dt > sum.limits.acoustic;
  sum.viscous_violated = sum.dt > sum.limits.viscous;
  sum.forced = opt.allow_unstable && (sum.acoustic_violated || sum.viscous_violated);

  const real duration = opt.duration > 0 ? opt.duration : scene.duration;
  const std::uint64_t total = opt.steps > 0 ? opt.steps : std::uint64_t(std::llround(duration / scene.model.dt));

  std::unique_ptr<SnapshotWriter> snaps;
  std::unique_ptr<io::ToolForceCsv> csv;
  if (!opt.out_dir.empty()) {
    std::filesystem::create_directories(opt.out_dir);
    if (scene.output.vtk) snaps = std::make_unique<SnapshotWriter>(opt.out_dir, scene.output.snapshot_interval);
    csv = std::make_unique<io::ToolForceCsv>(opt.out_dir / "tool_force.csv");
    if (snaps) snaps->maybe_write(state, true);
  }

  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const std::uint64_t report_every = std::max<std::uint64_t>(1, total / 100);
  sum.limits.force = std::numeric_limits<real>::infinity();
  // Dental scenes: the cavity voxelised once, the tool force accumulated every step.
  std::optional<CavityAssessor> assessor;
  if (scene.tooth) {
    AssessParams ap;
    ap.spacing = scene.material_spacing;
    assessor.emplace(*scene.tooth, ap);
    sum.cavity_json = cavity_json(*scene.tooth);
  }
  ForceStats forces;
  // A GPU backend keeps the particles on the GPU: each step reads back only the wrench and the
  // diagnostics; the particles come down for snapshots, events and the end of the run.
  std::unique_ptr<GpuStepper> gpu;
  if (opt.backend != Backend::cpu) gpu = make_gpu_stepper(opt.backend, scene.model, state);
  std::size_t next_event = 0;
  std::uint64_t solver_steps = 0;  // iisph: steps whose solve statistics were summed
  for (std::uint64_t k = 0; k < total; ++k) {
    // Events due by this step (a half step early, so that an event at t lands on the step at t).
    while (next_event < scene.events.size() && scene.events[next_event].t <= state.time + 0.5 * scene.model.dt) {
      if (gpu) gpu->download(state);
      apply_event(scene, state, scene.events[next_event++]);
      if (gpu) gpu = make_gpu_stepper(opt.backend, scene.model, state);
      ++sum.events_applied;
    }
    const real t_forces = state.time;
    state.tool_pose = scene.tool.at(state.time + scene.model.dt);
    if (gpu) {
      gpu->step(state.tool_pose);
      gpu->copy_results(state);
    } else {
      step(scene.model, state, StepOptions{opt.threads, nullptr});
    }
    if (csv) csv->add(t_forces, state.tool_wrench);
    if (sum.solver == Solver::iisph) {
      ++solver_steps;
      const StepDiagnostics& d = state.diagnostics;
      sum.iterations_mean += d.pressure_iterations;
      sum.iterations_max = std::max(sum.iterations_max, d.pressure_iterations);
      sum.density_error_mean += d.density_error;
      sum.density_error_max = std::max<double>(sum.density_error_max, d.density_error);
      sum.pressure_residual_max = std::max<double>(sum.pressure_residual_max, d.pressure_residual);
    }
    sum.peak_tool_force_N = std::max(sum.peak_tool_force_N, norm(state.tool_wrench.force));
    forces.add(state.tool_wrench.force, scene.model.dt);
    const real force_limit = force_time_step_limit(scene.model, state.diagnostics);
    sum.limits.force = std::min(sum.limits.force, force_limit);
    if (sum.dt > force_limit) {
      if (sum.force_violation_steps++ == 0) sum.first_force_violation_t = t_forces;
    }
    // Exploded material: the run says so instead of writing garbage.
    if (exploded(state.diagnostics, sum.limits.sound_speed)) {
      const bool non_finite = state.diagnostics.non_finite > 0;
      sum.status = "diverged";
      sum.message = fmt::format(
          "{} at t = {:.6g} s (step {}); the smallest {} limit seen was {:.3g} s against dt = {:.3g} s: lower "
          "simulation.dt or the stiffness",
          non_finite ? fmt::format("{} material particles became non-finite", state.diagnostics.non_finite)
                     : fmt::format("material reached {:.3g} m/s, over {} times the sound speed {:.3g} m/s",
                                   state.diagnostics.max_speed, explosion_speed_factor, sum.limits.sound_speed),
          state.time, state.steps, scene.model.solver == Solver::iisph ? "velocity CFL" : "force", sum.limits.force,
          sum.dt);
      break;
    }
    if (snaps && gpu && snaps->due(state)) gpu->download(state);
    if (snaps) snaps->maybe_write(state);
    if (opt.on_progress && ((k + 1) % report_every == 0 || k + 1 == total)) {
      const double w = elapsed();
      opt.on_progress({k + 1, total, state.time, w, w / double(k + 1) * double(total - k - 1)});
    }
  }
  if (gpu) gpu->download(state);
  sum.steps = state.steps;
  if (solver_steps > 0) {
    sum.iterations_mean /= double(solver_steps);
    sum.density_error_mean /= double(solver_steps);
  }
  sum.material = state.count(Role::material);  // at the end: increments add material
  sum.boundary = state.count(Role::boundary);
  sum.tool = state.count(Role::tool);
  sum.sim_time_s = state.time;
  sum.wall_time_s = elapsed();
  sum.steps_per_second = sum.wall_time_s > 0 ? double(sum.steps) / sum.wall_time_s : 0;
  sum.bonds = state.bonds.counters;
  sum.bonds_current = state.bonded_pairs();
  if (snaps) {
    snaps->maybe_write(state, true);
    sum.snapshots = snaps->count();
  }
  if (assessor) {
    const Assessment a = assessor->assess(state, scene.model, forces, scene.force_scale);
    sum.assessment_json = assessment_json(a);
    sum.assessment_report = a.report();
  }
  if (!opt.out_dir.empty()) {
    io::write_summary(opt.out_dir / "summary.json", sum);
    io::write_preview_png(opt.out_dir / "preview.png", state, -scene.model.gravity, scene.model.kernel.h);
  }
  return sum;
}

}  // namespace dentsph
