// The haptic runtime (docs/haptics.md): three loops on their own threads.
//  - the haptic loop, at a fixed rate (default 1 kHz, 500 Hz to 4 kHz), reads the device pose and
//    writes the device force; it never blocks, allocates, locks, logs or touches the State;
//  - the simulation loop owns the State: it takes the newest tool pose, steps, and publishes the
//    newest tool force (paced to real time or as fast as it can);
//  - the consumer loop takes particle snapshots at 30 to 60 Hz (recording, rendering).
// Data passes between them through lock-free triple buffers. The force a device receives is
// finite, within the device profile's magnitude and rate limits, and ramps to zero when the
// simulation stalls or the device goes quiet.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dentsph/haptics/device.hpp"
#include "dentsph/haptics/recording.hpp"
#include "dentsph/run.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/simulation.hpp"

namespace dentsph {

enum class ForceMode {
  direct,    // the paper's: the tool moves with the device, the tool force is rendered
  coupling,  // virtual coupling: the tool is a proxy tied to the device by a spring and damper;
             // the coupling force is rendered and drives the proxy
};
const char* force_mode_name(ForceMode m);
ForceMode force_mode_from_name(const std::string& name);  // throws std::invalid_argument

// Virtual coupling, in the device frame. The proxy (mass m) feels the spring-damper to the
// device and the scaled tool force of the simulation, and a little drag; it is integrated
// implicitly on the haptic thread at the haptic rate (stable for any stiffness).
struct CouplingParams {
  double stiffness_N_per_m = 400;
  double damping_N_s_per_m = 2;      // relative velocity of proxy and device
  double proxy_mass_kg = 0.05;
  double proxy_drag_N_s_per_m = 2;   // proxy against the world while the tool touches (dissipates energy)
  // Set by the runtime, not a user's setting: the proxy's largest speed (device m/s; 0: none), the
  // velocity CFL limit of the step (cfl h / dt, in the device's frame). The proxy is the simulated
  // tool: a tool that moves more than cfl h in one step outruns the solver (at the iisph solver's
  // 1 ms a contact pushed the proxy 7 mm in two steps and the paste exploded). Slowing the proxy
  // only takes energy out.
  double max_speed_m_per_s = 0;
};

struct WatchdogParams {
  double sim_timeout_s = 0.025;   // the newest simulation output older than this: fault
  double pose_timeout_s = 0.02;   // no new device pose for this long: fault
  double ramp_down_s = 0.01;      // force gain 1 -> 0 after a fault
  double ramp_up_s = 0.1;         // force gain 0 -> 1 after recovery
};

// Faults injected for tests and demonstrations.
struct FaultInjection {
  double sim_stall_at_s = -1;  // the simulation thread sleeps at this wall time (s since start)
  double sim_stall_s = 0;      // for this long
};

// Live figures of the haptic loop, kept current by it every tick with relaxed atomic stores (no
// lock, no allocation) for a viewer to show while the runtime runs.
struct HapticLive {
  std::atomic<std::uint64_t> ticks{0};
  std::atomic<std::uint64_t> deadline_misses{0};
  std::atomic<double> period_last_us{0};
  std::atomic<double> period_max_recent_us{0};  // largest period of the last half second
  std::atomic<double> force_x{0}, force_y{0}, force_z{0};  // N, sent to the device
  std::atomic<double> pose_age_ms{-1};  // -1: no pose received yet
  std::atomic<double> sim_age_ms{-1};   // -1: no simulation output yet
  std::atomic<double> gain{0};          // the watchdog's gain in [0, 1]
  std::atomic<std::uint32_t> status{0}; // haptic_protocol::ForceStatus bits of the last tick
};

struct RealtimeOptions {
  double haptic_rate_hz = 1000;       // 500 .. 4000
  double duration_s = 0;              // wall seconds; 0: until the device finishes (or stop is set)
  ForceMode mode = ForceMode::coupling;
  std::optional<double> force_scale;  // device N per simulated N; default: Scene::force_scale
  DeviceProfile profile;              // force limits
  CouplingParams coupling;
  WatchdogParams watchdog;
  WorkspaceMap workspace;             // device -> scene
  bool pace_realtime = true;          // the simulation never runs ahead of the wall clock
  double sim_rate_limit_hz = 0;       // > 0: at most this many steps per second
  double snapshot_rate_hz = 30;       // 30 .. 60; 0: no consumer loop
  int threads = 1;                    // threads of the simulation step
  // A step's solves stop once this share of dt has passed since the step began (after their least
  // iterations; SimulationOptions::solve_budget_s), so that a slow step keeps the loop paced; the
  // summary counts such steps (solver.on_deadline). In [0, 1], 0 for none (the default: a step cut
  // short depends on the machine's load, so a replay of the session differs from there on); only
  // while pace_realtime (`run --realtime --solve-deadline`).
  double solve_share = 0;
  Backend backend = Backend::cpu;     // where the simulation steps (a GPU: the particles stay there,
                                      // downloaded at the snapshot rate)
  bool realtime_priority = true;      // ask for SCHED_FIFO for the haptic thread and nice -10 for the
                                      // simulation (best effort)
  bool allow_unstable = false;
  double record_capacity_s = 120;     // haptic-rate recording preallocated for this long (176 B a tick)
  std::filesystem::path out_dir;      // summary.json and the recording (empty: nothing written)
  FaultInjection faults;
  // m^3 of the increment the device's button 1 dispenses (dispense_increment, on each press);
  // 0: as the viewer, a sixth of the cavity (or 200 particles without a tooth).
  double dispense_volume = 0;
  const std::atomic<bool>* stop = nullptr;  // set by the caller (a signal) to end the run
  // Called on the consumer thread with each snapshot's particle positions (scene frame) and sim
  // time; for rendering and tests.
  std::function<void(std::span<const Vec3> positions, double sim_time)> on_snapshot;
  // When set, the haptic loop keeps it current (a viewer's live panel).
  HapticLive* live = nullptr;
  // The hard contact's field when the caller has made it (the viewer, for its mouse): built from
  // the scene otherwise (scene_contact_field: the whole tooth's distance, 0.3 to 0.6 s).
  std::shared_ptr<const ContactField> contact_field;
  // Called on the simulation thread before every step, after the procedure's events, never on the
  // haptic thread: a viewer applies its edits (dispense, switch tool) through the Simulation and
  // takes its snapshots here (Simulation::synced). It must not take long. It appends to `recorded`
  // what a replay must repeat (RealtimeResult::recording's events, at state().steps): an increment
  // dispensed (kButtonIncrement, Simulation::dispense of the session's dispense_volume), a tool
  // switched (tool_switch_event).
  std::function<void(Simulation& sim, std::vector<EventSample>& recorded)> between_steps;
};

// Rate and period jitter of a loop.
struct LoopTiming {
  std::uint64_t ticks = 0;
  double rate_hz = 0;
  double period_p50_us = 0, period_p99_us = 0, period_max_us = 0;
  std::uint64_t deadline_misses = 0;  // ticks that started more than half a period late
};

// The force the device rendered while the instrument touched nothing: the ticks at which no
// step of the last `window_s` of wall time had a force on the tool (without material within reach
// the tool's force is exactly zero) and the hard contact did not touch (HapticSample::contact_force
// zero: the tooth and set paste put no force on the simulated tool), against the ticks in contact. What a student feels in air is
// the coupling's lag behind the hand, not the material.
struct FreeAirForce {
  double window_s = 0.02;
  std::uint64_t free_ticks = 0, contact_ticks = 0;
  double free_mean_N = 0, free_p95_N = 0;        // |force sent to the device| over the free ticks
  double contact_mean_N = 0, contact_p95_N = 0;  // the same in contact
};
// From a recording (its ticks and steps, both on the runtime's wall clock). Ticks before the first
// step, or with no step in their window, count as neither.
FreeAirForce free_air_force(const Recording& recording, double window_s = 0.02);

// The spectrum of the force rendered to the device (HapticSample::force, the three axes), above a
// cutoff: how much of what the hand feels is vibration rather than the material's slow push.
// The ticks' force is held from one tick to the next (as the device holds it) and read at the
// middle of each period of the nominal haptic rate (Recording::haptic_rate_hz; when 0, the median
// tick period), so a late or skipped tick counts as the force held the longer, and jitter under
// half a period changes nothing. The power spectrum is Welch's: Hann-windowed segments of
// `segment_s` (or the whole recording when shorter), overlapping by half, each segment's mean
// removed, power per axis summed (FFTW). Recordings shorter than 64 ticks, or whose rate puts the
// cutoff at or above the Nyquist frequency, are not analysed: ticks = 0 and every figure 0.
struct ForceBand {
  double lo_hz = 0, hi_hz = 0;  // [lo, hi); the last band ends at the Nyquist frequency, included
  double rms_N = 0;             // RMS of the force (three axes together) in the band
};
struct ForceSpectrum {
  double cutoff_hz = 100;
  double rate_hz = 0;            // the rate the force was read at (the nominal haptic rate)
  std::uint64_t ticks = 0;       // samples analysed (0: not analysed)
  double segment_s = 0;          // the Welch segment's length (the frequency resolution is 1 / segment_s)
  std::uint64_t segments = 0;
  double fluctuation_rms_N = 0;  // RMS of the force minus its mean over the whole recording, three axes together
  double above_rms_N = 0;        // RMS of the force at and above cutoff_hz, three axes together
  double above_share = 0;        // above_rms_N / fluctuation_rms_N (a ratio of RMS; 0 without fluctuation)
  double peak_hz = 0;            // the strongest frequency at or above the cutoff (0: no power there)
  double peak_amplitude_N = 0;   // the amplitude of a sine carrying the power around the peak (+-2 bins)
  std::vector<ForceBand> bands;  // band_hz wide from cutoff_hz up to the Nyquist frequency
  std::size_t top_band = 0;      // index of the band with the most power (bands empty: 0)
};
ForceSpectrum force_spectrum(const Recording& recording, double cutoff_hz = 100, double band_hz = 100,
                             double segment_s = 0.5);

struct HapticReport {
  double target_rate_hz = 0;
  DeviceProfile profile;                  // the force limits the loop kept to
  bool realtime_priority = false;         // the haptic thread got SCHED_FIFO
  LoopTiming timing;
  double force_age_p50_us = 0, force_age_p99_us = 0, force_age_max_us = 0;  // now - stamp of the pose the
                                                                            // simulation output answered
  double max_force_N = 0;                 // largest force sent to the device
  double max_force_step_N = 0;            // largest change between consecutive ticks
  std::uint64_t magnitude_limited_ticks = 0, rate_limited_ticks = 0, non_finite_rejected = 0;
  std::uint64_t non_finite_poses = 0;     // device poses refused (the previous pose is kept)
  // Ticks whose force the passivity control damped (the device had given the hand more energy than
  // it took: haptics/passivity_control.hpp), and the energy the forces did on the hand at the end (J;
  // below zero: the hand's work taken in).
  std::uint64_t passivity_damped_ticks = 0;
  double passivity_energy_J = 0;
  std::uint64_t sessions = 0;             // device sessions started (DeviceSample::session)
  std::uint64_t contact_ticks = 0;        // ticks the instrument touched the tooth, band or set paste
  std::uint64_t contact_rebuilds = 0;     // the contact field rebuilt (paste set, instrument switched)
  double contact_build_max_ms = 0;        // the longest rebuild (off the haptic thread)
  std::uint64_t dispense_presses = 0;     // presses of button 1 counted (handed to the simulation)
  std::uint64_t dispense_presses_refused = 0;  // presses over limits::max_dispense_presses_per_s
  std::uint64_t light_presses = 0;        // presses of button 2 counted (the curing light toggled)
  std::uint64_t light_presses_refused = 0;  // presses over limits::max_light_presses_per_s
  std::uint64_t watchdog_trips = 0;       // healthy -> fault transitions
  std::uint64_t sim_stale_ticks = 0, pose_stale_ticks = 0, zero_gain_ticks = 0;
  FreeAirForce free_air;                  // from the recording, after the run
  ForceSpectrum force_spectrum;           // from the recording, after the run
};

struct SimReport {
  std::uint64_t steps = 0;
  double steps_per_second = 0;
  double realtime_factor = 0;  // simulated s per wall s
  double step_p50_us = 0, step_p99_us = 0, step_max_us = 0;
  std::uint64_t stalls_injected = 0;
  std::uint64_t button_dispenses = 0;  // increments dispensed by the device's button 1
  std::uint64_t light_toggles = 0;     // the curing light turned on or off by the device's button 2
};

struct ConsumerReport {
  std::uint64_t frames = 0;
  double rate_hz = 0;
  double snapshot_age_p99_us = 0;  // from publication by the simulation to the consumer taking it
};

struct RealtimeResult {
  RunSummary run;                 // the shared summary (scene, steps, particles, bonds, tool, ...)
  HapticReport haptic;
  SimReport sim;
  ConsumerReport consumer;
  std::string device_name;
  std::string device_json;        // the device's own counters
  Recording recording;            // device pose and rendered force per tick, tool pose per step
};

// Runs `scene` with `device` until the device finishes, duration_s passes or *stop is set.
// Throws UnstableTimeStep (like run_offline) and std::invalid_argument for bad options.
RealtimeResult run_realtime(const Scene& scene, Device& device, const RealtimeOptions& options);
// What run_realtime checks before it starts: throws std::invalid_argument naming the option and
// its range when one of `options`, with the run's force scale (device N per simulated N), is out
// of it (a NaN included).
void check_realtime_options(const RealtimeOptions& options, double force_scale);

// The realtime sections of summary.json ("haptic", "sim", "consumer", "device") as a JSON object.
std::string realtime_json(const RealtimeResult& r);
// The same for a person.
std::string realtime_report(const RealtimeResult& r);

}  // namespace dentsph
