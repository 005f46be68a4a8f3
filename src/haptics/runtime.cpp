// The runtime: checks the options, starts the haptic and consumer threads, runs the simulation loop
// on the calling thread, and stops them
// when the device finishes, the duration passes, the caller asks or the simulation diverges,
// and gathers the reports, the recording and the shared summary.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <fmt/format.h>

#include "dentsph/dental.hpp"
#include "dentsph/dispense.hpp"
#include "dentsph/haptics.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/limits.hpp"
#include "haptics/clock.hpp"
#include "haptics/consumer_loop.hpp"
#include "haptics/contact_loop.hpp"
#include "haptics/haptic_loop.hpp"
#include "haptics/sim_loop.hpp"
#include "report/run_outputs.hpp"
#include "report/session_assessment.hpp"

namespace dentsph {

const char* force_mode_name(ForceMode m) { return m == ForceMode::direct ? "direct" : "coupling"; }

ForceMode force_mode_from_name(const std::string& name) {
  if (name == "direct") return ForceMode::direct;
  if (name == "coupling") return ForceMode::coupling;
  throw std::invalid_argument("force mode '" + name + "': use direct or coupling");
}

void check_realtime_options(const RealtimeOptions& o, double force_scale) {
  auto bad = [](const std::string& what) { throw std::invalid_argument(what); };
  if (!(o.haptic_rate_hz >= 500 && o.haptic_rate_hz <= 4000))
    bad(fmt::format("haptic rate {} Hz: use 500 to 4000 Hz", o.haptic_rate_hz));
  if (!(o.snapshot_rate_hz == 0 || (o.snapshot_rate_hz >= 30 && o.snapshot_rate_hz <= 60)))
    bad(fmt::format("snapshot rate {} Hz: use 30 to 60 Hz (0: no consumer)", o.snapshot_rate_hz));
  if (!(force_scale >= 1e-6 && force_scale <= 1e9))
    bad(fmt::format("force scale {}: use 1e-6 to 1e9 device N per simulated N", force_scale));
  if (!(o.workspace.scale >= 1e-4 && o.workspace.scale <= 1e4) || !is_finite(o.workspace.origin) ||
      norm(o.workspace.origin) > 10)
    bad(fmt::format("workspace: the scale {} must be 1e-4 to 1e4 scene m per device m, the origin finite and within "
                    "10 m",
                    o.workspace.scale));
  if (!(o.coupling.stiffness_N_per_m >= 1 && o.coupling.stiffness_N_per_m <= 1e7) ||
      !(o.coupling.damping_N_s_per_m >= 0 && o.coupling.damping_N_s_per_m <= 1e4))
    bad(fmt::format("virtual coupling: stiffness {} N/m must be 1 to 1e7 (stable over that range, tested), damping {} "
                    "N s/m 0 to 1e4",
                    o.coupling.stiffness_N_per_m, o.coupling.damping_N_s_per_m));
  if (!(o.solve_share >= 0 && o.solve_share <= 1))
    bad(fmt::format("solve share {}: the share of a step's dt its solves may take must be in [0, 1] (0: no deadline)",
                    o.solve_share));
  if (!(o.duration_s >= 0) || !(o.sim_rate_limit_hz >= 0) || !(o.threads >= 1))
    bad("duration and simulation rate limit must be non-negative, threads at least 1");
  if (!(o.record_capacity_s >= 0) || o.record_capacity_s * o.haptic_rate_hz > double(limits::max_recorded_ticks))
    bad(fmt::format("record capacity {} s: at {} Hz a recording holds at most {} ticks, so that replay reads its "
                    "haptic.csv back; give 0 to {:.0f} s",
                    o.record_capacity_s, o.haptic_rate_hz, limits::max_recorded_ticks,
                    std::floor(double(limits::max_recorded_ticks) / o.haptic_rate_hz)));
  if (o.duration_s > limits::max_realtime_s)
    bad(fmt::format("duration {} s: a realtime run lasts at most {:.0f} s of wall time", o.duration_s,
                    limits::max_realtime_s));
  const WatchdogParams& w = o.watchdog;
  if (!(o.dispense_volume >= 0) || !std::isfinite(o.dispense_volume))
    bad(fmt::format("dispense volume {} m^3: must be non-negative and finite (0: a sixth of the cavity)", o.dispense_volume));
  if (!(w.sim_timeout_s > 0 && w.pose_timeout_s > 0 && w.ramp_down_s >= 0 && w.ramp_up_s >= 0))
    bad("watchdog: timeouts must be positive, ramps non-negative");
}

RealtimeResult run_realtime(const Scene& scene, Device& device, const RealtimeOptions& opt) {
  const double force_scale = opt.force_scale.value_or(double(scene.force_scale));
  check_realtime_options(opt, force_scale);
  // The simulation first: it checks dt and starts the backend before any thread starts.
  SimulationOptions sim_options{opt.backend, opt.threads, opt.allow_unstable};
  if (opt.pace_realtime && opt.solve_share > 0) sim_options.solve_budget_s = opt.solve_share * double(scene.model.dt);
  Simulation core(scene, sim_options);
  RealtimeResult res;
  haptics::Snapshot empty;
  empty.positions.resize(std::size_t(core.state().size()) * 2 + 1024);  // room for dispensed increments
  // The hard contact's field (the tooth, the band, set paste) and the instrument's shape, built
  // before the threads start; rebuilt by the contact loop when paste sets.
  haptics::ContactWorld world;
  world.field = opt.contact_field ? *opt.contact_field : scene_contact_field(scene);
  world.shape = instrument_contact_shape(scene, core.state());
  haptics::RigidInput rigid;
  rigid.particles.reserve(core.state().size() * 2 + 1024);
  haptics::RuntimeShared shared(empty, world, rigid);
  haptics::HapticLoop haptic(device, opt, shared);
  haptics::SimLoop sim(core, opt, force_scale, shared, scene_rigid_band(scene));
  haptics::ConsumerLoop consumer(opt, shared);
  haptics::ContactLoop contact(shared);

  const std::int64_t t0 = haptics::now_ns() + 20'000'000;  // the threads start together
  std::thread ht([&] { haptic.run(t0); });
  if (opt.realtime_priority) {
    // Best effort: the haptic thread first in line for a core (SCHED_FIFO; needs root or
    // CAP_SYS_NICE). It sleeps most of each period, so it takes little from the others.
    sched_param sp{};
    sp.sched_priority = 20;
    res.haptic.realtime_priority = pthread_setschedparam(ht.native_handle(), SCHED_FIFO, &sp) == 0;
  }
  std::thread ct([&] { consumer.run(t0); });
  std::thread kt([&] { contact.run(); });
  // The simulation (this thread) ahead of ordinary work too, but without real-time priority: it
  // runs flat out when behind, and must not take a core from everything else. Restored after.
  const int tid = int(gettid());
  errno = 0;
  const int old_nice = getpriority(PRIO_PROCESS, id_t(tid));
  const bool reniced = opt.realtime_priority && errno == 0 && setpriority(PRIO_PROCESS, id_t(tid), -10) == 0;
  // The simulation runs on the calling thread: the State stays with its owner, and OpenMP's
  // parallel regions always start from the same thread.
  // Without a duration the run ends with the device, or at the longest run (limits.hpp); every run
  // ends before its recording of the steps outgrows limits::max_recorded_steps.
  const double end_s = opt.duration_s > 0 ? opt.duration_s : limits::max_realtime_s;
  sim.run(t0, [&](std::int64_t now) {
    return double(now - t0) * 1e-9 >= end_s || core.state().steps >= limits::max_recorded_steps ||
           shared.device_finished.load(std::memory_order_acquire) ||
           (opt.stop && opt.stop->load(std::memory_order_relaxed));
  });
  if (!shared.stop.load(std::memory_order_relaxed)) {
    // Diverged: let the watchdog bring the force down before stopping.
    haptics::sleep_until_ns(
        haptics::now_ns() + std::int64_t((opt.watchdog.sim_timeout_s + opt.watchdog.ramp_down_s + 0.01) * 1e9), 0);
    shared.stop.store(true, std::memory_order_relaxed);
  }
  ht.join();
  ct.join();
  kt.join();
  if (reniced) setpriority(PRIO_PROCESS, id_t(tid), old_nice);
  const double wall = double(haptics::now_ns() - t0) * 1e-9;

  const bool priority = res.haptic.realtime_priority;
  res.haptic = haptic.report();
  res.haptic.realtime_priority = priority;
  res.haptic.profile = opt.profile;
  res.haptic.contact_rebuilds = contact.rebuilds();
  res.haptic.contact_build_max_ms = contact.build_max_ms();
  res.sim = sim.report();
  res.consumer = consumer.report();
  res.device_name = device.name();
  res.device_json = device.report_json();
  res.recording.mode = force_mode_name(opt.mode);
  res.recording.haptic_rate_hz = opt.haptic_rate_hz;
  res.recording.force_scale = force_scale;
  res.recording.dispense_volume = increment_volume_or_default(scene, opt.dispense_volume);
  res.recording.backend = backend_name(opt.backend);
  res.recording.solver = solver_name(scene.model.solver);
  res.recording.material = scene.paste_preset;
  res.recording.material_temperature_c = scene.paste_temperature_c;
  res.recording.haptic_dropped = haptic.recording_dropped();
  res.recording.haptic = haptic.take_recording();
  res.recording.steps = std::move(sim.steps);
  res.recording.events = std::move(sim.events);
  res.haptic.free_air = free_air_force(res.recording);
  res.haptic.force_spectrum = force_spectrum(res.recording);

  RunSummary& sum = res.run;
  sum = core.summary();
  sum.force_scale = force_scale;
  if (scene.tooth) sum.assessment_json = report::session_assessment_json(scene, core.synced(), res.recording);
  sum.wall_time_s = wall;
  sum.steps_per_second = res.sim.steps_per_second;
  sum.realtime_json = realtime_json(res);
  if (!opt.out_dir.empty()) {
    std::filesystem::create_directories(opt.out_dir);
    save_recording(opt.out_dir / "recording", res.recording);
    report::end_run(opt.out_dir, scene, core.synced(), sum, report::log_of_recording(scene, res.recording));
  }
  return res;
}

}  // namespace dentsph
