// The simulation behind the viewer, on a thread of its own: either its own loop around a
// Simulation (simulation.hpp), driven by the mouse as a stand-in device (tool target, press), or
// the haptic runtime with a real device (use_device: the runtime's simulation loop calls back
// between steps with its Simulation). Either way the steps run on the session's backend. Either way it takes
// commands (dispense, switch tool, paste edits, reset; pause and single step in its own loop)
// and publishes snapshots for the render loop, which never touches the State. Commands may be
// scheduled for an exact step, so a scripted session runs the same simulation however fast the
// frames come.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "dentsph/assess.hpp"
#include "dentsph/contact.hpp"
#include "dentsph/haptics.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/step.hpp"

namespace dentsph::viewer {

// Paste parameters a user may change while the simulation runs (docs/model.md's names).
struct MaterialEdit {
  real Kp = 0, Ka = 0, mu = 0;          // paste: m^2/s^2, Pa, Pa s (a non-Newtonian paste's consistency, Pa s^n)
  real A = 0, B = 0, eps = 0, zeta = 0;  // adhesion kernel: m, m, -, -
  real flow_index = 1, yield_stress = 0;  // the paste's rheology, shown, not edited (an edit keeps them)
};

struct Command {
  enum class Kind {
    pause, resume, single_step, reset, dispense, switch_tool, set_material, tool_target, press, light, load_preset
  };
  Command() = default;
  Command(Kind k) : kind(k) {}  // NOLINT(google-explicit-constructor): {Kind::dispense} reads well
  Kind kind = Kind::pause;
  std::string tool;          // switch_tool: instrument name
  MaterialEdit material;     // set_material
  std::string preset;        // load_preset: a paste preset's name (paste_presets.hpp); empty: the scene's own paste
  double temperature_c = 23;  // load_preset: the preset's temperature, C
  Vec3 target;               // tool_target: tool tip position, m, world
  bool pressed = false;      // press: held down or released; light: on (over the cavity) or off
};

// What one frame shows. Arrays in particle order of the moment, [n] each.
struct Snapshot {
  std::uint64_t version = 0;  // increases with every publication
  real time = 0;              // s, simulated
  std::uint64_t steps = 0;
  std::vector<float> xyz;     // [3n] m
  std::vector<Role> role;     // [n]
  std::vector<float> pressure, density, speed, bonds;  // [n] Pa, kg/m^3, m/s, count
  std::vector<float> conversion;  // [n] the paste's degree of conversion (0 elsewhere and before any light)
  real conversion_max = 0.6;      // the cured paste's largest conversion (the colour map's top)
  std::optional<CuringLight> light;  // the curing light while it is on (set paste is drawn as paste)
  Pose tool_pose;
  Vec3 device_force_N;        // device N: the simulated tool force times the force scale
  real force_scale = 1;       // device N per simulated N
  std::optional<Assessment> assessment;
  StabilityLimits limits;
  real dt = 0;
  MaterialEdit material;      // the parameters in effect
  std::string preset;         // the paste preset the scene is filled with; empty: the scene's own paste
  double preset_temperature_c = 23;
  std::string tool_name;
  std::string message;        // the last command's complaint (an invalid edit), empty if none
  bool paused = false;
  bool diverged = false;
  double steps_per_second = 0;  // wall-clock rate of the simulation loop
  std::string backend;          // where it steps: cpu, cuda or cuda-emulation
  // With a device (the haptic runtime): the haptic loop's live figures.
  struct Haptic {
    std::string device;
    double rate_hz = 0, period_last_us = 0, period_max_recent_us = 0;
    std::uint64_t ticks = 0, deadline_misses = 0;
    Vec3 force_N;                    // sent to the device
    double pose_age_ms = -1, sim_age_ms = -1, gain = 0;
    std::uint32_t status = 0;
  };
  std::optional<Haptic> haptic;
};

struct SessionOptions {
  int threads = 1;                  // threads of the step
  Backend backend = Backend::cpu;   // where the step runs (a GPU keeps the particles, downloaded per snapshot)
  real tool_speed = 0.02;           // m/s, fastest the tool follows its target (of simulated time)
  real press_depth_spacings = 2.5;  // a held press moves the tool this many spacings down the tooth axis
  real dispense_volume = 0;         // m^3 of an increment; 0: a sixth of the cavity (or 200 particles)
  double snapshot_hz = 60;          // publications per second of wall time
  double assess_hz = 5;             // assessments per second of wall time (dental scenes)
  bool start_paused = false;
  // The scene again, filled with a paste preset at a temperature (an empty name: the scene's own
  // paste): what load_preset loads. None: the viewer's scene has no presets (a scene file).
  std::function<Scene(const std::string& preset, double temperature_c)> rebuild = {};
};

class SimSession {
 public:
  SimSession(Scene scene, SessionOptions options);
  ~SimSession();
  SimSession(const SimSession&) = delete;
  SimSession& operator=(const SimSession&) = delete;

