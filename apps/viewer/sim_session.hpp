// The simulation behind the viewer: a scene stepped on its own thread, driven by commands (tool
// target, dispense, pause, single step, reset, switch tool, material edits) and publishing
// snapshots for the render loop. The render loop never touches the State: it reads snapshots,
// the simulation thread alone owns the State. Commands may be scheduled for an exact step, so a
// scripted session runs the same simulation however fast the frames come.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "dentsph/assess.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/step.hpp"

namespace dentsph::viewer {

// Paste parameters a user may change while the simulation runs (MODEL.md's names).
struct MaterialEdit {
  real Kp = 0, Ka = 0, mu = 0;          // paste: m^2/s^2, Pa, Pa s
  real A = 0, B = 0, eps = 0, zeta = 0;  // adhesion kernel: m, m, -, -
};

struct Command {
  enum class Kind { pause, resume, single_step, reset, dispense, switch_tool, set_material, tool_target, press };
  Command() = default;
  Command(Kind k) : kind(k) {}  // NOLINT(google-explicit-constructor): {Kind::dispense} reads well
  Kind kind = Kind::pause;
  std::string tool;          // switch_tool: instrument name
  MaterialEdit material;     // set_material
  Vec3 target;               // tool_target: tool tip position, m, world
  bool pressed = false;      // press: held down or released
};

// What one frame shows. Arrays in particle order of the moment, [n] each.
struct Snapshot {
  std::uint64_t version = 0;  // increases with every publication
  real time = 0;              // s, simulated
  std::uint64_t steps = 0;
  std::vector<float> xyz;     // [3n] m
  std::vector<Role> role;     // [n]
  std::vector<float> pressure, density, speed, bonds;  // [n] Pa, kg/m^3, m/s, count
  Pose tool_pose;
  Vec3 tool_force_N;          // rendered force: simulated force times the scene's force scale
  std::optional<Assessment> assessment;
  StabilityLimits limits;
  real dt = 0;
  MaterialEdit material;      // the parameters in effect
  std::string tool_name;
  std::string message;        // the last command's complaint (an invalid edit), empty if none
  bool paused = false;
  bool diverged = false;
  double steps_per_second = 0;  // wall-clock rate of the simulation loop
};

struct SessionOptions {
  int threads = 1;                  // threads of the step
  real tool_speed = 0.02;           // m/s, fastest the tool follows its target (of simulated time)
  real press_depth_spacings = 2.5;  // a held press moves the tool this many spacings down the tooth axis
  real dispense_volume = 0;         // m^3 of an increment; 0: a sixth of the cavity (or 200 particles)
  double snapshot_hz = 60;          // publications per second of wall time
  double assess_hz = 5;             // assessments per second of wall time (dental scenes)
  bool start_paused = false;
};

class SimSession {
 public:
  SimSession(Scene scene, SessionOptions options);
  ~SimSession();
  SimSession(const SimSession&) = delete;
  SimSession& operator=(const SimSession&) = delete;

  void start();
  void stop();  // joins the thread; idempotent

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
  void apply(const Command& c);
  void publish(bool with_assessment, double steps_per_second);
  void reset_state();
  void apply_paste();  // paste_ onto every material particle
  Vec3 tool_tip_goal() const;

  Scene scene_;
  SessionOptions opt_;
  State state_;
  std::optional<CavityAssessor> assessor_;
  ForceStats forces_;
  real paste_mass_ = 0;
  real sound_speed_ = 0;  // m/s, sqrt(max Kp): material far faster than this has exploded
  Material paste_, tool_material_;
  std::string tool_name_ = "ball_burnisher";
  std::string message_;
  Vec3 target_;  // tool tip target, m
  Vec3 press_axis_;
  bool pressed_ = false;
  bool paused_ = false, single_ = false, diverged_ = false;

  mutable std::mutex mutex_;  // guards the command queues and the published snapshot
  std::deque<Command> queue_;
  std::multimap<std::uint64_t, Command> scheduled_;
  Snapshot published_;
  std::condition_variable wake_;
  std::atomic<bool> running_{false};
  std::atomic<std::uint64_t> steps_{0};
  std::thread thread_;
};

}  // namespace dentsph::viewer
