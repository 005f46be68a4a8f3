// Google Benchmark: one step of the built-in dental scene (the paper's counts, the tool moving
// along its procedure), and of the `dentsph bench` sweep's scenes (small blocks of material in a
// container, then 1 to 14 copies of the 16^3 block's cup), grid step against the all-pairs
// reference, for growing particle counts and threads; the dental scene's step also through the
// Simulation every loop steps with. Arguments: side, cups, threads.
#include <benchmark/benchmark.h>

#include "dentsph/bench.hpp"
#include "dentsph/simulation.hpp"
#include "step/stages.hpp"

namespace {

using namespace dentsph;

void run(benchmark::State& bs, bool all_pairs) {
  const Scene sc = sweep_cups_scene(int(bs.range(0)), int(bs.range(1)));
  State st = make_state(sc);
  const StepOptions opt{int(bs.range(2)), nullptr};
  for (int k = 0; k < 10; ++k) step(sc.model, st, opt);  // first bonds, warm caches
  for (auto _ : bs) {
    if (all_pairs)
      step_all_pairs(sc.model, st);
    else
      step(sc.model, st, opt);
  }
  bs.counters["particles"] = st.size();
  bs.counters["steps_per_second"] = benchmark::Counter(double(bs.iterations()), benchmark::Counter::kIsRate);
}

void BM_DentalStep(benchmark::State& bs) {
  const Scene sc = default_dental_scene();
  State st = make_state(sc);
  const StepOptions opt{int(bs.range(0)), nullptr};
  auto one = [&] {
    st.tool_pose = sc.tool.at(st.time + sc.model.dt);
    step(sc.model, st, opt);
  };
  for (int k = 0; k < 10; ++k) one();
  for (auto _ : bs) one();
  bs.counters["particles"] = st.size();
  bs.counters["steps_per_second"] = benchmark::Counter(double(bs.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DentalStep)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The same steps through the run core every loop uses (a Simulation: the CPU's Stepper, the tool
// force statistics, the force limit, the divergence check): beside BM_DentalStep, the cost of the
// core around the step.
void BM_DentalSimulation(benchmark::State& bs) {
  const Scene sc = default_dental_scene();
  Simulation sim(sc, {Backend::cpu, int(bs.range(0)), false});
  auto one = [&] { sim.step(sim.keyframe_pose()); };
  for (int k = 0; k < 10; ++k) one();
  for (auto _ : bs) one();
  bs.counters["particles"] = sim.state().size();
  bs.counters["steps_per_second"] = benchmark::Counter(double(bs.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DentalSimulation)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

// One stage of the dental scene's step, repeated on the state after 200 steps (the paste pressed in,
// bonds formed): the density pass over the kept lists (with each particle's pressure), and the
// force pass (its bond updates find nothing to change on a repeat).
template <class Stage>
void dental_stage(benchmark::State& bs, Stage&& stage) {
  const Scene sc = default_dental_scene();
  State st = make_state(sc);
  const StepOptions opt{int(bs.range(0)), nullptr};
  for (int k = 0; k < 200; ++k) {
    st.tool_pose = sc.tool.at(st.time + sc.model.dt);
    step(sc.model, st, opt);
  }
  for (auto _ : bs) stage(sc.model, st, opt.threads);
}
void BM_DentalDensity(benchmark::State& bs) {
  dental_stage(bs, [](const Model& m, State& st, int t) { stages::compute_density(m, st, t, false); });
}
BENCHMARK(BM_DentalDensity)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();
void BM_DentalForces(benchmark::State& bs) {
  dental_stage(bs, [](const Model& m, State& st, int t) { stages::compute_forces(m, st, t); });
}
BENCHMARK(BM_DentalForces)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The rows of `dentsph bench`'s CPU sweep, on 1 and 2 threads.
void sweep_rows(benchmark::internal::Benchmark* b) {
  for (const SweepSize& s : BenchOptions{}.sweep)
    for (int threads : {1, 2}) b->Args({s.side, s.cups, threads});
}

void BM_GridStep(benchmark::State& bs) { run(bs, false); }
BENCHMARK(BM_GridStep)->Apply(sweep_rows)->ArgNames({"side", "cups", "threads"})->Unit(benchmark::kMicrosecond)->UseRealTime();

void BM_AllPairsStep(benchmark::State& bs) { run(bs, true); }
BENCHMARK(BM_AllPairsStep)->Args({8, 1, 1})->Args({12, 1, 1})->ArgNames({"side", "cups", "threads"})->Unit(benchmark::kMicrosecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
