// `dentsph bench`: steps per second of the built-in dental scene for several thread counts, and a
// sweep over particle counts (grid and all-pairs, per-stage times), as a table and as JSON.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "dentsph/backend.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

// One scene of the CPU sweep: `cups` identical cups, each a cube of side^3 paste particles in its
// box (sweep_cups_scene).
struct SweepSize {
  int side = 16;
  int cups = 1;
};

struct BenchOptions {
  std::vector<int> threads{1, 2};                  // thread counts to measure
  // Two small single blocks (1600 and 3808 particles), then 1 to 14 cups of the side-16 block
  // (7488 to 104832 particles): the boundary's share stays that of one cup, so the cost per
  // particle along the cups measures the size alone.
  std::vector<SweepSize> sweep{{8, 1}, {12, 1}, {16, 1}, {16, 2}, {16, 4}, {16, 6}, {16, 11}, {16, 14}};
  std::uint32_t all_pairs_max_particles = 8000;    // the all-pairs step only up to this count
  int repeats = 5;                                 // runs per configuration; the median is kept
  double seconds_per_run = 0.25;                   // wall time of one run (at least 5 steps)
  // cuda (or cuda_emulation): a GPU backend instead of the CPU (one row per size, method "cuda", no
  // thread counts), over cuda_sweep_sides, which reach a million material particles and more.
  Backend backend = Backend::cpu;
  std::vector<int> cuda_sweep_sides{8, 16, 26, 40, 64, 80, 100, 126};
  int sweep_grid_reach = 1;  // the sweep scenes' grid: cells of h / reach, searched reach deep
  // CPU: the dental scene again with one core kept busy by a spinning thread, for each thread
  // count and for the ThreadGovernor (what a run does when another program takes a core).
  bool busy_core = true;
  // The step every scene runs: the dental scene at the solver's dental time step, the sweep at its
  // own; the all-pairs reference is the paper's step's and runs with it alone.
  Solver solver = Solver::paper;
  // CPU: the dental scene on each solver at its dental time step, for each thread count, the
  // solvers' runs alternated (paper, iisph, paper, ...): steps/s and simulated s per wall s.
  bool compare_solvers = true;
};

struct SolverRow {
  Solver solver = Solver::paper;
  real dt = 0;                 // s, the solver's dental time step
  int threads = 1;
  double steps_per_second = 0;  // median of the alternated runs
  double realtime_factor = 0;   // simulated s per wall s: steps_per_second * dt
};

struct BusyCoreRow {
  std::string configuration;  // "1 thread", "2 threads", "governor, up to 2"
  int threads = 1;            // the count, or the governor's largest
  bool governor = false;
  double steps_per_second = 0;
};

struct BenchRow {
  int cups = 1;               // copies of the cup in the scene (1 for a single block)
  std::uint32_t particles = 0;
  std::uint32_t moving = 0;   // of which material and tool (the rest is static boundary)
  real neighbours = 0;        // mean neighbours within h
  std::string method;         // grid | all_pairs | cuda | cuda-emulation
  int threads = 1;
  double steps_per_second = 0;  // median over the runs
  StageTimes stage_us;        // per step, from the median run
};

struct BenchResult {
  Solver solver = Solver::paper;                // the step measured
  std::string default_scene;                    // default_dental_scene(): the paper's counts
  std::map<std::string, std::uint32_t> default_particles;  // per role
  std::map<int, double> default_steps_per_second;           // by thread count (median)
  std::map<int, StageTimes> default_stage_us;               // by thread count, per step
  std::vector<BenchRow> sweep;
  std::vector<BusyCoreRow> busy_core;           // the dental scene with one core busy (CPU)
  std::vector<SolverRow> solvers;               // the dental scene on each solver (CPU)
  std::size_t bytes_per_particle = 0;           // of the largest sweep scene
  std::string machine;                          // CPU model and core count, or the GPU
  Backend backend = Backend::cpu;               // a GPU backend: default_* are keyed 1 (one GPU)
};

// `cups` identical cups, each a cube of side^3 material particles (1 cm spacing) in an open
// container of two wall layers, on a square-ish grid in x-y with gaps of 3.5 h and more between
// their walls: no two cups ever share a neighbour, nor a searched grid cell (the domain's wrap
// included). While the layout spans less than 2 m (up to 7 x 7 cups of side 16) the cups are
// copies bit for bit and, on grids of cells of h or h / 2, move alike bit for bit. The sweep's
// scenes.
Scene sweep_cups_scene(int side, int cups, int grid_reach = 1);
// One cup: the CUDA sweep's single blocks.
Scene sweep_block_scene(int side, int grid_reach = 1);

BenchResult run_benchmarks(const BenchOptions& options, const std::function<void(const std::string&)>& log);
std::string bench_json(const BenchResult& result);
std::string bench_table(const BenchResult& result);

}  // namespace dentsph
