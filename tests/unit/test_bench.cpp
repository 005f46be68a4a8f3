// The benchmark runner produces every documented field with plausible values (its speed is
// measured, never asserted).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "dentsph/bench.hpp"

namespace dentsph {
namespace {

TEST(Bench, DefaultDentalSceneHasThePapersCounts) {
  const Scene sc = default_dental_scene();
  const State st = make_state(sc);
  EXPECT_EQ(st.count(Role::material), 1600u);
  EXPECT_EQ(st.count(Role::tool), 42u);
  EXPECT_GT(st.count(Role::boundary), 1200u);
  EXPECT_LT(st.count(Role::boundary), 1700u);
  EXPECT_LE(sc.model.dt, stability_limits(sc.model, st).acoustic);
  EXPECT_LE(sc.model.dt, stability_limits(sc.model, st).viscous);
}

TEST(Bench, JsonHasDefaultSceneSweepAndMemory) {
  BenchOptions opt;
  opt.threads = {1, 2};
  opt.sweep_sides = {4, 6};
  opt.repeats = 1;
  opt.seconds_per_run = 0.01;
  int lines = 0;
  const BenchResult r = run_benchmarks(opt, [&](const std::string&) { ++lines; });
  const auto j = nlohmann::json::parse(bench_json(r));
  EXPECT_GT(j["default_scene"]["steps_per_second"]["1"].get<double>(), 0);
  EXPECT_GT(j["default_scene"]["steps_per_second"]["2"].get<double>(), 0);
  EXPECT_EQ(j["default_scene"]["particles"]["material"], 1600);
  ASSERT_EQ(j["sweep"].size(), 6u) << "2 sizes x (grid at 1 and 2 threads + all-pairs)";
  for (const auto& row : j["sweep"]) {
    for (const char* k : {"particles", "moving_particles", "neighbours", "method", "threads", "steps_per_second", "stage_us"})
      EXPECT_TRUE(row.contains(k)) << k;
    EXPECT_GT(row["moving_particles"].get<int>(), 0);
    EXPECT_LT(row["moving_particles"].get<int>(), row["particles"].get<int>()) << "paste in a box of boundary particles";
    EXPECT_GT(row["steps_per_second"].get<double>(), 0);
    EXPECT_GT(row["neighbours"].get<double>(), 5) << "h = 2 spacings: a lattice particle has ~30 neighbours inside";
    EXPECT_GE(row["stage_us"]["total"].get<double>(), 0);
  }
  EXPECT_EQ(j["sweep"][2]["method"], "all_pairs");
  EXPECT_GT(j["bytes_per_particle"].get<int>(), 100);
  EXPECT_LT(j["bytes_per_particle"].get<int>(), 4096);
  EXPECT_EQ(lines, 2 + 6);
  EXPECT_NE(bench_table(r).find("steps/s"), std::string::npos);
}

}  // namespace
}  // namespace dentsph
