// The offline run loop around a Simulation: the tool pose from the trajectory, one step, outputs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "dentsph/assess.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/io/summary.hpp"
#include "dentsph/run.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/surface.hpp"
#include "io/vtk_writer.hpp"
#include "report/run_outputs.hpp"

namespace dentsph {

namespace {

// Particle snapshots every `interval` s of simulated time, indexed by a .pvd file; with a paste
// spacing, the paste's surface beside each, indexed by its own.
class SnapshotWriter {
 public:
  // The surface of the paste within [lo, hi] (the model's domain).
  SnapshotWriter(const std::filesystem::path& dir, real interval, real surface_spacing, const Vec3& lo, const Vec3& hi)
      : dir_(dir), interval_(interval), index_(dir / "particles.pvd"), surface_spacing_(surface_spacing), lo_(lo),
        hi_(hi), surface_index_(dir / "paste_surface.pvd") {
    std::filesystem::create_directories(dir_ / "particles");
    if (surface_spacing_ > 0) std::filesystem::create_directories(dir_ / "paste_surface");
  }
  // `resting`: the paste is curing at rest (large cure updates): a snapshot every
  // kRestingInterval at most, so that a 20 s cure writes 20, not 2000.
  bool due(const State& s, bool resting = false) const {
    return interval_ > 0 && s.time + 1e-12 >= next_ + (resting ? std::max<real>(0, kRestingInterval - interval_) : 0);
  }
  void maybe_write(const State& s, bool force = false) {
    if (!force && !due(s)) return;
    const std::string name = fmt::format("particles/step_{:08d}.vtu", s.steps);
    io::write_vtu(dir_ / name, s);
    index_.add(s.time, name);
    if (surface_spacing_ > 0) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::string surface = fmt::format("paste_surface/step_{:08d}.vtp", s.steps);
      io::write_vtp(dir_ / surface, paste_surface(s, surface_spacing_, lo_, hi_));
      surface_index_.add(s.time, surface);
      surface_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    next_ = s.time + interval_;
  }
  static constexpr real kRestingInterval = 1.0;  // s
  std::size_t count() const { return index_.size(); }
  std::size_t surfaces() const { return surface_index_.size(); }
  double surface_seconds() const { return surface_seconds_; }

 private:
  std::filesystem::path dir_;
  real interval_;
  real next_ = 0;
  io::PvdIndex index_;
  real surface_spacing_;
  Vec3 lo_, hi_;
  io::PvdIndex surface_index_;
  double surface_seconds_ = 0;
};

}  // namespace

RunSummary run_offline(const Scene& scene, const RunOptions& opt) {
  Simulation sim(scene, {opt.backend, opt.threads, opt.allow_unstable});
  const real duration = opt.duration > 0 ? opt.duration : scene.duration;
  const std::uint64_t total = opt.steps > 0 ? opt.steps : std::uint64_t(std::llround(duration / scene.model.dt));

  std::unique_ptr<SnapshotWriter> snaps;
  std::unique_ptr<io::ToolForceCsv> csv;
  if (!opt.out_dir.empty()) {
    std::filesystem::create_directories(opt.out_dir);
    if (scene.output.vtk)
      snaps = std::make_unique<SnapshotWriter>(opt.out_dir, scene.output.snapshot_interval,
                                               scene.output.surface ? scene.material_spacing : 0,
                                               scene.model.domain_min, scene.model.domain_max);
    csv = std::make_unique<io::ToolForceCsv>(opt.out_dir / "tool_force.csv");
    if (snaps) snaps->maybe_write(sim.state(), true);
  }

  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const std::uint64_t report_every = std::max<std::uint64_t>(1, total / 100);
  // Dental scenes: the cavity voxelised once.
  std::optional<CavityAssessor> assessor;
  if (scene.tooth) {
    AssessParams ap;
    ap.spacing = scene.material_spacing;
    assessor.emplace(*scene.tooth, ap);
  }
  // A GPU backend keeps the particles on the GPU: each step reads back only the wrench and the
  // diagnostics; the particles come down for snapshots, events and the end of the run.
  const State& state = sim.state();
  // The procedure's log: each event as applied (the increments' particles, for their thickness).
  report::ProcedureLog procedure(state);
  // A run that cures goes by simulated time: while the paste cures at rest, the Simulation
  // advances the cure in large updates between a few steps (CureSchedule); --steps N takes N steps.
  const bool by_time = sim.curing() && opt.steps == 0;
  const real dt = scene.model.dt;
  auto finished = [&](std::uint64_t k) { return by_time ? state.time + 0.5 * dt >= duration : k >= total; };
  std::uint64_t k = 0;        // steps taken
  std::uint64_t reported = 0;  // progress: the last step-equivalent reported
  auto progress = [&] {
    if (!opt.on_progress) return;
    const std::uint64_t done =
        by_time ? std::min<std::uint64_t>(total, std::uint64_t(std::llround(state.time / dt))) : k;
    if (done < reported + report_every && done != total) return;
    reported = done;
    const double w = elapsed();
    opt.on_progress({done, total, state.time, w, done > 0 ? w / double(done) * double(total - done) : 0});
  };
  while (!finished(k)) {
    sim.apply_due_events([&](std::size_t i) { procedure.applied(sim.synced(), scene.events[i]); });
    if (by_time && sim.advance_cure_at_rest(duration) > 0) {
      if (snaps && snaps->due(state, true)) snaps->maybe_write(sim.synced());
      progress();
      continue;
    }
    const real t_forces = state.time;
    const bool going = sim.step(sim.keyframe_pose());
    ++k;
    if (csv) csv->add(t_forces, state.tool_wrench);
    if (!going) break;  // exploded material: the run says so instead of writing garbage
    if (snaps && snaps->due(state, sim.curing_at_rest())) snaps->maybe_write(sim.synced());
    progress();
  }
  RunSummary sum = sim.summary();
  sum.wall_time_s = elapsed();
  sum.steps_per_second = sum.wall_time_s > 0 ? double(sum.steps) / sum.wall_time_s : 0;
  if (snaps) {
    snaps->maybe_write(state, true);
    sum.snapshots = snaps->count();
    sum.surfaces = snaps->surfaces();
    sum.surface_seconds = snaps->surface_seconds();
  }
  if (assessor) {
    const Assessment a = assessor->assess(state, scene.model, sim.forces(), scene.force_scale);
    sum.assessment_json = assessment_json(a);
    sum.assessment_report = a.report();
  }
  if (!opt.out_dir.empty()) {
    csv.reset();  // flushed and closed: the report reads it
    sum.grading_report = report::end_run(opt.out_dir, scene, state, sum, procedure);
  }
  return sum;
}

}  // namespace dentsph
