// The viewer's parts that need no window: colour maps, the camera's mouse mapping, input
// scripts, and the simulation session's commands (exact steps, edits, refusals).
#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <thread>

#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include "camera.hpp"
#include "colour_map.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/scene.hpp"
#include "input_script.hpp"
#include "paste_surface_view.hpp"
#include "sim_session.hpp"
#include "surface_worker.hpp"
#include "support/small_scene.hpp"

namespace dentsph::viewer {
namespace {

std::string error_of(const std::string& json) {
  try {
    parse_input_script(json, "inputs.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// The surface view builds the paste's surface again only where the paste has moved since the last
// build: a particle farther than the tolerance (a tenth of a voxel in the view), or paste added or
// gone; paste at rest, whose snapshots differ by less, is not built again frame after frame.
TEST(PasteSurfaceView, ThePasteIsBuiltAgainOnlyWhereItMoved) {
  const real tolerance = 1e-5;
  const std::vector<Vec3> built{{0, 0, 0}, {1e-3, 0, 0}, {2e-3, 0, 0}};
  std::vector<Vec3> now = built;
  EXPECT_FALSE(paste_moved(now, built, tolerance)) << "the same paste";
  now[1].z += 0.9 * tolerance;
  EXPECT_FALSE(paste_moved(now, built, tolerance)) << "a particle crept under the tolerance";
  now[1].z += 0.2 * tolerance;
  EXPECT_TRUE(paste_moved(now, built, tolerance)) << "one particle over it";
  now = built;
  now.push_back({3e-3, 0, 0});
  EXPECT_TRUE(paste_moved(now, built, tolerance)) << "paste added";
  now.pop_back();
  now.pop_back();
  EXPECT_TRUE(paste_moved(now, built, tolerance)) << "paste gone";
  now = built;
  now[0].x = NAN;
  EXPECT_TRUE(paste_moved(now, built, tolerance)) << "a position that is not finite";
  std::swap(now[0], now[2]);
  now[2] = built[0];
  EXPECT_TRUE(paste_moved(now, built, tolerance)) << "the same particles in another order";
}

// The frames keep pace with the surface (PasteSurfaceView::update): a frame waits for the surface
// of the paste the frame before submitted. The worker says when that surface, or a newer one, is
// finished, and not before; a paste replaced before its build started stands for the older one.
TEST(SurfaceWorker, AFrameWaitsForTheSurfaceOfThePasteItIsDue) {
  const real s = 1e-4;
  std::vector<Vec3> block, moved;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) block.push_back(Vec3{real(i), real(j), real(k)} * s);
  for (const Vec3& p : block) moved.push_back(p + Vec3{10 * s, 0, 0});
  SurfaceWorker worker(s);
  EXPECT_FALSE(worker.wait_for(1, std::chrono::milliseconds(20))) << "nothing submitted: nothing finished";
  const std::uint64_t first = worker.submit(block), second = worker.submit(moved);
  EXPECT_EQ(second, first + 1);
  ASSERT_TRUE(worker.wait_for(second, std::chrono::seconds(30)));
  EXPECT_TRUE(worker.wait_for(first, std::chrono::milliseconds(0))) << "a newer surface stands for the older paste";
  SurfaceMesh mesh;
  ASSERT_TRUE(worker.take(mesh, second));
  ASSERT_FALSE(mesh.empty());
  real lowest_x = 1;
  for (const Vec3& v : mesh.vertices) lowest_x = std::min(lowest_x, v.x);
  EXPECT_GT(lowest_x, 9 * s) << "the newest paste's surface, the block moved by 10 spacings";
  EXPECT_FALSE(worker.wait_for(second + 1, std::chrono::milliseconds(20))) << "the next paste is not submitted";
  EXPECT_GE(worker.built(), 1u);
  EXPECT_LE(worker.built(), 2u);
}

TEST(ColourMap, EndsClampsAndFlagsNaN) {
  const Rgb lo = colour_map(0), hi = colour_map(1);
  EXPECT_LT(lo[1], 0.1f);  // dark purple
  EXPECT_GT(hi[0], 0.9f);  // yellow
  EXPECT_GT(hi[1], 0.8f);
  EXPECT_EQ(colour_map(-3), lo);
  EXPECT_EQ(colour_map(7), hi);
  EXPECT_EQ(colour_map(NAN), (Rgb{1, 0, 1}));
  // Brighter along the map (green channel rises monotonically in viridis).
  float prev = -1;
  for (int k = 0; k <= 20; ++k) {
    const float gch = colour_map(float(k) / 20)[1];
    EXPECT_GT(gch, prev);
    prev = gch;
  }
}

TEST(ColourMap, AutoRangeUsesMaterialPercentiles) {
  std::vector<float> v;
  std::vector<Role> r;
  for (int i = 0; i <= 100; ++i) {
    v.push_back(float(i));
    r.push_back(Role::material);
  }
  v.push_back(1e6f);  // a wall particle's huge value does not set the scale
  r.push_back(Role::boundary);
  const Range range = auto_range(v, r);
  EXPECT_NEAR(range.lo, 2, 1e-6);
  EXPECT_NEAR(range.hi, 98, 1e-6);
  const Range flat = auto_range(std::vector<float>{5, 5}, std::vector<Role>{Role::material, Role::material});
  EXPECT_LT(flat.lo, 5);
  EXPECT_GT(flat.hi, 5);
  std::vector<float> rgb;
  particle_colours(ColourBy::speed, v, r, range, rgb);
  ASSERT_EQ(rgb.size(), 3 * v.size());
  EXPECT_EQ((Rgb{rgb[0], rgb[1], rgb[2]}), colour_map(0));  // material by the field
  EXPECT_GT(rgb[3 * 101], 0.8f);                             // the wall muted towards white
  particle_colours(ColourBy::role, v, r, range, rgb);
  EXPECT_EQ((Rgb{rgb[3 * 101], rgb[3 * 101 + 1], rgb[3 * 101 + 2]}), role_colour(Role::boundary));
  EXPECT_THROW(colour_by_from_name("temperature"), std::invalid_argument);
  EXPECT_EQ(colour_by_from_name("bonds"), ColourBy::bonds);
  EXPECT_EQ(colour_by_from_name("conversion"), ColourBy::conversion);
}

TEST(Camera, MouseDragFollowsTheCursorInTheViewPlane) {
  Camera c;
  c.target = {0.01, 0.02, 0.03};
  c.distance = 0.05f;
  EXPECT_NEAR(norm(c.eye() - c.target), 0.05, 1e-6);
  const Vec3 d = c.view_plane_offset(100, 0, 1000);
  // 100 of 1000 pixels of a view 2 d tan(fov / 2) high.
  EXPECT_NEAR(norm(d), 0.1 * 2 * 0.05 * std::tan(0.5 * c.fov_y), 1e-7);
  EXPECT_NEAR(dot(d, c.right()), norm(d), 1e-9);
  EXPECT_NEAR(dot(d, c.forward()), 0, 1e-9);
  const Vec3 up = c.view_plane_offset(0, -100, 1000);  // the cursor moving up the screen
  EXPECT_GT(dot(up, c.screen_up()), 0);
  c.orbit(0, 1e4);
  EXPECT_LE(c.pitch, 1.5f);
}

TEST(InputScript, ReadsActionsInStepOrder) {
  const InputScript s = parse_input_script(R"({"actions": [
    {"step": 0, "action": "move", "position_mm": [1, 2, 3]},
    {"step": 10, "action": "dispense"},
    {"step": 20, "action": "switch_tool", "tool": "flat_plugger"},
    {"step": 20, "action": "colour_by", "mode": "pressure"},
    {"step": 90, "action": "end"}]})",
                                           "inputs.json");
  ASSERT_EQ(s.actions.size(), 5u);
  EXPECT_EQ(s.actions[0].kind, ScriptAction::Kind::move);
  EXPECT_EQ(s.actions[0].position_mm, (Vec3{1, 2, 3}));
  EXPECT_EQ(s.actions[2].name, "flat_plugger");
  EXPECT_EQ(s.end_step(), 90u);
}

TEST(InputScript, ErrorsNameTheFileTheFieldAndTheFix) {
  std::string e = error_of(R"({"actions": [{"step": 0, "action": "dispence"}]})");
  EXPECT_NE(e.find("inputs.json: actions[0].action"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'dispense'"), std::string::npos) << e;
  e = error_of(R"({"actions": [{"step": 50, "action": "press"}, {"step": 10, "action": "release"}]})");
  EXPECT_NE(e.find("actions[1].step"), std::string::npos) << e;
  EXPECT_NE(e.find("step order"), std::string::npos) << e;
  e = error_of(R"({"actions": [{"step": 0, "action": "move"}]})");
  EXPECT_NE(e.find("actions[0].position_mm"), std::string::npos) << e;
  e = error_of(R"({"actions": [{"step": 0, "action": "switch_tool", "tool": "drill"}]})");
  EXPECT_NE(e.find("actions[0].tool"), std::string::npos) << e;
  e = error_of(R"({"actions": [{"step": 0, "action": "colour_by", "mode": "heat"}]})");
  EXPECT_NE(e.find("actions[0].mode"), std::string::npos) << e;
  e = error_of(R"({"actions": [{"step": -1, "action": "end"}]})");
  EXPECT_NE(e.find("actions[0].step"), std::string::npos) << e;
  e = error_of(R"({"actions": [)");
  EXPECT_NE(e.find("line 1, column 14: syntax error"), std::string::npos) << e;
  e = error_of(R"({"actions": [{"step": 1e8880, "action": "end"}]})");  // beyond a double (found by fuzz_input_script)
  EXPECT_NE(e.find("inputs.json: JSON: number overflow parsing '1e8880'"), std::string::npos) << e;
  EXPECT_NE(e.find("numbers within double range"), std::string::npos) << e;
  e = error_of(R"({"action": []})");
  EXPECT_NE(e.find("inputs.json"), std::string::npos) << e;
}

// A script runs unattended: what could never happen, or would take unbounded time, is refused.
TEST(InputScript, AnActionAfterAPauseOrEndlessRebuildsAreRefused) {
  // The steps stop while paused: an end after the pause waited for --timeout.
  std::string e = error_of(R"({"actions": [{"step": 5, "action": "pause"}, {"step": 9, "action": "end"}]})");
  EXPECT_NE(e.find("inputs.json: actions[1].step: 9 comes after the pause at step 5 (actions[0])"), std::string::npos)
      << e;
  EXPECT_NE(e.find("add a resume at step 5"), std::string::npos) << e;
  e = error_of(R"({"actions": [{"step": 5, "action": "pause"}, {"step": 9, "action": "resume"}]})");
  EXPECT_NE(e.find("actions[1].step"), std::string::npos) << e;
  // A pause resumed at its step, or ending the script there, is fine.
  EXPECT_EQ(error_of(R"({"actions": [{"step": 5, "action": "pause"}, {"step": 5, "action": "resume"},
                                     {"step": 9, "action": "end"}]})"),
            "");
  EXPECT_EQ(error_of(R"({"actions": [{"step": 5, "action": "pause"}, {"step": 5, "action": "end"}]})"), "");
  // 10,000 resets took 50 s for 97 steps.
  nlohmann::json resets = {{"actions", nlohmann::json::array()}};
  for (int i = 0; i < 101; ++i) resets["actions"].push_back({{"step", i}, {"action", i % 2 ? "reset" : "load_preset"},
                                                              {"preset", "universal"}});
  for (auto& a : resets["actions"])
    if (a["action"] == "reset") a.erase("preset");
  e = error_of(resets.dump());
  EXPECT_NE(e.find("actions[100].action: more than 100 reset and load_preset actions"), std::string::npos) << e;
  nlohmann::json many = {{"actions", nlohmann::json::array()}};
  for (int i = 0; i < 1001; ++i) many["actions"].push_back({{"step", i}, {"action", "dispense"}});
  e = error_of(many.dump());
  EXPECT_NE(e.find("inputs.json: actions: 1001 actions, over the limit of 1000"), std::string::npos) << e;
}

// A block of paste on a plate and a one-particle tool above it.
Scene small_scene() { return testing::small_paste_scene(1e-4, {{0.0, Pose{{0.015, 0.015, 0.06}, {}}}}); }

// Waits (up to 20 s) until `done` holds for the newest snapshot, which it returns.
template <class Pred>
Snapshot wait_for(const SimSession& session, Pred done) {
  Snapshot s;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < until) {
    session.latest(s);
    if (done(s)) return s;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ADD_FAILURE() << "the session did not get there in 20 s (at step " << s.steps << ")";
  return s;
}

std::uint32_t count(const Snapshot& s, Role r) {
  return std::uint32_t(std::count(s.role.begin(), s.role.end(), r));
}

TEST(SimSession, ScheduledCommandsApplyAtTheirStepsSoRunsRepeat) {
  auto run = [] {
    SimSession session(small_scene(), SessionOptions{});
    Command move{Command::Kind::tool_target};
    move.target = {0.015, 0.015, 0.035};
    session.post_at(5, move);
    session.post_at(20, Command{Command::Kind::dispense});
    session.post_at(60, Command{Command::Kind::pause});
    session.start();
    const Snapshot s = wait_for(session, [](const Snapshot& x) { return x.paused && x.steps == 60; });
    session.stop();
    return s;
  };
  const Snapshot a = run(), b = run();
  EXPECT_EQ(a.steps, 60u);
  EXPECT_GT(count(a, Role::material), 48u);  // the increment arrived
  EXPECT_EQ(a.xyz, b.xyz);                   // the same simulation, whatever the timing
  EXPECT_NEAR(a.tool_pose.position.z, 0.06 - 55 * 1e-4 * 0.02, 1e-9);  // followed at 0.02 m/s for 55 steps
}

// The session's own loop yields to the frames: its thread (named viewer-sim) runs
// SimSession::kFreeRunningNice above the nice value of the thread that started it, which keeps its own.
TEST(SimSession, ItsOwnLoopRunsBelowTheFrames) {
  const int own = getpriority(PRIO_PROCESS, 0);
  SimSession session(small_scene(), SessionOptions{});
  session.start();
  (void)wait_for(session, [](const Snapshot& x) { return x.steps >= 5; });
  int found = 0, nice = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream comm(task.path() / "comm");
    std::string name;
    std::getline(comm, name);
    if (name != "viewer-sim") continue;
    ++found;
    errno = 0;
    nice = getpriority(PRIO_PROCESS, id_t(std::stoi(task.path().filename().string())));
    EXPECT_EQ(errno, 0);
  }
  session.stop();
  ASSERT_EQ(found, 1) << "one thread named viewer-sim";
  EXPECT_EQ(nice, std::min(19, own + SimSession::kFreeRunningNice));
  EXPECT_EQ(getpriority(PRIO_PROCESS, 0), own) << "the caller's thread (the frames') keeps its own";
}

