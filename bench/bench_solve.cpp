// Google Benchmark: the iisph solver's two pressure solves side by side (IisphParams::pressure_solve;
// docs/model.md, "The pressure solve"; docs/performance.md, "The pressure solve: Jacobi and conjugate
// gradients"): relaxed Jacobi (src/solver/pressure_jacobi.cpp) and projected conjugate gradients (MPRGP,
// src/solver/pressure_cg.cpp), on two scenes:
//   - BM_DentalSolve/<solve>/<threads>: the built-in dental scene on the iisph solver over the window
//     bench_step's BM_DentalIisph steps (0.4 s of the procedure from its start, after 10 steps), its
//     own budget and tolerances (dental_iisph_params), only the solve changed;
//   - BM_TankSolve/<solve>_<budget>/<threads>: about 100,000 particles of liquid (46 x 46 x 48 on a
//     cubic lattice of 1 mm, rho0 1000, Kp 100, 1 Pa s, no adhesion) in an open box of boundary
//     particles, dt 1 ms, gravity on; settled once for 50 steps (cg, budget 200), each run a copy of
//     it stepped once with its own solve, then 30 steps timed; density_error 1e-4 and
//     max_density_error 1e-3 on every solve, so that they aim at the same tolerance.
// Counters, per step of the timed window: iterations (mean), iterations_max, residual (mean of
// pressure_residual, the mean density error of the solve) and residual_max, max_error (the largest
// pressure_max_error: cg only, 0 after jacobi), density_error (mean, the end of step's compression),
// on_budget (share of steps that stopped at max_iterations over tolerance), pressure_us (the pressure
// stage's wall time), ns_per_particle_it (the pressure stage's time per material particle per
// iteration, over the steps that were not split into substeps), substepped (share of steps split).
// Compare only figures of one invocation, alternated (--benchmark_repetitions=3
// --benchmark_enable_random_interleaving=true): this kind of machine drifts 2 to 3 times in speed.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "dentsph/dental.hpp"
#include "dentsph/model.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/state.hpp"
#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace {

using namespace dentsph;

// ---- the figures of a window of steps ------------------------------------------------------------

std::uint32_t material_count(const State& st) {
  std::uint32_t n = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) n += st.role[i] == Role::material;
  return n;
}

class SolveFigures {
 public:
  explicit SolveFigures(const State& st) { recount(st); }

  // After each step; `times` holds the stage times summed since the window began.
  void add(const State& st, const StageTimes& times) {
    if (st.layout_stamp != layout_) recount(st);
    const StepDiagnostics& d = st.diagnostics;
    const double pressure_step_us = times.pressure_us - pressure_us_;
    pressure_us_ = times.pressure_us;
    ++steps_;
    iterations_ += std::uint64_t(d.pressure_iterations);
    iterations_max_ = std::max(iterations_max_, d.pressure_iterations);
    residual_ += double(d.pressure_residual);
    residual_max_ = std::max(residual_max_, double(d.pressure_residual));
    max_error_ = std::max(max_error_, double(d.pressure_max_error));
    density_error_ += double(d.density_error);
    on_budget_ += d.pressure_on_budget;
    if (d.substeps > 1) {
      // The diagnostics hold the last substep's iterations, the stage time all of them: left out of
      // the cost per iteration.
      ++substepped_;
    } else {
      single_us_ += pressure_step_us;
      particle_iterations_ += double(material_) * double(d.pressure_iterations);
    }
  }

  void report(benchmark::State& bs) const {
    const double n = double(std::max<std::uint64_t>(steps_, 1));
    bs.counters["particles"] = double(material_);
    bs.counters["iterations"] = double(iterations_) / n;
    bs.counters["iterations_max"] = iterations_max_;
    bs.counters["residual"] = residual_ / n;
    bs.counters["residual_max"] = residual_max_;
    bs.counters["max_error"] = max_error_;
    bs.counters["density_error"] = density_error_ / n;
    bs.counters["on_budget"] = double(on_budget_) / n;
    bs.counters["substepped"] = double(substepped_) / n;
    bs.counters["pressure_us"] = pressure_us_ / n;
    bs.counters["ns_per_particle_it"] = particle_iterations_ > 0 ? 1e3 * single_us_ / particle_iterations_ : 0;
  }

 private:
  void recount(const State& st) {
    material_ = material_count(st);
    layout_ = st.layout_stamp;
  }

  std::uint64_t layout_ = 0;
  std::uint32_t material_ = 0;
  std::uint64_t steps_ = 0, iterations_ = 0, on_budget_ = 0, substepped_ = 0;
  int iterations_max_ = 0;
  double residual_ = 0, residual_max_ = 0, max_error_ = 0, density_error_ = 0;
  double pressure_us_ = 0, single_us_ = 0, particle_iterations_ = 0;
};

// ---- the built-in dental scene --------------------------------------------------------------------

