// The paste's surface (dentsph/surface.hpp): one build of the built-in dental scene's paste, as the
// viewer's worker builds it every frame while the paste moves (docs/viewer.md) and a run builds it
// for every snapshot (docs/outputs.md), beside one step of the same scene.
#include <benchmark/benchmark.h>

#include <vector>

#include <tbb/task_arena.h>

#include "dentsph/dental.hpp"
#include "dentsph/dispense.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/surface.hpp"

namespace {

using namespace dentsph;

// The built-in scene's paste after `steps` steps (a settling heap, not the lattice it starts as).
std::vector<Vec3> settling_paste(int steps) {
  const Scene sc = default_dental_scene();
  Simulation sim(sc, {Backend::cpu, 2, false});
  for (int k = 0; k < steps; ++k) sim.step(sim.keyframe_pose());
  const State& st = sim.state();
  std::vector<Vec3> paste;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.is_paste(i)) paste.push_back(st.pos[i]);
  return paste;
}

void BM_PasteSurface(benchmark::State& bs) {
  static const std::vector<Vec3> paste = settling_paste(500);
  const real spacing = increment_spacing(default_dental_scene());
  std::size_t triangles = 0;
  tbb::task_arena one(1);  // on one thread, as the viewer's worker builds it
  for (auto _ : bs) {
    one.execute([&] {
      const SurfaceMesh m = particle_surface(paste, spacing);
      triangles = m.triangles.size();
    });
    benchmark::DoNotOptimize(triangles);
  }
  bs.counters["particles"] = double(paste.size());
  bs.counters["triangles"] = double(triangles);
}
BENCHMARK(BM_PasteSurface)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
