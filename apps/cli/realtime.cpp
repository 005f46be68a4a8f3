#include "realtime.hpp"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <thread>

#include <fmt/format.h>

#include "dentsph/haptics/replay.hpp"
#include "dentsph/haptics/replay_outputs.hpp"
#include "dentsph/limits.hpp"
#include "dentsph/scene.hpp"
#include "option_checks.hpp"

namespace dentsph::cli {

namespace {
std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop.store(true); }
}  // namespace

void RealtimeCommand::add_options(CLI::App& run) {
  auto* rt = run.add_flag("--realtime", realtime_,
                          "Run the haptic runtime: a haptic loop, the simulation and a consumer on their own threads");
  add_device_options(run, rt);
}

void RealtimeCommand::add_device_options(CLI::App& run, CLI::Option* rt) {
  auto need = [rt](CLI::Option* o) {
    if (rt) o->needs(rt);
  };
  threads_option_ = run.get_option_no_throw("--threads");
  need(run.add_option("--device", device_, "Haptic device: scripted (the scene's keyframes), replay (a recording), udp (the network bridge)")
           ->check(CLI::IsMember({"scripted", "replay", "udp"}))
           ->capture_default_str());
  need(run.add_option("--replay", replay_dir_, "Recording folder for --device replay (OUT/recording of a realtime run)")
           ->check(CLI::ExistingDirectory));
  need(run.add_option("--mode", mode_, "Force rendering: coupling (virtual coupling) or direct (the paper's)")
           ->check(CLI::IsMember({"coupling", "direct"}))
           ->capture_default_str());
  need(run.add_option("--haptic-rate", haptic_rate_, "Haptic loop rate (Hz)")->check(finite_range(500.0, 4000.0))->capture_default_str());
  need(run.add_option("--force-scale", force_scale_, "Device N per simulated N (default: the scene's force_scale)")
           ->check(finite_range(1e-6, 1e9)));
  need(run.add_option("--profile", profile_, "Device force limits and contact stiffness: falcon (9 N, 3000 N/m), omega (12 N, 5000 N/m), touch (3.3 N, 1000 N/m), sigma7 (20 N, 0.4 N m torque)")
           ->check(CLI::IsMember({"falcon", "omega", "touch", "sigma7"}))
           ->capture_default_str());
  need(run.add_option("--port", udp_.port, "UDP port of the bridge (--device udp)")->capture_default_str());
  need(run.add_option("--address", udp_.address, "IPv4 address the bridge listens on (0.0.0.0: every interface)")->capture_default_str());
  need(run.add_option("--workspace-scale", workspace_scale_, "Scene m per device m")->check(finite_range(1e-4, 1e4))->capture_default_str());
  need(run.add_option("--workspace-origin", origin_, "Scene position of the device's origin (m; default: the tool's first keyframe)")
           ->expected(3)
           ->check(finite_range(-10, 10)));
  need(run.add_option("--stiffness", coupling_.stiffness_N_per_m, "Virtual coupling stiffness (N/m)")->check(finite_range(1, 1e7))->capture_default_str());
  need(run.add_option("--damping", coupling_.damping_N_s_per_m, "Virtual coupling damping (N s/m)")->check(finite_range(0, 1e4))->capture_default_str());
  need(run.add_option("--solve-deadline", solve_share_,
                      "Stop a step's solves once this share of dt has passed since it began (0 to 1; 0: no deadline). "
                      "Keeps a slow step from holding up the haptic loop, but a replay then differs where it cut a "
                      "solve short (summary.json's solver.on_deadline counts those steps)")
           ->check(finite_range(0, 1)));
  need(run.add_option("--sim-rate", sim_rate_, "Cap the simulation at this many steps per second (0: no cap)")->check(finite_range(0, 1e7)));
  need(run.add_flag("--free-run", free_run_, "Step as fast as possible (default: never ahead of the wall clock)"));
  need(run.add_option("--snapshot-rate", snapshot_rate_, "Consumer loop rate (Hz, 30 to 60)")->check(finite_range(30.0, 60.0))->capture_default_str());
}

RealtimeOptions RealtimeCommand::options(const Scene& scene, double duration_s, int threads, bool allow_unstable,
                                         const std::filesystem::path& out_dir) const {
  RealtimeOptions o;
  o.haptic_rate_hz = haptic_rate_;
  o.duration_s = duration_s;
  o.mode = force_mode_from_name(mode_);
  if (force_scale_ > 0) o.force_scale = force_scale_;
  o.profile = device_profile(profile_);
  o.coupling = coupling_;
  o.pace_realtime = !free_run_;
  o.sim_rate_limit_hz = sim_rate_;
  o.solve_share = solve_share_;
  o.snapshot_rate_hz = snapshot_rate_;
  // Without --threads the simulation may use every core: its thread governor (ThreadGovernor, the
  // Simulation's default) times the steps and falls back to fewer threads when the haptic loop, the
  // consumer or another program takes a core (one thread against two under the runtime, measured:
  // bench/results/realtime-solvers-amd-epyc-2core.txt).
  o.threads = threads_option_ && threads_option_->count() > 0 ? threads
                                                              : std::max(1, int(std::thread::hardware_concurrency()));
  o.allow_unstable = allow_unstable;
  o.out_dir = out_dir;
  o.workspace.scale = workspace_scale_;
  o.workspace.origin = origin_.size() == 3 ? Vec3{origin_[0], origin_[1], origin_[2]}
                       : scene.tool.keyframes.empty() ? Vec3{}
                                                      : scene.tool.keyframes.front().pose.position;
  return o;
}

