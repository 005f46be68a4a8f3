// A replay written as a run folder (replay_outputs.hpp).
#include "dentsph/haptics/replay_outputs.hpp"

#include <chrono>

#include "dentsph/assess.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/io/summary.hpp"
#include "dentsph/run.hpp"
#include "report/run_outputs.hpp"

namespace dentsph {

std::vector<Vec3> replay_to_folder(const Scene& scene, const Recording& r, int threads,
                                   const std::filesystem::path& dir, Backend backend) {
  std::filesystem::create_directories(dir);
  report::ProcedureLog log(make_state(scene));
  State state;
  RunSummary sum;
  const auto t0 = std::chrono::steady_clock::now();
  std::uint64_t events = 0;  // every recorded event: the scene's, the buttons' and the tool switches
  const std::vector<Vec3> forces = replay_steps(
      scene, r, threads, backend, &state,
      [&](const State& s, const EventSample& e) {
        log.replayed(scene, s, e);
        ++events;
      },
      &sum);
  // The simulation's summary (its solver's statistics, its cure) as an offline run's; the session's
  // force scale and the replay's own wall time.
  sum.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  sum.steps_per_second = sum.wall_time_s > 0 ? double(sum.steps) / sum.wall_time_s : 0;
  sum.force_scale = r.force_scale;
  sum.events_applied = events;
  ForceStats stats;
  {
    io::ToolForceCsv csv(dir / "tool_force.csv");
    for (std::size_t k = 0; k < forces.size(); ++k) {
      ToolWrench w;
      w.force = forces[k];
      csv.add(real(k) * scene.model.dt, w);
      stats.add(forces[k], scene.model.dt);
    }
  }
  if (scene.tooth) {
    AssessParams p;
    p.spacing = scene.material_spacing > 0 ? scene.material_spacing : default_tooth_spacing;
    const Assessment a = CavityAssessor(*scene.tooth, p).assess(state, scene.model, stats, r.force_scale);
    sum.assessment_json = assessment_json(a);
    sum.assessment_report = a.report();
  }
  report::end_run(dir, scene, state, sum, log);
  return forces;
}

}  // namespace dentsph
