// The offline run: its files, its refusal of an unstable time step, and its report of divergence.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "dentsph/io/summary.hpp"
#include "dentsph/run.hpp"
#include "dentsph/scene.hpp"
#include "support/small_scene.hpp"

namespace dentsph {
namespace {

namespace fs = std::filesystem;

Scene small_scene(real dt) {
  return testing::small_paste_scene(dt, {{0.0, Pose{{0.015, 0.015, 0.05}, {}}}, {0.1, Pose{{0.015, 0.015, 0.02}, {}}}});
}

TEST(Run, WritesSummaryCsvAndSnapshots) {
  const fs::path out = fs::temp_directory_path() / ("dentsph_run_" + std::to_string(::getpid()));
  fs::remove_all(out);
  RunOptions opt;
  opt.steps = 100;
  opt.out_dir = out;
  int progress_calls = 0;
  opt.on_progress = [&](const RunProgress& p) {
    ++progress_calls;
    EXPECT_LE(p.step, p.total);
  };
  Scene scene = small_scene(5e-4);
  scene.force_scale = 20;
  const RunSummary sum = run_offline(scene, opt);
  EXPECT_EQ(sum.status, "completed");
  EXPECT_EQ(sum.steps, 100u);
  EXPECT_GT(progress_calls, 10);
  const auto j = nlohmann::json::parse(std::ifstream(out / "summary.json"));
  EXPECT_EQ(j["steps"], 100);
  EXPECT_NEAR(j["sim_time_s"].get<double>(), 0.05, 1e-12);
  EXPECT_EQ(j["particles"]["material"], 48);
  EXPECT_EQ(j["particles"]["tool"], 1);
  // The tool force in simulated N, and rendered on a device at the scene's force scale.
  EXPECT_EQ(j["tool"]["force_scale"], 20);
  EXPECT_EQ(sum.force_scale, 20);
  RunSummary pressed = sum;
  pressed.peak_tool_force_N = 0.25;
  const auto t = nlohmann::json::parse(io::summary_json(pressed))["tool"];
  EXPECT_EQ(t["peak_force_N"], 0.25);
  EXPECT_EQ(t["peak_device_force_N"], 5.0);
  std::ifstream csv(out / "tool_force.csv");
  int lines = 0;
  for (std::string l; std::getline(csv, l);) ++lines;
  EXPECT_EQ(lines, 101) << "header + one row per step";
  // Snapshots at t = 0, every 0.01 s, and the final state.
  EXPECT_GE(sum.snapshots, 6u);
  EXPECT_TRUE(fs::exists(out / "particles.pvd"));
  EXPECT_TRUE(fs::exists(out / "particles" / "step_00000000.vtu"));
  // The paste's surface beside each snapshot (the scene's paste has a spacing).
  EXPECT_EQ(sum.surfaces, sum.snapshots);
  EXPECT_TRUE(fs::exists(out / "paste_surface.pvd"));
  EXPECT_GT(fs::file_size(out / "paste_surface" / "step_00000000.vtp"), 1000u);
  EXPECT_EQ(j["paste_surface"]["surfaces"], sum.snapshots);
  EXPECT_GT(fs::file_size(out / "preview.png"), 1000u);
}

// "output": {"surface": false} leaves the paste's surface out.
TEST(Run, TheSurfaceIsLeftOutWhenTheSceneSaysSo) {
  const fs::path out = fs::temp_directory_path() / ("dentsph_run_nosurface_" + std::to_string(::getpid()));
  fs::remove_all(out);
  RunOptions opt;
  opt.steps = 10;
  opt.out_dir = out;
  Scene scene = small_scene(5e-4);
  scene.output.surface = false;
  const RunSummary sum = run_offline(scene, opt);
  EXPECT_GE(sum.snapshots, 2u);
  EXPECT_EQ(sum.surfaces, 0u);
  EXPECT_FALSE(fs::exists(out / "paste_surface.pvd"));
  fs::remove_all(out);
}

TEST(Run, RefusesATimeStepOverTheLimitAndNamesTheField) {
  Scene sc = small_scene(0.05);  // far over the acoustic limit (~ 0.4 * 0.02 / sqrt(200) = 5.7e-4 s)
  RunOptions opt;
  opt.steps = 5;
  try {
    run_offline(sc, opt);
    FAIL() << "expected UnstableTimeStep";
  } catch (const UnstableTimeStep& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("small.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("simulation.dt"), std::string::npos) << msg;
    EXPECT_NE(msg.find("acoustic"), std::string::npos) << msg;
  }
}

// A material whose stability limit is under the shortest time step a scene may take gets advice it can
// follow (the material, not a dt of 5e-11 s where dt must be at least 1e-9 s).
TEST(Run, ALimitUnderTheShortestTimeStepAdvisesTheMaterial) {
  nlohmann::json j = nlohmann::json::parse(std::ifstream("scenes/blob_on_plate.json"));
  j["materials"]["paste"]["viscosity"] = 1e9;  // viscous limit 0.125 h^2 rho0 / mu = 5e-11 s
  const Scene sc = parse_scene(j.dump(), "viscous.json");
  RunOptions opt;
  opt.steps = 1;
  try {
    run_offline(sc, opt);
    FAIL() << "expected UnstableTimeStep";
  } catch (const UnstableTimeStep& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("viscous.json: simulation.dt"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no time step the program takes (at least 1e-09 s) is under it"), std::string::npos) << msg;
    EXPECT_NE(msg.find("lower the stiffest material's stiffness or viscosity"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("set simulation.dt to at most"), std::string::npos) << msg;
  }
}

TEST(Run, ForcedUnstableRunReportsDivergenceInsteadOfSilentNaN) {
  RunOptions opt;
  opt.steps = 2000;
  opt.allow_unstable = true;
  const RunSummary sum = run_offline(small_scene(0.05), opt);
  EXPECT_TRUE(sum.forced);
  EXPECT_TRUE(sum.acoustic_violated);
  EXPECT_GT(sum.force_violation_steps, 0u);
  EXPECT_EQ(sum.status, "diverged");
  EXPECT_NE(sum.message.find("sound speed"), std::string::npos) << sum.message;
  EXPECT_LT(sum.steps, 2000u) << "stopped at the divergence";
}

}  // namespace
}  // namespace dentsph