// The mouse's instrument stops on the tooth: its target 2 mm below the empty cavity's floor, the
// tool goes down to the floor and no deeper (the hard contact's proxy, contact.hpp).
TEST(SimSession, TheMousesInstrumentStopsOnTheTooth) {
  Scene scene = default_dental_procedure();
  scene.events.clear();
  const ToothFrame f = scene.tooth->frame();
  const PreparedTooth tooth = *scene.tooth;
  SessionOptions o;
  o.tool_speed = 0.1;
  SimSession session(std::move(scene), o);
  Command move{Command::Kind::tool_target};
  move.target = f.to_world({0.5e-3, 0, -4e-3});
  session.post_at(1, move);
  session.start();
  const Snapshot s = wait_for(session, [](const Snapshot& x) { return x.steps >= 300; });
  session.stop();
  const Vec3 tip = s.tool_pose.position;
  EXPECT_GT(tooth.distance(tip).distance, 0) << "the tip is outside the tooth";
  EXPECT_GT(f.to_local(tip).z, -2.0e-3) << "above the floor";
  EXPECT_LT(f.to_local(tip).z, -1.5e-3) << "it went down to the floor";
}

// The curing light (the L key, a script's light_on): on over the paste, the paste under it cures,
// the snapshot carries the light and each particle's conversion, highest at the top; off again,
// the light is gone and the conversion stays.
TEST(SimSession, TheCuringLightCuresThePasteUnderIt) {
  const InputScript script = parse_input_script(
      R"({"actions": [{"step": 0, "action": "light_on"}, {"step": 300, "action": "light_off"}]})", "light.json");
  ASSERT_EQ(script.actions.size(), 2u);
  EXPECT_EQ(script.actions[0].kind, ScriptAction::Kind::light_on);
  EXPECT_EQ(script.actions[1].kind, ScriptAction::Kind::light_off);
  SimSession session(small_scene(), SessionOptions{});
  Command on{Command::Kind::light}, off{Command::Kind::light};
  on.pressed = true;
  session.post_at(0, on);
  session.post_at(200, Command{Command::Kind::pause});
  session.start();
  const Snapshot lit = wait_for(session, [](const Snapshot& x) { return x.paused && x.steps == 200; });
  ASSERT_TRUE(lit.light.has_value());
  EXPECT_LT(lit.light->direction.z, 0) << "pointing down onto the paste";
  ASSERT_EQ(lit.conversion.size(), lit.role.size());
  float top_z = -1e9f, bottom_z = 1e9f, top_alpha = 0, bottom_alpha = 0;
  for (std::size_t i = 0; i < lit.role.size(); ++i) {
    if (lit.role[i] != Role::material) {
      EXPECT_EQ(lit.conversion[i], 0.f);
      continue;
    }
    const float z = lit.xyz[3 * i + 2];
    if (z > top_z) top_z = z, top_alpha = lit.conversion[i];
    if (z < bottom_z) bottom_z = z, bottom_alpha = lit.conversion[i];
  }
  EXPECT_GT(top_alpha, 0.f) << "0.02 s at 1000 mW/cm2 on the top";
  EXPECT_LT(bottom_alpha, top_alpha) << "less light reaches the bottom";
  EXPECT_DOUBLE_EQ(lit.conversion_max, 0.6);
  session.post(off);
  session.post(Command{Command::Kind::single_step});
  const Snapshot dark = wait_for(session, [](const Snapshot& x) { return x.steps > 200; });
  EXPECT_FALSE(dark.light.has_value());
  session.stop();
}

