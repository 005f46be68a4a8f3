// The built-in dental scene stepped by the iisph solver at its dental time step (1.5 ms, 24 times the
// paper's step's acoustic limit): nothing explodes, the paste stays out of the tooth while the ball
// presses into it, the tool feels it, and the pressure solve stays within its budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>

#include "dentsph/dental.hpp"
#include "dentsph/run.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/step.hpp"

namespace dentsph {
namespace {

TEST(IisphDental, StableAndNoLeakWhilePressing) {
  DentalSceneParams dp;
  dp.solver = Solver::iisph;
  const Scene sc = default_dental_scene(dp);
  ASSERT_EQ(sc.model.solver, Solver::iisph);
  ASSERT_EQ(sc.model.dt, 1.5e-3);
  State st = make_state(sc);
  const StabilityLimits paper = stability_limits(sc.model, st);
  EXPECT_GT(sc.model.dt, 20 * paper.paper_acoustic) << "the paper's step's acoustic limit";
  EXPECT_GT(sc.model.dt, 15 * paper.paper_viscous) << "and its viscous limit";

  const ToothScene ts = default_tooth_scene();
  const real s = ts.boundary.spacing;
  auto inside_tooth = [&] {
    int n = 0;
    for (std::uint32_t i = 0; i < st.size(); ++i)
      if (st.role[i] == Role::material && ts.tooth.distance(st.pos[i]).distance < -0.5 * s) ++n;
    return n;
  };
  real peak = 0, max_speed = 0, worst_error = 0;
  int leaked = 0, iterations = 0;
  // 2 s: the tool goes down 2.5 spacings into the paste and back up, again and again. From 0.9 s
  // paste of this heaped scene crept into the tooth at the end of the cavity with either step (at
  // 1.1 s 11 particles with the paper's step, 14 with this solver at 1 ms before the wall field;
  // docs/model.md); the wall field keeps it out. With the field over the lining's box alone, the
  // heap spreading beyond the lining let paste into the tooth from 1.5 s (13 particles at 1.9 s;
  // the paper's step 79 at 2 s): the field covers the whole domain.
  const int steps = int(std::lround(2.0 / sc.model.dt));
  for (int k = 0; k < steps; ++k) {
    st.tool_pose = sc.tool.at(st.time + sc.model.dt);
    step(sc.model, st, StepOptions{1, nullptr});
    ASSERT_EQ(st.diagnostics.non_finite, 0u) << "step " << k;
    peak = std::max(peak, norm(st.tool_wrench.force));
    if (k > 0) max_speed = std::max(max_speed, st.diagnostics.max_speed);
    worst_error = std::max(worst_error, st.diagnostics.pressure_residual);
    iterations += st.diagnostics.pressure_iterations;
    ASSERT_LE(st.diagnostics.pressure_iterations, sc.model.iisph.max_iterations);
    if (k % 100 == 99) leaked = std::max(leaked, inside_tooth());
  }
  std::printf("%d steps of %g s: peak tool force %.3g N, fastest %.3g m/s, worst mean solve error %.4f, %.2f "
              "iterations a step, %d leaked, %llu bonds\n",
              steps, sc.model.dt, peak, max_speed, worst_error, double(iterations) / steps, leaked,
              (unsigned long long)st.bonded_pairs());
  EXPECT_EQ(leaked, 0) << "material more than half a spacing inside the tooth wall";
  EXPECT_GT(peak, 1e-5) << "N: the tool pressed the paste";
  EXPECT_LT(max_speed * sc.model.dt, sc.model.iisph.cfl * sc.model.kernel.h) << "the velocity CFL condition held";
  // The solve's target is 0.2%; within its budget of 12 iterations the worst step of these left
  // 0.57% at 1.5 ms (measured; 1.1% at 2 ms, under 1% at 1 ms).
  EXPECT_LT(worst_error, 0.02) << "the pressure solve's mean error, every step";
  EXPECT_LT(double(iterations) / steps, 6) << "pressure iterations per step on average";
  EXPECT_GT(st.bonded_pairs(), 1000u);
  EXPECT_EQ(st.diagnostics.pair_overflow, 0u);
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// The built-in procedure with every step's solves past their deadline from their first iteration (as
// `run --realtime --solve-deadline` gives a step slower than its share of dt): a solve past its
// deadline stops only once its error is within kDeadlineErrorFactor (10) of its targets. Before, it
// stopped at its least iterations wherever they left it: mean density errors of up to 65 (6,500%)
// in a realtime run, one of six of which diverged. The procedure stays finite and no cut step is
// left with more than 10 times the mean density error the solve aims for.
TEST(IisphDental, EverySolveCutAtItsDeadlineStaysWithinTenTimesItsTarget) {
  const Scene scene = default_dental_procedure();
  SimulationOptions o;
  o.threads = 2;
  o.solve_budget_s = 1e-12;  // past before the first iteration ends
  Simulation sim(scene, o);
  std::uint64_t cut = 0;
  real worst = 0;
  while (sim.state().time < 1.5 && !sim.diverged()) {
    sim.apply_due_events();
    sim.step(sim.keyframe_pose());
    const StepDiagnostics& d = sim.state().diagnostics;
    if (d.on_deadline) {
      ++cut;
      worst = std::max(worst, d.pressure_residual);
    }
  }
  std::printf("%llu of %llu steps cut at the deadline, the largest error left %.4g; %s\n", (unsigned long long)cut,
              (unsigned long long)sim.state().steps, worst, sim.divergence().c_str());
  EXPECT_FALSE(sim.diverged()) << sim.divergence();
  EXPECT_GT(cut, 100u);
  EXPECT_LE(worst, 10 * scene.model.iisph.density_error);
}

}  // namespace
}  // namespace dentsph
