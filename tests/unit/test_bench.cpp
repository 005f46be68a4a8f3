// The benchmark runner produces every documented field with plausible values (its speed is
// measured, never asserted), and its multi-cup sweep scenes are copies of one cup that never
// interact.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "dentsph/bench.hpp"

namespace dentsph {
namespace {

TEST(Bench, DefaultDentalSceneHasThePapersCounts) {
  DentalSceneParams dp;
  dp.solver = Solver::paper;  // the paper's scene, on its step (bench's default)
  const Scene sc = default_dental_scene(dp);
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
  opt.sweep = {{4, 1}, {4, 2}};
  opt.repeats = 1;
  opt.seconds_per_run = 0.01;
  int lines = 0;
  const BenchResult r = run_benchmarks(opt, [&](const std::string&) { ++lines; });
  const auto j = nlohmann::json::parse(bench_json(r));
  EXPECT_EQ(j["backend"], "cpu");
  EXPECT_FALSE(j["machine"].get<std::string>().empty());
  EXPECT_EQ(j["default_scene"]["name"], default_dental_scene().name);
  EXPECT_GT(j["default_scene"]["steps_per_second"]["1"].get<double>(), 0);
  EXPECT_GT(j["default_scene"]["steps_per_second"]["2"].get<double>(), 0);
  EXPECT_GT(j["default_scene"]["stage_us"]["2"]["forces"].get<double>(), 0);
  EXPECT_EQ(j["default_scene"]["particles"]["material"], 1600);
  EXPECT_EQ(j["default_scene"]["particles"]["tool"], 42);
  ASSERT_EQ(j["sweep"].size(), 6u) << "2 sizes x (grid at 1 and 2 threads + all-pairs)";
  for (const auto& row : j["sweep"]) {
    for (const char* k : {"cups", "particles", "moving_particles", "neighbours", "method",
                          "threads", "steps_per_second", "stage_us"})
      EXPECT_TRUE(row.contains(k)) << k;
    EXPECT_GT(row["moving_particles"].get<int>(), 0);
    EXPECT_LT(row["moving_particles"].get<int>(), row["particles"].get<int>())
        << "paste in a box of boundary particles";
    EXPECT_GT(row["steps_per_second"].get<double>(), 0);
    EXPECT_GT(row["neighbours"].get<double>(), 5)
        << "h = 2 spacings: a lattice particle has ~30 neighbours inside";
    for (const char* k :
         {"hash", "sort", "reorder", "density", "forces", "wrench", "integrate", "total"})
      EXPECT_GE(row["stage_us"][k].get<double>(), 0) << k;
  }
  for (int i : {0, 1, 2}) {
    const auto &one = j["sweep"][i], &two = j["sweep"][i + 3];
    EXPECT_EQ(one["cups"], 1);
    EXPECT_EQ(two["cups"], 2);
    EXPECT_EQ(two["particles"].get<int>(), 2 * one["particles"].get<int>())
        << "two copies of the cup";
    EXPECT_EQ(two["moving_particles"].get<int>(), 2 * one["moving_particles"].get<int>());
    EXPECT_EQ(two["neighbours"].get<double>(), one["neighbours"].get<double>())
        << "the same cup twice, bit for bit";
  }
  EXPECT_EQ(j["sweep"][0]["threads"], 1);
  EXPECT_EQ(j["sweep"][1]["threads"], 2);
  EXPECT_EQ(j["sweep"][0]["method"], "grid");
  EXPECT_GT(j["sweep"][0]["stage_us"]["total"].get<double>(), 0)
      << "the grid step's stages are timed";
  EXPECT_EQ(j["sweep"][2]["method"], "all_pairs");
  EXPECT_GT(j["bytes_per_particle"].get<int>(), 100);
  EXPECT_LT(j["bytes_per_particle"].get<int>(), 4096);
  ASSERT_EQ(j["busy_core"].size(), 3u) << "1 and 2 threads and the governor, one core busy";
  EXPECT_EQ(j["busy_core"][0]["threads"], 1);
  EXPECT_EQ(j["busy_core"][1]["threads"], 2);
  EXPECT_EQ(j["busy_core"][2]["governor"], true);
  for (const auto& row : j["busy_core"]) EXPECT_GT(row["steps_per_second"].get<double>(), 0);
  ASSERT_EQ(j["solvers"].size(), 4u) << "both solvers at 1 and 2 threads";
  for (const auto& row : j["solvers"]) {
    EXPECT_GT(row["steps_per_second"].get<double>(), 0);
    EXPECT_DOUBLE_EQ(row["realtime_factor"].get<double>(), row["steps_per_second"].get<double>() * row["dt_s"].get<double>());
  }
  EXPECT_EQ(j["solvers"][0]["solver"], "paper");
  EXPECT_EQ(j["solvers"][0]["dt_s"], dental_time_step(Solver::paper));
  EXPECT_EQ(j["solvers"][1]["solver"], "iisph");
  EXPECT_EQ(j["solvers"][1]["dt_s"], dental_time_step(Solver::iisph));
  EXPECT_EQ(j["solvers"][2]["threads"], 2);
  EXPECT_EQ(lines, 2 + 3 + 4 + 6);
  const std::string table = bench_table(r);
  EXPECT_NE(table.find("steps/s"), std::string::npos);
  EXPECT_NE(table.find("cups"), std::string::npos);
  EXPECT_NE(table.find("one core kept busy"), std::string::npos);
  EXPECT_NE(table.find("simulated s per wall s"), std::string::npos);
}

TEST(Bench, TheIisphSolverRunsTheDentalSceneAndTheSweep) {
  BenchOptions opt;
  opt.threads = {1};
  opt.sweep = {{4, 1}};
  opt.repeats = 1;
  opt.seconds_per_run = 0.01;
  opt.solver = Solver::iisph;
  const BenchResult r = run_benchmarks(opt, [](const std::string&) {});
  const auto j = nlohmann::json::parse(bench_json(r));
  EXPECT_EQ(j["solver"], "iisph");
  EXPECT_GT(j["default_scene"]["steps_per_second"]["1"].get<double>(), 0);
  EXPECT_GT(j["default_scene"]["stage_us"]["1"]["viscosity"].get<double>(), 0) << "the implicit viscosity ran";
  ASSERT_EQ(j["sweep"].size(), 1u) << "no all-pairs row: the reference is the paper's step";
  EXPECT_EQ(j["sweep"][0]["method"], "grid");
  EXPECT_EQ(nlohmann::json::parse(bench_json(run_benchmarks([] {
              BenchOptions o;
              o.threads = {1};
              o.sweep = {};
              o.repeats = 1;
              o.seconds_per_run = 0.01;
              return o;
            }(), [](const std::string&) {})))["solver"],
            "paper");
}

// The CPU sweep's rows: the single blocks first, then the cup series up to 100k particles, whose
// cups are all the side-16 block in its box (7488 particles, 4096 of them paste).
TEST(Bench, DefaultSweepIsSmallBlocksThenCupsOfOneSize) {
  const BenchOptions opt;
  ASSERT_GE(opt.sweep.size(), 4u);
  EXPECT_EQ(opt.sweep[0].cups, 1);
  EXPECT_EQ(opt.sweep[0].side, 8);
  const Scene cup = sweep_cups_scene(16, 1);
  EXPECT_EQ(cup.particles.size(), 7488u);
  int most = 0;
  for (const SweepSize& s : opt.sweep)
    if (s.cups > 1) {
      EXPECT_EQ(s.side, 16) << "every multi-cup row is copies of the same cup";
      most = std::max(most, s.cups);
    }
  EXPECT_GE(most * 7488, 100000) << "the series reaches 100k particles";
  EXPECT_THROW(sweep_cups_scene(16, 0), std::invalid_argument);
  EXPECT_THROW(sweep_cups_scene(0, 2), std::invalid_argument);
}

// Each cup's particles are one contiguous run of the scene's, in the order of the single cup.
Vec3 cup_offset(const Scene& cups, const Scene& one, std::size_t cup) {
  return cups.particles[cup * one.particles.size()].pos - one.particles[0].pos;
}

TEST(Bench, CupsAreCopiesFarApartInsideTheGrid) {
  const Scene one = sweep_cups_scene(16, 1);
  const std::size_t n = one.particles.size();
  for (int cups : {2, 6, 14})
    for (int reach : {1, 2, 3}) {
      const Scene sc = sweep_cups_scene(16, cups, reach);
      ASSERT_EQ(sc.particles.size(), cups * n);
      std::vector<std::array<real, 3>> lo(cups, {1e9, 1e9, 1e9}), hi(cups, {-1e9, -1e9, -1e9});
      for (int c = 0; c < cups; ++c) {
        const Vec3 off = cup_offset(sc, one, c);
        EXPECT_EQ(off.z, 0);
        for (std::size_t i = 0; i < n; ++i) {
          const ParticleInit& p = sc.particles[c * n + i];
          ASSERT_EQ(p.role, one.particles[i].role);
          ASSERT_EQ(norm(p.pos - off - one.particles[i].pos), 0) << "an exact copy";
          for (int ax = 0; ax < 3; ++ax) {
            lo[c][ax] = std::min(lo[c][ax], p.pos[ax]);
            hi[c][ax] = std::max(hi[c][ax], p.pos[ax]);
          }
        }
      }
      // Between any two cups' boxes: more than 3 h (h + skin is h here) in x or y.
      const real h = sc.model.kernel.h;
      for (int a = 0; a < cups; ++a)
        for (int b = a + 1; b < cups; ++b) {
          const real gap = std::max(
              {lo[b][0] - hi[a][0], lo[a][0] - hi[b][0], lo[b][1] - hi[a][1], lo[a][1] - hi[b][1]});
          EXPECT_GT(gap, 3 * h + sc.model.neighbour_skin) << cups << " cups: " << a << " and " << b;
        }
      // Every particle inside the domain, and the cells a search reaches past the particles' span
      // (wrapped at the domain's edges) empty: no far cup is ever a neighbour candidate.
      const GridSpec& g = sc.model.grid;
      for (int ax = 0; ax < 3; ++ax) {
        int first = g.dims[ax], last = -1;
        for (int c = 0; c < cups; ++c) {
          first = std::min(first, int(std::floor((lo[c][ax] - g.origin[ax]) / g.cell_size)));
          last = std::max(last, int(std::floor((hi[c][ax] - g.origin[ax]) / g.cell_size)));
        }
        EXPECT_GE(first, 0);
        EXPECT_LT(last - first + 2 * g.reach, g.dims[ax]) << "axis " << ax << ", reach " << reach;
      }
    }
}

// Stepped together, the cups do exactly what one cup does alone, bit for bit: they never share a
// neighbour, and a cup's translation changes no rounding. The paste stays inside its own box.
TEST(Bench, CupsSteppedTogetherMatchOneCupSteppedAlone) {
  const int side = 6, cups = 4;  // 2 x 2: neighbours in x, in y and across
  for (int reach : {1, 2}) {
    SCOPED_TRACE(::testing::Message() << "cells of h / " << reach);
    const Scene one = sweep_cups_scene(side, 1, reach), many = sweep_cups_scene(side, cups, reach);
    State a = make_state(one), b = make_state(many);
    const std::size_t n = one.particles.size();
    for (int k = 0; k < 150; ++k) {
      step(one.model, a);
      step(many.model, b, StepOptions{2, nullptr});
    }
    real moved = 0;
    for (std::size_t i = 0; i < n; ++i)
      moved = std::max(moved, norm(a.pos[a.index_of_id[i]] - one.particles[i].pos));
    EXPECT_GT(moved, 1e-5) << "the paste has settled by a measurable amount";
    // The single cup's walls, in x and y: its paste must stay between them.
    std::array<real, 2> wall_lo{1e9, 1e9}, wall_hi{-1e9, -1e9};
    for (const ParticleInit& p : one.particles)
      for (int ax : {0, 1}) {
        wall_lo[ax] = std::min(wall_lo[ax], p.pos[ax]);
        wall_hi[ax] = std::max(wall_hi[ax], p.pos[ax]);
      }
    for (int c = 0; c < cups; ++c) {
      const Vec3 off = cup_offset(many, one, c);
      real dpos = 0, dvel = 0;
      int outside = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t ia = a.index_of_id[i], ib = b.index_of_id[c * n + i];
        dpos = std::max(dpos, norm(b.pos[ib] - off - a.pos[ia]));
        dvel = std::max(dvel, norm(b.vel[ib] - a.vel[ia]));
        if (one.particles[i].role == Role::material)
          for (int ax : {0, 1})
            outside +=
                b.pos[ib][ax] - off[ax] <= wall_lo[ax] || b.pos[ib][ax] - off[ax] >= wall_hi[ax];
      }
      EXPECT_EQ(dpos, 0) << "cup " << c;
      EXPECT_EQ(dvel, 0) << "cup " << c;
      EXPECT_EQ(outside, 0) << "cup " << c << ": paste past its walls";
    }
  }
}

}  // namespace
}  // namespace dentsph