TEST(SimSession, EditsAreCheckedAndUnstableOnesRefused) {
  SimSession session(small_scene(), SessionOptions{.start_paused = true});
  session.start();
  Snapshot s = wait_for(session, [](const Snapshot& x) { return x.version > 0; });
  MaterialEdit m = s.material;
  EXPECT_EQ(m.Kp, 60);
  m.Kp = 1e9;  // acoustic limit far below dt
  Command c{Command::Kind::set_material};
  c.material = m;
  session.post(c);
  s = wait_for(session, [](const Snapshot& x) { return !x.message.empty(); });
  EXPECT_NE(s.message.find("acoustic"), std::string::npos) << s.message;
  EXPECT_EQ(s.material.Kp, 60);
  m = s.material;
  m.B = m.A / 2;  // the adhesion kernel needs A < B
  c.material = m;
  session.post(c);
  s = wait_for(session, [](const Snapshot& x) { return x.message.find("adhesion") != std::string::npos; });
  m = s.material;
  m.Kp = 80;
  m.Ka = 10;
  c.material = m;
  session.post(c);
  s = wait_for(session, [](const Snapshot& x) { return x.material.Kp == 80; });
  EXPECT_TRUE(s.message.empty()) << s.message;
  EXPECT_EQ(s.material.Ka, 10);
  Command t{Command::Kind::switch_tool};
  t.tool = "flat_plugger";
  session.post(t);
  s = wait_for(session, [](const Snapshot& x) { return x.tool_name == "flat_plugger"; });
  EXPECT_GT(count(s, Role::tool), 1u);
  t.tool = "drill";
  session.post(t);
  s = wait_for(session, [](const Snapshot& x) { return !x.message.empty(); });
  EXPECT_NE(s.message.find("drill"), std::string::npos);
  session.post(Command{Command::Kind::single_step});
  s = wait_for(session, [](const Snapshot& x) { return x.steps == 1; });
  session.post(Command{Command::Kind::dispense});
  s = wait_for(session, [](const Snapshot& x) { return count(x, Role::material) > 48; });
  session.post(Command{Command::Kind::reset});
  s = wait_for(session, [](const Snapshot& x) { return count(x, Role::material) == 48 && x.steps == 0; });
  EXPECT_EQ(s.material.Kp, 80);  // a reset keeps the edited paste
  session.stop();
}

