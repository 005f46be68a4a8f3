// Google Benchmark: one step of a block of material in a container, grid step against the
// all-pairs reference, for growing particle counts (the paper's Fig. 3, on the CPU).
#include <benchmark/benchmark.h>

#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace {

using namespace dentsph;

constexpr real s = 0.01;

struct Setup {
  Model model;
  State state;
};

// A cube of n^3 material particles in an open container with two wall layers.
Setup block(int n) {
  const real ext = (n + 6) * s;
  Setup st{make_model(testing::params_for_spacing(s, {-3 * s, -3 * s, -3 * s}, {ext, ext, ext}, 2e-4, {0, 0, -9.81})),
           {}};
  const real m = lattice_particle_mass(1000, s, st.model.kernel);
  const Material paste{0.5, 60, 1000, 50}, wall{0.5, 200, 1000, 0};
  std::vector<ParticleInit> ps;
  for (Vec3 p : testing::lattice({0, 0, 0}, s, n, n, n)) ps.push_back(testing::particle(Role::material, p, m, paste));
  for (Vec3 p : testing::open_container({0, 0, 0}, s, n - 1, n - 1, n + 1, 2))
    ps.push_back(testing::particle(Role::boundary, p, m, wall));
  st.state.add_particles(st.model, ps);
  for (int k = 0; k < 20; ++k) step(st.model, st.state);  // settle the first transients
  return st;
}

void BM_GridStep(benchmark::State& bs) {
  Setup st = block(int(bs.range(0)));
  for (auto _ : bs) step(st.model, st.state);
  bs.counters["particles"] = st.state.size();
  bs.counters["steps_per_second"] = benchmark::Counter(double(bs.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_GridStep)->Arg(8)->Arg(12)->Arg(16)->Arg(24)->Arg(32)->Unit(benchmark::kMicrosecond);

void BM_AllPairsStep(benchmark::State& bs) {
  Setup st = block(int(bs.range(0)));
  for (auto _ : bs) step_all_pairs(st.model, st.state);
  bs.counters["particles"] = st.state.size();
  bs.counters["steps_per_second"] = benchmark::Counter(double(bs.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AllPairsStep)->Arg(8)->Arg(12)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