std::unique_ptr<Device> RealtimeCommand::make_device(const Scene& scene, const RealtimeOptions& o, bool quiet) const {
  if (device_ == "scripted") return make_scripted_device(scene, o.workspace, o.duration_s);
  if (device_ == "replay") {
    if (replay_dir_.empty()) throw std::invalid_argument("--device replay needs --replay FOLDER (OUT/recording of a realtime run)");
    return make_replay_device(replay_dir_);
  }
  std::uint16_t port = 0;
  std::unique_ptr<Device> device = make_udp_device(udp_, &port);
  if (o.duration_s <= 0 && !quiet) fmt::print("no --duration: runs until Ctrl-C\n");
  fmt::print("listening for a haptic client on udp {}:{} (dentsph-haptic-client --port {})\n", udp_.address, port, port);
  return device;
}

int RealtimeCommand::run(const Scene& scene, const RunOptions& offline, bool quiet) {
  if (offline.steps > 0) throw std::invalid_argument("--steps does not apply to --realtime: give --duration SECONDS of wall time");
  if (double(offline.duration) > limits::max_realtime_s)
    throw std::invalid_argument(fmt::format("--duration {}: a realtime run lasts at most {:.0f} s of wall time; give a "
                                            "shorter --duration (or leave it out: the run then ends at {:.0f} s)",
                                            offline.duration, limits::max_realtime_s, limits::max_realtime_s));
  RealtimeOptions o = options(scene, double(offline.duration), offline.threads, offline.allow_unstable, offline.out_dir);
  o.backend = offline.backend;
  o.stop = &g_stop;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  if (!quiet) {
    // Where the device is in the scene (docs/haptic-protocol.md, "Frames and units").
    const Vec3& at = o.workspace.origin;
    fmt::print("device     origin at ({:.4g}, {:.4g}, {:.4g}) m in the scene, {:.4g} scene m per device m, axes the "
               "scene's",
               at.x, at.y, at.z, o.workspace.scale);
    if (scene.tooth) {
      const Vec3 in = -scene.tooth->frame().z + Vec3{0, 0, 0};  // no "-0.000"
      fmt::print("; into the cavity: ({:.3f}, {:.3f}, {:.3f})", in.x, in.y, in.z);
    }
    fmt::print("\n");
  }
  const std::unique_ptr<Device> device = make_device(scene, o, quiet);
  std::fflush(stdout);
  const RealtimeResult r = run_realtime(scene, *device, o);
  fmt::print("\n{}", realtime_report(r));
  fmt::print("{} steps ({:.4g} s simulated) in {:.2f} s; peak tool force {:.4g} N simulated, {:.4g} N at force scale "
             "{:.4g}; the device was sent at most {:.4g} N\n",
             r.run.steps, r.run.sim_time_s, r.run.wall_time_s, r.run.peak_tool_force_N,
             r.run.peak_tool_force_N * r.run.force_scale, r.run.force_scale, r.haptic.max_force_N);
  if (!r.haptic.realtime_priority && !quiet)
    fmt::print("note: the haptic thread runs without real-time priority (SCHED_FIFO needs root or CAP_SYS_NICE)\n");
  if (!o.out_dir.empty())
    fmt::print("wrote {}: summary.json (haptic, sim, consumer, device), recording/ (haptic.csv, steps.csv, events.csv)\n",
               o.out_dir.string());
  if (r.run.status != "completed") {
    fmt::print(stderr, "error: the simulation diverged: {}\n", r.run.message);
    return 3;
  }
  return 0;
}

int replay_recording(Scene scene, const std::string& dir, int threads, Backend backend,
                     const std::filesystem::path& out_dir, const std::string& solver) {
  const Recording r = load_recording(dir);
  if (const std::string notice = choose_solver(scene, solver.empty() ? r.solver : solver, backend != Backend::cpu);
      !notice.empty())
    fmt::print("{}\n", notice);
  const std::vector<Vec3> f = out_dir.empty() ? replay_steps(scene, r, threads, backend)
                                              : replay_to_folder(scene, r, threads, out_dir, backend);
  const ReplayComparison c = compare_replay(f, r, kBackendParityTolerance);
  const bool exact = r.backend == backend_name(backend);
  fmt::print("replayed {} steps and {} events of {} on {} (recorded on {}): {} tool forces differ from the recording "
             "(largest difference {:.3g} N; recorded peak {:.4g} N)\n",
             f.size(), r.events.size(), dir, backend_name(backend), r.backend, c.differ, c.largest, c.peak);
  if (!out_dir.empty()) fmt::print("wrote {}: summary.json, tool_force.csv, report.html\n", out_dir.string());
  if (exact) return c.differ == 0 ? 0 : 4;
  fmt::print("another backend than the recording's: {} forces outside the parity tolerance ({:g} of the recorded peak, "
             "or of {:g} N if larger)\n",
             c.outside, kBackendParityTolerance, kBackendParityForceFloor);
  return c.outside == 0 ? 0 : 4;
}

}  // namespace dentsph::cli
