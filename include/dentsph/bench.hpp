// `dentsph bench`: steps per second of the built-in dental scene for several thread counts, and a
// sweep over particle counts (grid and all-pairs, per-stage times), as a table and as JSON.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "dentsph/dental.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

struct BenchOptions {
  std::vector<int> threads{1, 2};                  // thread counts to measure
  std::vector<int> sweep_sides{8, 12, 16, 20, 26, 32, 40, 44};  // material blocks of side^3 particles
  std::uint32_t all_pairs_max_particles = 8000;    // the all-pairs step only up to this count
  int repeats = 5;                                 // runs per configuration; the median is kept
  double seconds_per_run = 0.25;                   // wall time of one run (at least 5 steps)
};

struct BenchRow {
  std::uint32_t particles = 0;
  real neighbours = 0;        // mean neighbours within h
  std::string method;         // grid | all_pairs
  int threads = 1;
  double steps_per_second = 0;  // median over the runs
  StageTimes stage_us;        // per step, from the median run
};

struct BenchResult {
  std::string default_scene;                    // default_dental_scene(): the paper's counts
  std::map<std::string, std::uint32_t> default_particles;  // per role
  std::map<int, double> default_steps_per_second;           // by thread count (median)
  std::map<int, StageTimes> default_stage_us;               // by thread count, per step
  std::vector<BenchRow> sweep;
  std::size_t bytes_per_particle = 0;           // of the largest sweep scene
  std::string machine;                          // CPU model and core count
};

// A cube of side^3 material particles (1 cm spacing) in an open container: the sweep's scenes.
Scene sweep_block_scene(int side);

BenchResult run_benchmarks(const BenchOptions& options, const std::function<void(const std::string&)>& log);
std::string bench_json(const BenchResult& result);
std::string bench_table(const BenchResult& result);

}  // namespace dentsph