// The session's own loop steps through the same Simulation as `dentsph run`: a scene's procedure
// event lands on the step at its time, and the GPU's algorithm (cuda-emulation) steps the same
// scripted session as the CPU, within the backends' parity tolerance, naming itself.
TEST(SimSession, AppliesTheScenesEventsAndStepsOnAnyBackend) {
  Scene sc = small_scene();
  ProcedureEvent drop;
  drop.kind = ProcedureEvent::Kind::dispense;
  drop.t = 10 * sc.model.dt;
  for (Vec3 p : testing::lattice({0.0, 0.0, 0.05}, 0.01, 2, 2, 1))
    drop.particles.push_back(testing::particle(Role::material, p, sc.particles.front().mass, sc.particles.front().material));
  sc.events.push_back(drop);
  auto run = [&](Backend backend, std::uint64_t until) {
    SessionOptions o;
    o.backend = backend;
    SimSession session(sc, o);
    session.post_at(until, Command{Command::Kind::pause});
    session.start();
    const Snapshot s = wait_for(session, [&](const Snapshot& x) { return x.paused && x.steps == until; });
    session.stop();
    return s;
  };
  EXPECT_EQ(count(run(Backend::cpu, 9), Role::material), 48u) << "not before its time";
  const Snapshot cpu = run(Backend::cpu, 40), gpu = run(Backend::cuda_emulation, 40);
  EXPECT_EQ(count(cpu, Role::material), 52u);
  EXPECT_EQ(cpu.backend, "cpu");
  EXPECT_EQ(gpu.backend, "cuda-emulation");
  ASSERT_EQ(gpu.xyz.size(), cpu.xyz.size());
  EXPECT_GT(norm(cpu.device_force_N), 0) << "the tool touched the paste";
  for (int ax = 0; ax < 3; ++ax)
    EXPECT_NEAR(gpu.device_force_N[ax], cpu.device_force_N[ax], kBackendParityTolerance * norm(cpu.device_force_N));
}

