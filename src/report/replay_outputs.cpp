// A replay written as a run folder (replay_outputs.hpp).
#include "report/replay_outputs.hpp"

#include <chrono>

#include "dentsph/assess.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/run.hpp"
#include "io/preview.hpp"
#include "io/summary.hpp"
#include "report/run_outputs.hpp"

namespace dentsph::report {

std::vector<Vec3> replay_to_folder(const Scene& scene, const Recording& r, int threads,
                                   const std::filesystem::path& dir, Backend backend) {
  std::filesystem::create_directories(dir);
  const State initial = make_state(scene);
  RunSummary sum;
  sum.scene = scene.name;
  sum.threads = threads;
  sum.backend = backend_name(backend);
  sum.dt = scene.model.dt;
  sum.limits = check_time_step(scene, initial, true);
  sum.acoustic_violated = sum.dt > sum.limits.acoustic;
  sum.viscous_violated = sum.dt > sum.limits.viscous;
  sum.force_scale = r.force_scale;
  ProcedureLog log(initial);
  State state;
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<Vec3> forces = replay_steps(scene, r, threads, backend, &state, [&](const State& s, const EventSample& e) {
    log.replayed(scene, s, e);
    ++sum.events_applied;
  });
  sum.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ForceStats stats;
  {
    io::ToolForceCsv csv(dir / "tool_force.csv");
    for (std::size_t k = 0; k < forces.size(); ++k) {
      ToolWrench w;
      w.force = forces[k];
      csv.add(real(k) * scene.model.dt, w);
      stats.add(forces[k], scene.model.dt);
      sum.peak_tool_force_N = std::max(sum.peak_tool_force_N, norm(forces[k]));
    }
  }
  sum.steps = state.steps;
  sum.sim_time_s = state.time;
  sum.steps_per_second = sum.wall_time_s > 0 ? double(sum.steps) / sum.wall_time_s : 0;
  sum.material = state.count(Role::material);
  sum.boundary = state.count(Role::boundary);
  sum.tool = state.count(Role::tool);
  sum.bonds = state.bonds.counters;
  sum.bonds_current = state.bonded_pairs();
  if (scene.tooth) {
    AssessParams p;
    p.spacing = scene.material_spacing > 0 ? scene.material_spacing : default_tooth_spacing;
    const Assessment a = CavityAssessor(*scene.tooth, p).assess(state, scene.model, stats, r.force_scale);
    sum.assessment_json = assessment_json(a);
    sum.assessment_report = a.report();
    sum.cavity_json = cavity_json(*scene.tooth);
  }
  io::write_summary(dir / "summary.json", sum);
  io::write_preview_png(dir / "preview.png", state, -scene.model.gravity, scene.model.kernel.h);
  finish_run(dir, scene, state, log);
  return forces;
}

}  // namespace dentsph::report
