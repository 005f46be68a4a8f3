// The built-in dental scene: the paper's counts, a stable time step, and paste that stays in the
// cavity while the tool presses into it.
#include <gtest/gtest.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "dentsph/dental.hpp"
#include "dentsph/run.hpp"
#include "dentsph/step.hpp"

namespace dentsph {
namespace {

TEST(DentalScene, PaperCountsStableAndNoLeakWhilePressing) {
  DentalSceneParams dp;
  dp.solver = Solver::paper;  // the paper's scene, on its step
  const Scene sc = default_dental_scene(dp);
  State st = make_state(sc);
  EXPECT_EQ(st.count(Role::material), 1600u);
  EXPECT_EQ(st.count(Role::tool), 42u);
  EXPECT_NEAR(st.count(Role::boundary), 1400, 200);
  const StabilityLimits l = stability_limits(sc.model, st);
  EXPECT_LE(sc.model.dt, l.acoustic);
  EXPECT_LE(sc.model.dt, l.viscous);

  const ToothScene ts = default_tooth_scene();
  const real s = ts.boundary.spacing;
  real peak = 0;
  // 0.1 s: the tool goes down 2.5 spacings into the paste and back up.
  for (int k = 0; k < 2000; ++k) {
    st.tool_pose = sc.tool.at(st.time + sc.model.dt);
    step(sc.model, st, StepOptions{2, nullptr});
    ASSERT_EQ(st.diagnostics.non_finite, 0u) << "step " << k;
    peak = std::max(peak, norm(st.tool_wrench.force));
  }
  EXPECT_GT(peak, 0) << "the tool touched the paste";
  int leaked = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.role[i] == Role::material && ts.tooth.distance(st.pos[i]).distance < -0.5 * s) ++leaked;
  EXPECT_EQ(leaked, 0) << "material inside the tooth wall";
  EXPECT_GT(st.bonded_pairs(), 1000u);
}

TEST(DentalScene, BuildsOnAScannedMolar) {
  const std::filesystem::path mesh = "../shared/data/molar_FDI36_lower_left_first.stl";
  if (!std::filesystem::exists(mesh)) GTEST_SKIP() << "no ../shared/data: the scanned molars are not here";
  const Scene sc = dental_scene_from_mesh(mesh);
  State st = make_state(sc);
  EXPECT_EQ(st.count(Role::material), 1600u);
  EXPECT_EQ(st.count(Role::tool), 52u) << "the ball burnisher as the iisph solver, the default, runs it";
  EXPECT_GT(st.count(Role::boundary), 1000u);
  EXPECT_EQ(sc.source, mesh.string());
  for (int k = 0; k < 50; ++k) {
    st.tool_pose = sc.tool.at(st.time + sc.model.dt);
    step(sc.model, st, StepOptions{2, nullptr});
  }
  EXPECT_EQ(st.diagnostics.non_finite, 0u);
}

TEST(DentalScene, ARunAssessesTheFilling) {
  RunOptions opt;
  opt.steps = 20;
  opt.threads = 2;
  const RunSummary s = run_offline(default_dental_scene(), opt);
  ASSERT_FALSE(s.assessment_json.empty());
  const auto j = nlohmann::json::parse(s.assessment_json);
  for (const char* k : {"fill_fraction", "void_count", "void_volume_mm3", "overfill_mm3", "leaked_particles",
                        "lost_particles", "peak_tool_force_N", "mean_tool_force_N", "duration_s"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_GT(j["fill_fraction"].get<double>(), 0.97) << "the scene starts with its cavity full";
  EXPECT_EQ(j["leaked_particles"], 0);
  EXPECT_NEAR(j["duration_s"].get<double>(), 20 * dental_time_step(Solver::iisph), 1e-12);
  EXPECT_NE(s.assessment_report.find("filled"), std::string::npos);
}

TEST(DentalScene, AMissingMeshIsAClearError) {
  try {
    dental_scene_from_mesh("no/such/tooth.stl");
    FAIL();
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/tooth.stl"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dentsph
