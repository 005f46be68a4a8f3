// Google Benchmark: one step of the built-in dental scene (the paper's counts, the tool moving
// along its procedure), and of the `dentsph bench` sweep's scenes (small blocks of material in a
// container, then 1 to 14 copies of the 16^3 block's cup), grid step against the all-pairs
// reference, for growing particle counts and threads; the dental scene's step also through the
// Simulation every loop steps with. Arguments: side, cups, threads.
#include <benchmark/benchmark.h>

#include <cctype>
#include <cmath>
#include <string>

#include "dentsph/bench.hpp"
#include "dentsph/cure.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/dispense.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/solver.hpp"
#include "step/stages.hpp"

namespace {

using namespace dentsph;

// One step of `sc` with the tool moved along its keyframes to the step's end.
void step_along(const Scene& sc, State& st, const StepOptions& opt = {}) {
  st.tool_pose = sc.tool.at(st.time + sc.model.dt);
  step(sc.model, st, opt);
}
// `n` of them.
void step_along(const Scene& sc, State& st, int n, const StepOptions& opt = {}) {
  for (int k = 0; k < n; ++k) step_along(sc, st, opt);
}

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
  auto one = [&] { step_along(sc, st, opt); };
  step_along(sc, st, 10, opt);
  for (auto _ : bs) one();
  bs.counters["particles"] = st.size();
  bs.counters["steps_per_second"] = benchmark::Counter(double(bs.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DentalStep)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The built-in dental scene's step on either solver at its dental time step over the same window of
// the procedure (0.4 s of simulated time from its start, the first increment's dispensing and
// compaction), each stage's mean time as a counter (us per step), the share of steps that rebuilt
// the grid, and the simulated seconds per wall second (`realtime`). Arg: threads.
void dental_solver(benchmark::State& bs, Solver solver) {
  DentalSceneParams dp;
  dp.solver = solver;
  const Scene sc = default_dental_scene(dp);
  State st = make_state(sc);
  StageTimes times;
  const StepOptions opt{int(bs.range(0)), &times};
  auto one = [&] { step_along(sc, st, opt); };
  step_along(sc, st, 10, opt);
  times = {};
  std::uint64_t rebuilds = 0, steps = 0, iterations = 0;
  double rebuild_us = 0;  // the whole step's time, in the steps that rebuilt the neighbour lists
  for (auto _ : bs) {
    const double before = times.density_us;
    one();
    if (st.diagnostics.rebuilt) rebuild_us += times.density_us - before;
    rebuilds += st.diagnostics.rebuilt;
    iterations += std::uint64_t(st.diagnostics.pressure_iterations);
    ++steps;
  }
  const double n = double(std::max<std::uint64_t>(steps, 1));
  bs.counters["rebuilt"] = double(rebuilds) / n;
  bs.counters["rebuild_step_us"] = rebuilds > 0 ? rebuild_us / double(rebuilds) : 0;
  bs.counters["other_step_us"] = steps > rebuilds ? (times.density_us - rebuild_us) / double(steps - rebuilds) : 0;
  bs.counters["grid_us"] = (times.hash_us + times.sort_us + times.reorder_us) / n;
  bs.counters["pairs_us"] = times.density_us / n;
  bs.counters["forces_us"] = (times.forces_us + times.wrench_us) / n;
  bs.counters["pressure_us"] = times.pressure_us / n;
  bs.counters["viscosity_us"] = times.viscosity_us / n;
  bs.counters["integrate_us"] = times.integrate_us / n;
  bs.counters["iterations"] = double(iterations) / n;
  bs.counters["realtime"] = benchmark::Counter(double(bs.iterations()) * sc.model.dt, benchmark::Counter::kIsRate);
}
// 0.4 s of the procedure on each: 8000 paper steps, 267 iisph steps of 1.5 ms.
std::int64_t window_steps(Solver s) { return std::llround(0.4 / double(dental_time_step(s))); }
// One for every registered solver (solver.hpp), named after it: BM_DentalPaper, BM_DentalIisph.
const bool dental_solvers_registered = [] {
  for (const SolverEntry& e : registered_solvers()) {
    std::string name = std::string("BM_Dental") + e.name;
    name[9] = char(std::toupper(static_cast<unsigned char>(name[9])));
    const Solver key = e.key;
    benchmark::RegisterBenchmark(name.c_str(), [key](benchmark::State& bs) { dental_solver(bs, key); })
        ->Arg(1)
        ->Arg(2)
        ->Iterations(window_steps(key))
        ->Unit(benchmark::kMicrosecond)
        ->UseRealTime();
  }
  return true;
}();

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

// Light curing on the dental scene (src/cure): the curing light over the cavity, 1000 mW/cm^2.
CuringLight dental_light(const Scene& sc) {
  CuringLight light;
  light.tip = sc.tooth->frame().to_world({0, 0, 2e-3});
  light.direction = -sc.tooth->frame().z;
  return light;
}

// The cure update alone, as a run calls it after every step (the dose each step, a pass every
// transition_interval: 1 in 20 steps at the dental dt). The paste is kept from setting (gel point at
// alpha_max), so that every pass does the same work; the cure update is serial.
void BM_DentalCureUpdate(benchmark::State& bs) {
  const Scene sc = default_dental_scene();
  State st = make_state(sc);
  step_along(sc, st, 10);
  CureMaterial never_sets = cure_material_preset("composite");
  never_sets.alpha_gel = never_sets.alpha_max;
  const CureModel cure = make_cure_model(sc.model, never_sets, sc.material_spacing, scene_paste(sc).material);
  const std::optional<CuringLight> light = dental_light(sc);
  std::uint32_t lit = 0;
  for (auto _ : bs) {
    st.time += sc.model.dt;  // as the step would
    lit = cure_between_steps(cure, st, light, sc.model.dt).lit;
  }
  bs.counters["lit"] = lit;
}
BENCHMARK(BM_DentalCureUpdate)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The light's transport alone (part of a pass).
void BM_DentalLightTransport(benchmark::State& bs) {
  const Scene sc = default_dental_scene();
  State st = make_state(sc);
  const CureModel cure =
      make_cure_model(sc.model, cure_material_preset("composite"), sc.material_spacing, scene_paste(sc).material);
  const CuringLight light = dental_light(sc);
  for (auto _ : bs) benchmark::DoNotOptimize(compute_irradiance(cure, st, light));
}
BENCHMARK(BM_DentalLightTransport)->Unit(benchmark::kMicrosecond)->UseRealTime();

// One cure pass alone (what a call does every transition_interval: the transport, every paste
// particle's conversion and parameters, the transition check): the size of the spike.
void BM_DentalCurePass(benchmark::State& bs) {
  const Scene sc = default_dental_scene();
  State st = make_state(sc);
  step_along(sc, st, 10);
  CureMaterial never_sets = cure_material_preset("composite");
  never_sets.alpha_gel = never_sets.alpha_max;
  const CureModel cure = make_cure_model(sc.model, never_sets, sc.material_spacing, scene_paste(sc).material);
  const std::optional<CuringLight> light = dental_light(sc);
  for (auto _ : bs) {
    st.cure.next_pass = -1;
    cure_between_steps(cure, st, light, sc.model.dt);
  }
}
BENCHMARK(BM_DentalCurePass)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The step and the cure update after it, over the first 0.1 s of light (the top millimetre of
// paste sets: role changes, the boundary's static density recomputed, lists rebuilt), restarting
// from the unlit state every 2000 steps; compare with BM_DentalStep.
void BM_DentalStepCuring(benchmark::State& bs) {
  const Scene sc = default_dental_scene();
  State start = make_state(sc);
  const StepOptions opt{int(bs.range(0)), nullptr};
  step_along(sc, start, 10, opt);
  const CureModel cure =
      make_cure_model(sc.model, cure_material_preset("composite"), sc.material_spacing, scene_paste(sc).material);
  const std::optional<CuringLight> light = dental_light(sc);
  State st = start;
  int k = 0;
  std::uint64_t set = 0;
  for (auto _ : bs) {
    if (k++ == 2000) {
      bs.PauseTiming();
      st = start;
      k = 1;
      bs.ResumeTiming();
    }
    step_along(sc, st, opt);
    set += cure_between_steps(cure, st, light, sc.model.dt).set;
  }
  bs.counters["set_per_step"] = benchmark::Counter(double(set) / double(bs.iterations()));
}
BENCHMARK(BM_DentalStepCuring)->Arg(1)->Arg(2)->Iterations(4000)->Unit(benchmark::kMicrosecond)->UseRealTime();

// One stage of the dental scene's step, repeated on the state after 200 steps (the paste pressed in,
// bonds formed): the density pass over the kept lists (with each particle's pressure), and the
// force pass (its bond updates find nothing to change on a repeat).
template <class Stage>
void dental_stage(benchmark::State& bs, Stage&& stage) {
  const Scene sc = default_dental_scene();
  State st = make_state(sc);
  const StepOptions opt{int(bs.range(0)), nullptr};
  step_along(sc, st, 200, opt);
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

// The reorder of a rebuild (stage 2b) on the dental scene after 200 steps: the cell order of that
// state, applied again and again (near the identity, as between two rebuilds of a run). Counters:
// the bytes per particle the reorder gathers, and the bytes every per-particle array holds.
void BM_DentalReorder(benchmark::State& bs) {
  const Scene sc = default_dental_scene();
  State st = make_state(sc);
  const StepOptions opt{int(bs.range(0)), nullptr};
  step_along(sc, st, 200, opt);
  stages::compute_cell_keys(sc.model, st, opt.threads);
  stages::sort_by_cell(sc.model, st);
  for (auto _ : bs) stages::reorder(sc.model, st, opt.threads);
  // id, role, pos, vel, anchor, mass, material (mu, Kp, rho0, Ka are written from the table)
  bs.counters["gathered_bytes_per_particle"] =
      double(sizeof(std::uint32_t) + sizeof(Role) + 3 * sizeof(Vec3) + sizeof(real) + sizeof(MaterialIndex));
  bs.counters["state_bytes_per_particle"] = double(st.bytes_per_particle());
  bs.counters["particles"] = st.size();
}
BENCHMARK(BM_DentalReorder)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

// The same on the sweep's largest scene (14 cups of a 16^3 block, about 100k particles: the arrays
// no longer fit in the cache), after one step has put it in cell order.
void BM_SweepReorder(benchmark::State& bs) {
  const Scene sc = sweep_cups_scene(16, 14);
  State st = make_state(sc);
  const StepOptions opt{int(bs.range(0)), nullptr};
  step(sc.model, st, opt);
  stages::compute_cell_keys(sc.model, st, opt.threads);
  stages::sort_by_cell(sc.model, st);
  for (auto _ : bs) stages::reorder(sc.model, st, opt.threads);
  bs.counters["particles"] = st.size();
}
BENCHMARK(BM_SweepReorder)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

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