  // Runs the haptic runtime with `device` instead of the session's own loop (before start()), on
  // the session's backend. The device drives the tool; pause, reset and paste edits are refused
  // then.
  void use_device(std::unique_ptr<Device> device, RealtimeOptions options);
  // Starts the session's thread: the session's own loop kFreeRunningNice above the viewer's nice
  // value (Linux's nice values are a thread's), or the haptic runtime at the viewer's own.
  void start();
  void stop();  // joins the thread; idempotent
  // How much nicer the session's own loop is than the frames: on two cores it yields to the frames and the
  // surface worker (docs/viewer.md, "The surface keeps pace with the frames"), which stepping as fast as it can would
  // otherwise starve.
  static constexpr int kFreeRunningNice = 5;
  // The runtime's result once stopped (use_device sessions).
  const std::optional<RealtimeResult>& realtime_result() const { return realtime_result_; }
  // The session's own loop (no device): the simulated time and tool force after each step since the
  // last reset, for the report's force plot; read once stopped.
  struct ForceSample {
    real t = 0;        // s, simulated, at the start of the step
    ToolWrench wrench;
  };
  const std::vector<ForceSample>& force_log() const { return force_log_; }

  // Applies `c` before the next step.
  void post(const Command& c);
  // Applies `c` before step `step` (0-based count of steps taken); a step already passed applies
  // it before the next one.
  void post_at(std::uint64_t step, const Command& c);
  // Copies the newest snapshot into `out` when it is newer than out.version; true if copied.
  bool latest(Snapshot& out) const;
  std::uint64_t steps() const { return steps_.load(std::memory_order_acquire); }
  // True once every scheduled command has been applied.
  bool schedule_done() const;

  const Scene& scene() const { return scene_; }
  const SessionOptions& options() const { return opt_; }
  std::vector<std::string> tools() const;  // instruments that switch_tool accepts

 private:
  void run();
  void run_device();
  // The runtime's hook (device mode): applies the commands due to its Simulation, recording the
  // dispenses and tool switches for the replay, and publishes.
  void between_steps(Simulation& sim, std::vector<EventSample>& recorded);
  // Moves the commands due at `steps` off the queues into due_ (under the lock).
  void take_due(std::uint64_t steps);
  // Applies `c` to `sim`; with `recorded` (device mode), appends what a replay must repeat.
  void apply(const Command& c, Simulation& sim, std::vector<EventSample>* recorded = nullptr);
  void set_material(const MaterialEdit& m, Simulation& sim);
  void load_preset(const std::string& preset, double temperature_c);  // the scene rebuilt with it, reset
  void publish(Simulation& sim, bool with_assessment, double steps_per_second);
  void reset();  // the session's own Simulation from the scene again, with the paste as edited
  Vec3 tool_tip_goal() const;
  // The mouse's tool held out of the tooth, the band and set paste (contact.hpp): the field
  // follows the paste as it sets (checked every kContactCheckSteps steps), the shape the tool.
  Vec3 held_by_contact(const Pose& pose);

  Scene scene_;
  SessionOptions opt_;
  std::unique_ptr<Simulation> sim_;  // the session's own loop's (and the first snapshot's)
  std::optional<CavityAssessor> assessor_;
  real force_scale_ = 1;  // device N per simulated N: the scene's, or the runtime's override
  Material paste_;
  AdhesionParams adhesion_;  // the edit's kernel (set_material), made again after a reset
  bool paste_edited_ = false;
  std::string tool_name_ = "ball_burnisher";
  std::string message_;
  Vec3 target_;  // tool tip target, m
  Vec3 press_axis_;
  bool pressed_ = false;
  bool paused_ = false, single_ = false, diverged_ = false;

  mutable std::mutex mutex_;  // guards the command queues and the published snapshot
  std::vector<Command> queue_, due_;  // posted; taken for this step
  Snapshot back_;                      // the next publication, filled outside the lock
  std::multimap<std::uint64_t, Command> scheduled_;
  Snapshot published_;
  std::condition_variable wake_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> steps_{0};
  std::thread thread_;
  // Device mode.
  std::unique_ptr<Device> device_;
  RealtimeOptions rt_options_;
  HapticLive live_;
  std::atomic<bool> rt_stop_{false};
  std::optional<RealtimeResult> realtime_result_;
  std::vector<ForceSample> force_log_;
  ContactField contact_field_;
  RigidWatch contact_rigid_;  // what contact_field_ and contact_shape_ were built from
  ContactShape contact_shape_;
  HardContact contact_;
  bool contact_stale_ = true;  // to be checked at once (a reset)
  static constexpr std::uint64_t kContactCheckSteps = 20;
  std::string run_error_;
  std::uint64_t live_ticks0_ = 0;
  std::chrono::steady_clock::time_point live_t0_, last_publish_, last_assess_, rate_t0_;
  double last_rate_hz_ = 0, sim_rate_ = 0;
  std::uint64_t rate_steps0_ = 0;
};

}  // namespace dentsph::viewer
