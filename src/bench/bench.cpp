// The benchmark runner behind `dentsph bench`. Each configuration runs `repeats` times for about
// `seconds_per_run` of wall time after a warm-up; the median run's rate and stage times are kept.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <memory>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/bench.hpp"

namespace dentsph {

namespace {

struct Measured {
  double steps_per_second = 0;
  StageTimes per_step;
};

// Runs `state` for repeats x seconds_per_run; `prepare` sets the tool pose before each step.
template <class Prepare>
Measured measure(const Model& model, State& state, bool all_pairs, int threads, const BenchOptions& opt,
                 Prepare&& prepare) {
  auto one = [&](StageTimes* times) {
    prepare(state);
    if (all_pairs)
      step_all_pairs(model, state);
    else
      step(model, state, StepOptions{threads, times});
  };
  for (int k = 0; k < 10; ++k) one(nullptr);  // warm-up: first bonds, caches
  std::vector<Measured> runs;
  for (int r = 0; r < std::max(1, opt.repeats); ++r) {
    StageTimes t;
    const auto t0 = std::chrono::steady_clock::now();
    std::uint64_t steps = 0;
    double elapsed = 0;
    while (steps < 5 || elapsed < opt.seconds_per_run) {
      one(&t);
      ++steps;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    Measured m;
    m.steps_per_second = double(steps) / elapsed;
    for (double StageTimes::*f : {&StageTimes::hash_us, &StageTimes::sort_us, &StageTimes::reorder_us,
                                  &StageTimes::density_us, &StageTimes::pressure_us, &StageTimes::forces_us,
                                  &StageTimes::wrench_us, &StageTimes::integrate_us})
      m.per_step.*f = t.*f / double(steps);
    m.per_step.steps = steps;
    runs.push_back(m);
  }
  std::sort(runs.begin(), runs.end(),
            [](const Measured& a, const Measured& b) { return a.steps_per_second < b.steps_per_second; });
  return runs[runs.size() / 2];
}

// The CUDA backend: the step rate from graph replays (the haptic path), then the stage times from
// separately timed steps (each stage waited for, so slower than the replays).
template <class Prepare>
Measured measure_gpu(const Model& model, const State& initial, const BenchOptions& opt, Prepare&& pose_of) {
  std::unique_ptr<GpuStepper> gpu = make_gpu_stepper(opt.backend, model, initial);
  State st = initial;  // only its time and tool pose are read
  auto one = [&](StageTimes* times) {
    pose_of(st);
    times ? gpu->step_timed(st.tool_pose, *times) : gpu->step(st.tool_pose);
    st.time = gpu->time();
  };
  for (int k = 0; k < 10; ++k) one(nullptr);
  std::vector<double> rates;
  for (int r = 0; r < std::max(1, opt.repeats); ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    std::uint64_t steps = 0;
    double elapsed = 0;
    while (steps < 5 || elapsed < opt.seconds_per_run) {
      one(nullptr);
      ++steps;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    rates.push_back(double(steps) / elapsed);
  }
  std::sort(rates.begin(), rates.end());
  Measured m;
  m.steps_per_second = rates[rates.size() / 2];
  StageTimes t;
  for (int k = 0; k < 20; ++k) one(&t);
  for (double StageTimes::*f : {&StageTimes::hash_us, &StageTimes::sort_us, &StageTimes::reorder_us,
                                &StageTimes::density_us, &StageTimes::pressure_us, &StageTimes::forces_us,
                                &StageTimes::wrench_us, &StageTimes::integrate_us})
    m.per_step.*f = t.*f / double(t.steps);
  m.per_step.steps = t.steps;
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

// The pressure is part of the density pass on the CPU, so every backend reports the two together
// as "density" (the GPU's separate pressure kernel added in).
nlohmann::json stages_json(const StageTimes& t) {
  return {{"hash", t.hash_us},     {"sort", t.sort_us},     {"reorder", t.reorder_us},
          {"density", t.density_us + t.pressure_us},        {"forces", t.forces_us},
          {"wrench", t.wrench_us}, {"integrate", t.integrate_us},
          {"total", t.total_us()}};
}

// Material and tool particles: the ones the step moves.
std::uint32_t moving_count(const State& st) {
  return std::uint32_t(st.count(Role::material) + st.count(Role::tool));
}

}  // namespace

Scene sweep_block_scene(int side, int grid_reach) {
  constexpr real s = 0.01;
  Scene sc;
  sc.name = fmt::format("block_{}", side);
  sc.source = "built-in";
  const real ext = (side + 6) * s;
  sc.params.dt = 2e-4;
  sc.params.h = 2 * s;
  sc.params.adhesion.A = 1.2 * s;
  sc.params.adhesion.B = 3 * s;
  sc.params.domain_min = {-3 * s, -3 * s, -3 * s};
  sc.params.domain_max = {ext, ext, ext};
  sc.params.grid_reach = grid_reach;
  sc.model = make_model(sc.params);
  const real m = lattice_particle_mass(1000, s, sc.model.kernel);
  const Material paste{0.5, 60, 1000, 50}, wall{0.5, 200, 1000, 0};
  auto add = [&](Role role, Vec3 p, const Material& mat) { sc.particles.push_back(make_particle(role, p, m, mat)); };
  // A cube of side^3 material in an open container with two wall layers, one spacing away.
  for (int k = -2; k <= side + 1; ++k)
    for (int j = -2; j <= side + 1; ++j)
      for (int i = -2; i <= side + 1; ++i) {
        const bool inner = i >= 0 && i < side && j >= 0 && j < side && k >= 0;
        if (inner && k < side) add(Role::material, {i * s, j * s, k * s}, paste);
        if (!inner) add(Role::boundary, {i * s, j * s, k * s}, wall);
      }
  return sc;
}

// A GPU backend's benchmark: the dental scene, then the sweep up to millions of particles.
BenchResult run_gpu_benchmarks(const BenchOptions& opt, const std::function<void(const std::string&)>& log) {
  BenchResult res;
  res.backend = opt.backend;
  if (opt.backend == Backend::cuda) {
    const CudaStatus cs = cuda_status();
    if (!cs.available) throw CudaUnavailable(cs.reason);
    res.machine = cs.device;
  } else {
    res.machine = machine_name() + " (emulating the CUDA backend)";
  }
  const std::string method = backend_name(opt.backend);
  const Scene paper = default_dental_scene();
  res.default_scene = paper.name;
  const State st = make_state(paper);
  for (Role r : {Role::material, Role::boundary, Role::tool}) res.default_particles[role_name(r)] = st.count(r);
  const Measured m = measure_gpu(paper.model, st, opt, [&](State& s) { s.tool_pose = paper.tool.at(s.time + paper.model.dt); });
  res.default_steps_per_second[1] = m.steps_per_second;
  res.default_stage_us[1] = m.per_step;
  log(fmt::format("{}: {}: {:.0f} steps/s", paper.name, method, m.steps_per_second));
  for (int side : opt.cuda_sweep_sides) {
    const Scene sc = sweep_block_scene(side, opt.sweep_grid_reach);
    State probe = make_state(sc);
    const real neighbours = mean_neighbours(sc.model, probe);
    const State start = make_state(sc);
    const Measured r = measure_gpu(sc.model, start, opt, [](State&) {});
    res.sweep.push_back({start.size(), moving_count(start), neighbours, method, 1, r.steps_per_second, r.per_step});
    res.bytes_per_particle = start.bytes_per_particle();
    log(fmt::format("{} particles, {}: {:.1f} steps/s", start.size(), method, r.steps_per_second));
  }
  return res;
}

BenchResult run_benchmarks(const BenchOptions& opt, const std::function<void(const std::string&)>& log) {
  if (opt.backend != Backend::cpu) return run_gpu_benchmarks(opt, log);
  BenchResult res;
  res.machine = machine_name();

  const Scene paper = default_dental_scene();
  res.default_scene = paper.name;
  {
    const State st = make_state(paper);
    for (Role r : {Role::material, Role::boundary, Role::tool}) res.default_particles[role_name(r)] = st.count(r);
  }
  for (int t : opt.threads) {
    State st = make_state(paper);
    const Measured m = measure(paper.model, st, false, t, opt, [&](State& s) { s.tool_pose = paper.tool.at(s.time + paper.model.dt); });
    res.default_steps_per_second[t] = m.steps_per_second;
    res.default_stage_us[t] = m.per_step;
    log(fmt::format("{}: {} threads: {:.0f} steps/s", paper.name, t, m.steps_per_second));
  }

  for (int side : opt.sweep_sides) {
    const Scene sc = sweep_block_scene(side, opt.sweep_grid_reach);
    State probe = make_state(sc);
    const real neighbours = mean_neighbours(sc.model, probe);
    auto row = [&](const std::string& method, int t) {
      State st = make_state(sc);
      const Measured m = measure(sc.model, st, method == "all_pairs", t, opt, [](State&) {});
      res.sweep.push_back({st.size(), moving_count(st), neighbours, method, t, m.steps_per_second, m.per_step});
      res.bytes_per_particle = st.bytes_per_particle();
      log(fmt::format("{} particles, {} threads, {}: {:.1f} steps/s", st.size(), t, method, m.steps_per_second));
    };
    for (int t : opt.threads) row("grid", t);
    if (probe.size() <= opt.all_pairs_max_particles) row("all_pairs", 1);
  }
  return res;
}

std::string bench_json(const BenchResult& r) {
  nlohmann::json j;
  j["machine"] = r.machine;
  j["backend"] = backend_name(r.backend);
  nlohmann::json sps = nlohmann::json::object(), stages = nlohmann::json::object();
  for (const auto& [t, v] : r.default_steps_per_second) sps[std::to_string(t)] = v;
  for (const auto& [t, v] : r.default_stage_us) stages[std::to_string(t)] = stages_json(v);
  j["default_scene"] = {{"name", r.default_scene}, {"particles", r.default_particles}, {"steps_per_second", sps},
                        {"stage_us", stages}};
  j["sweep"] = nlohmann::json::array();
  for (const BenchRow& row : r.sweep)
    j["sweep"].push_back({{"particles", row.particles},
                          {"moving_particles", row.moving},
                          {"neighbours", row.neighbours},
                          {"method", row.method},
                          {"threads", row.threads},
                          {"steps_per_second", row.steps_per_second},
                          {"stage_us", stages_json(row.stage_us)}});
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
  // ns/moving: the time per material or tool particle. The sweep's blocks are paste in a box, and
  // the box's share of the particles falls as the block grows (static boundary particles cost
  // less than moving ones), so ns/particle rises with size even where ns/moving is flat.
  out += fmt::format("\n{:>10} {:>8} {:>10} {:>10} {:>8} {:>12} {:>12} {:>10}\n", "particles", "moving", "neighbours",
                     "method", "threads", "steps/s", "ns/particle", "ns/moving");
  for (const BenchRow& row : r.sweep)
    out += fmt::format("{:>10} {:>8} {:>10.1f} {:>10} {:>8} {:>12.1f} {:>12.1f} {:>10.1f}\n", row.particles, row.moving,
                       row.neighbours, row.method, row.threads, row.steps_per_second,
                       1e9 / (row.steps_per_second * row.particles), 1e9 / (row.steps_per_second * row.moving));
  out += fmt::format("\nmemory: {} bytes per particle\n", r.bytes_per_particle);
  return out;
}

}  // namespace dentsph
