// The benchmark runner behind `dentsph bench`. Each configuration runs `repeats` times for about
// `seconds_per_run` of wall time after a warm-up; the median run's rate and stage times are kept.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/bench.hpp"
#include "dentsph/solver.hpp"
#include "dentsph/thread_governor.hpp"
#include "dentsph/dental.hpp"

namespace dentsph {

namespace {

struct Measured {
  double steps_per_second = 0;
  StageTimes per_step;
  std::size_t bytes_per_particle = 0;  // of the state it ran
};

// Per step: a sum of stage times over `steps` steps divided by their number.
StageTimes per_step(const StageTimes& sum, std::uint64_t steps) {
  StageTimes t;
  for (double StageTimes::*f : {&StageTimes::hash_us, &StageTimes::sort_us, &StageTimes::reorder_us,
                                &StageTimes::density_us, &StageTimes::pressure_us, &StageTimes::forces_us,
                                &StageTimes::wrench_us, &StageTimes::integrate_us, &StageTimes::viscosity_us})
    t.*f = sum.*f / double(steps);
  t.steps = steps;
  return t;
}

// The timing loop of every configuration: 10 warm-up steps (first bonds, caches), then
// opt.repeats runs of at least 5 steps and seconds_per_run each; the median run. `one(times)`
// takes one step, adding its stage times to `times` when given one: the runs give it one where
// `timed`, and the median run's stage times are then kept.
template <class One>
Measured timed_runs(const BenchOptions& opt, bool timed, One&& one) {
  for (int k = 0; k < 10; ++k) one(nullptr);
  std::vector<Measured> runs;
  for (int r = 0; r < std::max(1, opt.repeats); ++r) {
    StageTimes t;
    const auto t0 = std::chrono::steady_clock::now();
    std::uint64_t steps = 0;
    double elapsed = 0;
    while (steps < 5 || elapsed < opt.seconds_per_run) {
      one(timed ? &t : nullptr);
      ++steps;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    runs.push_back({double(steps) / elapsed, timed ? per_step(t, steps) : StageTimes{}, 0});
  }
  std::sort(runs.begin(), runs.end(),
            [](const Measured& a, const Measured& b) { return a.steps_per_second < b.steps_per_second; });
  return runs[runs.size() / 2];
}

// The all-pairs reference on the CPU: runs `state`; `prepare` sets the tool pose before each step.
template <class Prepare>
Measured measure_all_pairs(const Model& model, State& state, const BenchOptions& opt, Prepare&& prepare) {
  Measured m = timed_runs(opt, false, [&](StageTimes*) {
    prepare(state);
    step_all_pairs(model, state);
  });
  m.bytes_per_particle = state.bytes_per_particle();
  return m;
}

// The grid step with its thread count chosen before every step by a ThreadGovernor of up to
// `max_threads` (what the run loops use).
template <class Prepare>
Measured measure_governed(const Model& model, State& state, int max_threads, const BenchOptions& opt,
                          Prepare&& prepare) {
  ThreadGovernor governor(max_threads);
  const std::unique_ptr<StepSolver> solver = make_solver(model.solver);
  solver->resize(model, state);
  Measured m = timed_runs(opt, false, [&](StageTimes*) {
    prepare(state);
    const auto t0 = std::chrono::steady_clock::now();
    solver->step(model, state, StepOptions{governor.threads(), nullptr});
    governor.record(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  });
  m.bytes_per_particle = state.bytes_per_particle() + solver->bytes() / std::max<std::size_t>(1, state.size());
  return m;
}

// Keeps one core busy while it lives: a thread that spins, as another program would.
class BusyCore {
 public:
  BusyCore() : thread_([this] {
    volatile std::uint64_t n = 0;
    while (!stop_.load(std::memory_order_relaxed)) n = n + 1;
  }) {}
  ~BusyCore() {
    stop_.store(true);
    thread_.join();
  }
  BusyCore(const BusyCore&) = delete;
  BusyCore& operator=(const BusyCore&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// A Stepper (the CPU grid step on `threads`, or a GPU backend) from `state`: the step rate, then
// the stage times. The CPU times its stages in the measured runs (the clock costs nothing there);
// a GPU's stage times come from separately timed steps (each stage waited for, so slower than the
// graph replays that give its rate, the haptic path). `prepare` sets the tool pose before each step.
template <class Prepare>
Measured measure(const Model& model, State& state, int threads, const BenchOptions& opt, Prepare&& prepare) {
  const std::unique_ptr<Stepper> stepper = make_stepper(opt.backend, model, state, threads);
  const bool cpu = opt.backend == Backend::cpu;
  auto one = [&](StageTimes* times) {
    prepare(state);
    if (times)
      stepper->step_timed(state, state.tool_pose, *times);
    else
      stepper->step(state, state.tool_pose);
  };
  Measured m = timed_runs(opt, cpu, one);
  if (!cpu) {
    StageTimes t;
    for (int k = 0; k < 20; ++k) one(&t);
    m.per_step = per_step(t, t.steps);
  }
  m.bytes_per_particle = state.bytes_per_particle() + stepper->solver_bytes() / std::max<std::size_t>(1, state.size());
  return m;
}

std::string machine_name() {
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpu, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  return fmt::format("{}, {} hardware threads", model, std::thread::hardware_concurrency());
}

// The GPU, or the CPU that emulates it; throws CudaUnavailable where there is none.
std::string gpu_machine(Backend backend) {
  if (backend == Backend::cuda_emulation) return machine_name() + " (emulating the CUDA backend)";
  const CudaStatus cs = cuda_status();
  if (!cs.available) throw CudaUnavailable(cs.reason);
  return cs.device;
}

// The pressure is part of the density pass on the CPU, so every backend reports the two together
// as "density" (the GPU's separate pressure kernel added in).
nlohmann::json stages_json(const StageTimes& t) {
  return {{"hash", t.hash_us},     {"sort", t.sort_us},     {"reorder", t.reorder_us},
          {"density", t.density_us + t.pressure_us},        {"forces", t.forces_us},
          {"wrench", t.wrench_us}, {"integrate", t.integrate_us},
          {"viscosity", t.viscosity_us}, {"total", t.total_us()}};
}

// Material and tool particles: the ones the step moves.
std::uint32_t moving_count(const State& st) {
  return std::uint32_t(st.count(Role::material) + st.count(Role::tool));
}

}  // namespace

Scene sweep_block_scene(int side, int grid_reach) { return sweep_cups_scene(side, 1, grid_reach); }

Scene sweep_cups_scene(int side, int cups, int grid_reach) {
  if (side < 1 || cups < 1)
    throw std::invalid_argument(fmt::format("sweep scene: side {} and cups {} must be at least 1", side, cups));
  // The lattice spacing: 1 cm rounded to a multiple of 2^-50 m, and x and y measured from 2 m, so
  // that every lattice position is exact and, from 2 to 4 m, every translation by an even number
  // of spacings is exact in floating point and rounds alike: there the cups are copies bit for bit
  // (the same neighbours, the same sums), and stay so as they move.
  const real s = std::ldexp(std::round(std::ldexp(0.01, 50)), -50);
  constexpr real base = 2;
  // A cup's walls span side + 3 spacings (from -2 to side + 1); cups are `pitch` spacings apart,
  // leaving 7 or 8 spacings (3.5 h and more) between the walls of neighbouring cups. The pitch is
  // even: a whole number of h, so every cup sits at the same place in the grid's cells.
  const int pitch = side + 10 + side % 2;
  const int cols = int(std::ceil(std::sqrt(double(cups))));
  const int rows = (cups + cols - 1) / cols;
  Scene sc;
  sc.name = cups == 1 ? fmt::format("block_{}", side) : fmt::format("cups_{}x{}", cups, side);
  sc.source = "built-in";
  sc.params.dt = 2e-4;
  set_lattice_spacing(sc.params, s);
  // The domain begins one spacing before the walls and ends five after them on every axis, so a
  // search past its edge (the grid wraps there) finds empty cells, never another cup's.
  sc.params.domain_min = {base, base, -3 * s};
  sc.params.domain_max = {base + ((cols - 1) * pitch + side + 9) * s, base + ((rows - 1) * pitch + side + 9) * s,
                          (side + 6) * s};
  sc.params.grid_reach = grid_reach;
  sc.model = make_model(sc.params);
  const real m = lattice_particle_mass(1000, s, sc.model.kernel);
  const Material paste{0.5, 60, 1000, 50}, wall{0.5, 200, 1000, 0};
  // Each cup: a cube of side^3 paste in an open container with two wall layers, one spacing away.
  for (int c = 0; c < cups; ++c) {
    const int ox = (c % cols) * pitch + 3, oy = (c / cols) * pitch + 3;
    auto add = [&](Role role, int i, int j, int k, const Material& mat) {
      sc.particles.push_back(make_particle(role, {base + (ox + i) * s, base + (oy + j) * s, k * s}, m, mat));
    };
    for (int k = -2; k <= side + 1; ++k)
      for (int j = -2; j <= side + 1; ++j)
        for (int i = -2; i <= side + 1; ++i) {
          const bool inner = i >= 0 && i < side && j >= 0 && j < side && k >= 0;
          if (inner && k < side) add(Role::material, i, j, k, paste);
          if (!inner) add(Role::boundary, i, j, k, wall);
        }
  }
  intern_scene_materials(sc);
  return sc;
}

// The CPU measures each thread count of the grid step (and the all-pairs step on one thread up to
// all_pairs_max_particles); a GPU backend measures one configuration, keyed 1, and sweeps its own
// sizes (single blocks up to millions of particles). Each sweep scene is built and sorted once;
// every configuration runs from a copy of it.
BenchResult run_benchmarks(const BenchOptions& opt, const std::function<void(const std::string&)>& log) {
  const bool gpu = opt.backend != Backend::cpu;
  BenchResult res;
  res.backend = opt.backend;
  res.solver = opt.solver;
  res.machine = gpu ? gpu_machine(opt.backend) : machine_name();
  const std::string gpu_method = backend_name(opt.backend);
  // A configuration: the method, and the thread count on the CPU; each_scene: those every scene
  // runs (the sweep adds the all-pairs step to its small scenes).
  using Config = std::pair<std::string, int>;
  std::vector<Config> each_scene;
  if (gpu)
    each_scene.push_back({gpu_method, 1});
  else
    for (int t : opt.threads) each_scene.push_back({"grid", t});
  auto name = [&](const Config& c) { return gpu ? c.first : fmt::format("{} threads, {}", c.second, c.first); };
  // Runs a copy of `start` under one configuration; `prepare` sets the tool pose before each step.
  auto run = [&](const Model& model, const State& start, const Config& c, auto&& prepare) {
    State st = start;
    if (c.first == "all_pairs") return measure_all_pairs(model, st, opt, prepare);
    return measure(model, st, c.second, opt, prepare);
  };

  DentalSceneParams dental;
  dental.solver = opt.solver;
  const Scene paper = default_dental_scene(dental);  // the counts (the iisph solver's ball has 52)
  res.default_scene = paper.name;
  const State paper_start = make_state(paper);
  for (Role r : {Role::material, Role::boundary, Role::tool}) res.default_particles[role_name(r)] = paper_start.count(r);
  for (const Config& c : each_scene) {
    const Measured m =
        run(paper.model, paper_start, c, [&](State& s) { s.tool_pose = paper.tool.at(s.time + paper.model.dt); });
    res.default_steps_per_second[c.second] = m.steps_per_second;
    res.default_stage_us[c.second] = m.per_step;
    log(fmt::format("{}: {}: {:.0f} steps/s", paper.name, name(c), m.steps_per_second));
  }

  // The dental scene with one core kept busy by another thread: each thread count, and the
  // governor over all of them.
  if (!gpu && opt.busy_core) {
    const int most = *std::max_element(opt.threads.begin(), opt.threads.end());
    auto prepare = [&](State& s) { s.tool_pose = paper.tool.at(s.time + paper.model.dt); };
    BusyCore busy;
    for (int t : opt.threads) {
      State st = paper_start;
      const Measured m = measure(paper.model, st, t, opt, prepare);
      res.busy_core.push_back({fmt::format("{} thread{}", t, t == 1 ? "" : "s"), t, false, m.steps_per_second});
      log(fmt::format("{}, one core busy: {} threads: {:.0f} steps/s", paper.name, t, m.steps_per_second));
    }
    State st = paper_start;
    const Measured m = measure_governed(paper.model, st, most, opt, prepare);
    res.busy_core.push_back({fmt::format("governor, up to {}", most), most, true, m.steps_per_second});
    log(fmt::format("{}, one core busy: governor up to {} threads: {:.0f} steps/s", paper.name, most, m.steps_per_second));
  }

  // The dental scene on every registered solver (solver.hpp) at its dental time step: single runs
  // alternated, each solver in turn, `repeats` times for each thread count; the median of each.
  if (!gpu && opt.compare_solvers) {
    BenchOptions one = opt;
    one.repeats = 1;
    std::vector<Solver> both;
    for (const SolverEntry& e : registered_solvers()) both.push_back(e.key);
    std::map<Solver, std::pair<Scene, State>> scenes;  // each solver's scene and start, made once
    for (Solver s : both) {
      DentalSceneParams dp;
      dp.solver = s;
      Scene sc = default_dental_scene(dp);
      State st = make_state(sc);
      scenes.emplace(s, std::make_pair(std::move(sc), std::move(st)));
    }
    for (int t : opt.threads) {
      std::map<Solver, std::vector<double>> rates;
      for (int r = 0; r < std::max(1, opt.repeats); ++r)
        for (Solver s : both) {
          const Scene& sc = scenes.at(s).first;  // (not a structured binding: a lambda captures it)
          State st = scenes.at(s).second;
          rates[s].push_back(
              measure(sc.model, st, t, one, [&](State& x) { x.tool_pose = sc.tool.at(x.time + sc.model.dt); })
                  .steps_per_second);
        }
      for (Solver s : both) {
        std::vector<double>& v = rates[s];
        std::sort(v.begin(), v.end());
        const real dt = scenes.at(s).first.model.dt;
        const double sps = v[v.size() / 2];
        res.solvers.push_back({s, dt, t, sps, sps * dt});
        log(fmt::format("{}, {} solver at dt = {:.3g} s: {} threads: {:.0f} steps/s, {:.3f} s simulated per s", paper.name,
                        solver_name(s), dt, t, sps, sps * dt));
      }
    }
  }

  std::vector<SweepSize> sizes = opt.sweep;
  if (gpu) {
    sizes.clear();
    for (int side : opt.cuda_sweep_sides) sizes.push_back({side, 1});
  }
  for (const SweepSize& size : sizes) {
    Scene sc = sweep_cups_scene(size.side, size.cups, opt.sweep_grid_reach);
    if (opt.solver != sc.model.solver) select_solver(sc, opt.solver);
    State start = make_state(sc);
    const real neighbours = mean_neighbours(sc.model, start);  // sorts `start` by cell
    std::vector<Config> configs = each_scene;
    if (!gpu && opt.solver == Solver::paper && start.size() <= opt.all_pairs_max_particles)
      configs.push_back({"all_pairs", 1});
    for (const Config& c : configs) {
      const Measured m = run(sc.model, start, c, [](State&) {});
      res.sweep.push_back({size.cups, start.size(), moving_count(start), neighbours, c.first, c.second,
                           m.steps_per_second, m.per_step});
      if (c.first != "all_pairs") res.bytes_per_particle = m.bytes_per_particle;
      log(fmt::format("{} particles in {} cup{}, {}: {:.1f} steps/s", start.size(), size.cups, size.cups == 1 ? "" : "s",
                      name(c), m.steps_per_second));
    }
  }
  return res;
}

std::string bench_json(const BenchResult& r) {
  nlohmann::json j;
  j["machine"] = r.machine;
  j["backend"] = backend_name(r.backend);
  j["solver"] = solver_name(r.solver);
  nlohmann::json sps = nlohmann::json::object(), stages = nlohmann::json::object();
  for (const auto& [t, v] : r.default_steps_per_second) sps[std::to_string(t)] = v;
  for (const auto& [t, v] : r.default_stage_us) stages[std::to_string(t)] = stages_json(v);
  j["default_scene"] = {{"name", r.default_scene}, {"particles", r.default_particles}, {"steps_per_second", sps},
                        {"stage_us", stages}};
  j["sweep"] = nlohmann::json::array();
  for (const BenchRow& row : r.sweep)
    j["sweep"].push_back({{"cups", row.cups},
                          {"particles", row.particles},
                          {"moving_particles", row.moving},
                          {"neighbours", row.neighbours},
                          {"method", row.method},
                          {"threads", row.threads},
                          {"steps_per_second", row.steps_per_second},
                          {"stage_us", stages_json(row.stage_us)}});
  j["busy_core"] = nlohmann::json::array();
  for (const BusyCoreRow& row : r.busy_core)
    j["busy_core"].push_back({{"configuration", row.configuration},
                              {"threads", row.threads},
                              {"governor", row.governor},
                              {"steps_per_second", row.steps_per_second}});
  j["solvers"] = nlohmann::json::array();
  for (const SolverRow& row : r.solvers)
    j["solvers"].push_back({{"solver", solver_name(row.solver)},
                            {"dt_s", row.dt},
                            {"threads", row.threads},
                            {"steps_per_second", row.steps_per_second},
                            {"realtime_factor", row.realtime_factor}});
  j["bytes_per_particle"] = r.bytes_per_particle;
  return j.dump(2);
}

std::string bench_table(const BenchResult& r) {
  std::string out = fmt::format("machine: {}\n\n{} (", r.machine, r.default_scene);
  for (const auto& [role, n] : r.default_particles) out += fmt::format("{} {}, ", n, role);
  out += "particles)\n";
  for (const auto& [t, v] : r.default_steps_per_second) {
    const StageTimes& st = r.default_stage_us.at(t);
    const std::string who = r.backend != Backend::cpu ? std::string(backend_name(r.backend)) : fmt::format("{} threads", t);
    const double density = st.density_us + st.pressure_us;
    out += fmt::format("  {}: {:8.0f} steps/s  ({:.1f} us/step: density and pressure {:.1f}, forces and bonds {:.1f}, other {:.1f})\n",
                       who, v, st.total_us(), density, st.forces_us, st.total_us() - density - st.forces_us);
  }
  if (!r.busy_core.empty()) {
    out += "  with one core kept busy by another thread:\n";
    for (const BusyCoreRow& row : r.busy_core)
      out += fmt::format("  {}: {:8.0f} steps/s\n", row.configuration, row.steps_per_second);
  }
  if (!r.solvers.empty()) {
    out += "  by solver (each at its dental time step, runs alternated):\n";
    out += fmt::format("  {:>8} {:>10} {:>8} {:>10} {:>24}\n", "solver", "dt (s)", "threads", "steps/s",
                       "simulated s per wall s");
    for (const SolverRow& row : r.solvers)
      out += fmt::format("  {:>8} {:>10.3g} {:>8} {:>10.0f} {:>24.3f}\n", solver_name(row.solver), row.dt, row.threads,
                         row.steps_per_second, row.realtime_factor);
  }
  // ns/moving: the time per material or tool particle. A single block's box takes a smaller share
  // of the particles the larger the block (static boundary particles cost less than moving ones),
  // so across blocks ns/particle mixes size and composition; across the cups (copies of one block)
  // the share is constant and ns/particle measures the size alone.
  out += fmt::format("\n{:>5} {:>10} {:>8} {:>10} {:>10} {:>8} {:>12} {:>12} {:>10}\n", "cups", "particles", "moving",
                     "neighbours", "method", "threads", "steps/s", "ns/particle", "ns/moving");
  for (const BenchRow& row : r.sweep)
    out += fmt::format("{:>5} {:>10} {:>8} {:>10.1f} {:>10} {:>8} {:>12.1f} {:>12.1f} {:>10.1f}\n", row.cups,
                       row.particles, row.moving, row.neighbours, row.method, row.threads, row.steps_per_second,
                       1e9 / (row.steps_per_second * row.particles), 1e9 / (row.steps_per_second * row.moving));
  out += fmt::format("\nmemory: {} bytes per particle\n", r.bytes_per_particle);
  return out;
}

}  // namespace dentsph