TEST(SimSession, UnderTheHapticRuntimeAppliesCommandsBetweenItsStepsAndShowsTheHapticLoop) {
  Scene sc = small_scene();
  RealtimeOptions ro;
  ro.duration_s = 1.0;
  ro.workspace.origin = sc.tool.keyframes.front().pose.position;
  SimSession session(sc, SessionOptions{});
  session.use_device(make_scripted_device(sc, ro.workspace, 1.0), ro);
  session.post(Command{Command::Kind::dispense});
  session.post(Command{Command::Kind::pause});  // refused: the runtime does not pause
  session.start();
  Snapshot s = wait_for(session, [](const Snapshot& x) {
    return count(x, Role::material) > 48 && x.haptic && x.haptic->ticks > 50 && x.steps > 5;
  });
  ASSERT_TRUE(s.haptic);
  EXPECT_EQ(s.haptic->device, "scripted");
  EXPECT_NE(s.message.find("does not pause"), std::string::npos) << s.message;
  EXPECT_LE(norm(s.haptic->force_N), 9.0);
  // Nor does it reset: the runtime's clock, events and recording run on from the state's time.
  const std::uint64_t steps_before = s.steps;
  session.post(Command{Command::Kind::reset});
  s = wait_for(session, [](const Snapshot& x) { return x.message.find("does not reset") != std::string::npos; });
  EXPECT_GT(s.steps, steps_before) << "the state was not set back";
  EXPECT_GT(count(s, Role::material), 48u) << "the dispensed paste is still there";
  // Nor does it take paste edits: the recording replays the scene's paste.
  Command edit{Command::Kind::set_material};
  edit.material = s.material;
  edit.material.Kp *= 2;
  session.post(edit);
  s = wait_for(session, [](const Snapshot& x) { return x.message.find("paste is fixed") != std::string::npos; });
  EXPECT_EQ(s.material.Kp, edit.material.Kp / 2) << "the paste is unchanged";
  s = wait_for(session, [](const Snapshot& x) { return x.message.find("session ended") != std::string::npos; });
  session.stop();
  ASSERT_TRUE(session.realtime_result());
  EXPECT_GT(session.realtime_result()->haptic.timing.ticks, 500u);  // about 1 s at 1 kHz
  EXPECT_EQ(session.realtime_result()->run.status, "completed");
}