// One step of `sc` with the tool moved along its keyframes to the step's end (bench_step.cpp's).
void step_along(const Scene& sc, State& st, const StepOptions& opt = {}) {
  st.tool_pose = sc.tool.at(st.time + sc.model.dt);
  step(sc.model, st, opt);
}

// The benchmark's timed steps (`one` takes a step of `st`), their figures and its counters.
template <class Step>
void timed_steps(benchmark::State& bs, const State& st, StageTimes& times, Step one) {
  times = {};
  SolveFigures fig(st);
  for (auto _ : bs) {
    one();
    fig.add(st, times);
  }
  fig.report(bs);
}

void dental_solve(benchmark::State& bs, PressureSolve solve) {
  DentalSceneParams dp;
  dp.solver = Solver::iisph;
  dp.iisph.pressure_solve = solve;
  const Scene sc = default_dental_scene(dp);
  State st = make_state(sc);
  StageTimes times;
  const StepOptions opt{int(bs.range(0)), &times};
  for (int k = 0; k < 10; ++k) step_along(sc, st, opt);
  timed_steps(bs, st, times, [&] { step_along(sc, st, opt); });
}

// 0.4 s of the procedure at the iisph solver's dental step (267 steps of 1.5 ms), as BM_DentalIisph.
std::int64_t dental_window_steps() { return std::llround(0.4 / double(dental_time_step(Solver::iisph))); }

// ---- the 100k-particle tank -----------------------------------------------------------------------

constexpr real kSpacing = 1e-3, kRho0 = 1000, kG = 9.81, kKp = 100, kMu = 1.0, kDt = 1e-3;
constexpr int kNx = 46, kNy = 46, kNz = 48;  // a square tank: kNy = kNx
constexpr int kSettleSteps = 50, kTimedSteps = 30;
constexpr int kTankThreads = 2;

struct Tank {
  Model model;
  State state;
};

// The tank's model (h = 2 s: the tests' params_for_spacing) with the given solve and budget. Its
// material table is filled by State::add_particles.
Model tank_model(PressureSolve solve, int max_iterations) {
  const real s = kSpacing;
  ModelParams p = testing::params_for_spacing(s, Vec3{-5, -5, -5} * s, Vec3{kNx + 5, kNy + 5, kNz + 8} * s, kDt, {0, 0, -kG});
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = solve;
  p.iisph.max_iterations = max_iterations;
  p.iisph.density_error = 1e-4;
  p.iisph.max_density_error = 1e-3;
  return make_model(p);
}

// Built and settled once (the first tank benchmark pays for it, untimed); every run copies it.
const Tank& settled_tank() {
  static const Tank tank = [] {
    Tank t{tank_model(PressureSolve::cg, 200), {}};
    const Material liquid{kMu, kKp, kRho0, 0}, wall{kMu, 1.5 * kKp, kRho0, 0};
    t.state.add_particles(t.model, testing::column_in_container(t.model, kSpacing, kNx, kNz, liquid, wall));
    for (int k = 0; k < kSettleSteps; ++k) step(t.model, t.state, StepOptions{kTankThreads, nullptr});
    return t;
  }();
  return tank;
}

void tank_solve(benchmark::State& bs, PressureSolve solve, int max_iterations) {
  const Tank& settled = settled_tank();
  Model model = settled.model;  // its material table holds the particles' materials (add_particles)
  model.iisph.pressure_solve = solve;
  model.iisph.max_iterations = max_iterations;
  State st = settled.state;
  StageTimes times;
  const StepOptions opt{int(bs.range(0)), &times};
  step(model, st, opt);  // the solver's buffers sized for this copy; the solve's own warm start
  timed_steps(bs, st, times, [&] { step(model, st, opt); });
  bs.counters["all_particles"] = st.size();
}

// ---- registration ---------------------------------------------------------------------------------

const bool registered = [] {
  for (PressureSolve solve : {PressureSolve::jacobi, PressureSolve::cg}) {
    const std::string name = std::string("BM_DentalSolve/") + pressure_solve_name(solve);
    benchmark::RegisterBenchmark(name.c_str(), [solve](benchmark::State& bs) { dental_solve(bs, solve); })
        ->Arg(1)
        ->Arg(2)
        ->Iterations(dental_window_steps())
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
  }
  struct TankCase {
    PressureSolve solve;
    int budget;
  };
  for (const TankCase c : {TankCase{PressureSolve::jacobi, 12}, TankCase{PressureSolve::jacobi, 200},
                           TankCase{PressureSolve::cg, 200}}) {
    const std::string name =
        std::string("BM_TankSolve/") + pressure_solve_name(c.solve) + "_" + std::to_string(c.budget);
    benchmark::RegisterBenchmark(name.c_str(), [c](benchmark::State& bs) { tank_solve(bs, c.solve, c.budget); })
        ->Arg(kTankThreads)
        ->Iterations(kTimedSteps)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