// Under the runtime, the D key's increments and the tool menu's switches go into the runtime's
// recording, as the device button's increments do: a replay of the session gives its tool forces
// bit for bit, and without those events it does not (the increment lands on the tool).
TEST(SimSession, UnderTheHapticRuntimeRecordsDispensesAndToolSwitchesForTheReplay) {
  const Scene sc = small_scene();
  RealtimeOptions ro;
  ro.duration_s = 0.6;
  ro.workspace.origin = sc.tool.keyframes.front().pose.position;
  SimSession session(sc, SessionOptions{});
  session.use_device(make_scripted_device(sc, ro.workspace, 0.6), ro);
  session.start();
  wait_for(session, [](const Snapshot& x) { return x.steps > 20; });
  session.post(Command{Command::Kind::dispense});
  Command t{Command::Kind::switch_tool};
  t.tool = "drill";  // refused: nothing recorded
  session.post(t);
  t.tool = "flat_plugger";
  session.post(t);
  wait_for(session, [](const Snapshot& x) { return x.tool_name == "flat_plugger" && count(x, Role::material) > 48; });
  wait_for(session, [](const Snapshot& x) { return x.message.find("session ended") != std::string::npos; });
  session.stop();
  ASSERT_TRUE(session.realtime_result());
  const Recording& rec = session.realtime_result()->recording;
  ASSERT_EQ(rec.events.size(), 2u);
  EXPECT_EQ(rec.events[0].index, kButtonIncrement);
  EXPECT_EQ(rec.events[1].index, kToolSwitch + 1);  // instrument_names()[1]
  EXPECT_GE(rec.events[1].step, rec.events[0].step) << "in the order they were given";
  EXPECT_EQ(rec.dispense_volume, session.options().dispense_volume);
  const std::vector<Vec3> replayed = replay_steps(sc, rec, 1);
  ASSERT_EQ(replayed.size(), rec.steps.size());
  for (std::size_t k = 0; k < replayed.size(); ++k) ASSERT_EQ(replayed[k], rec.steps[k].tool_force) << "step " << k;
  Recording without = rec;
  without.events.clear();
  const std::vector<Vec3> bare = replay_steps(sc, without, 1);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < bare.size(); ++k) differ += !(bare[k] == rec.steps[k].tool_force);
  EXPECT_GT(differ, 0u);
}

}  // namespace
}  // namespace dentsph::viewer
