// Google Benchmark: the hard contact's cost on the haptic thread, one tick of HardContact::update
// with the built-in crown's contact field and the ball burnisher (its particles and shank), in air
// above the crown, held 1 mm into the enamel beside the cavity, and held on set paste in the
// cavity; and the contact loop's rebuild of the field's particle grid (ContactField::set_particles)
// for that set paste. Results: bench/results, docs/performance.md.
#include <benchmark/benchmark.h>

#include <vector>

#include "dentsph/contact.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics/device.hpp"
#include "dentsph/tools.hpp"

namespace {

using namespace dentsph;

struct Crown {
  Scene scene = default_dental_scene();
  ContactField field = scene_contact_field(scene);
  ContactShape shape;
  std::vector<Vec3> slab;  // set paste: three layers on the cavity floor, its top 1.25 mm below the reference
  Crown() {
    const real s = scene.material_spacing;
    shape = instrument_contact_shape(tool_by_name("ball_burnisher", s, Solver::iisph).points, s);
    const ToothFrame& f = scene.tooth->frame();
    for (real z = -1.25e-3 - 2 * s; z <= -1.25e-3 + 1e-9; z += s)
      for (real y = -3e-3; y <= 3e-3; y += s)
        for (real x = -3e-3; x <= 3e-3; x += s) {
          const Vec3 p = f.to_world({x, y, z});
          if (scene.tooth->in_cavity(p) && scene.tooth->distance(p).distance > 0.5 * s) slab.push_back(p);
        }
  }
};

const Crown& crown() {
  static const Crown c;
  return c;
}

// Ticks of a device held at `hold` (tooth frame), reached from `from` at 20 mm/s first.
void hold_ticks(benchmark::State& bs, const ContactField& field, Vec3 from, Vec3 hold) {
  const Crown& c = crown();
  const ToothFrame& f = c.scene.tooth->frame();
  HardContact contact(device_profile("falcon").contact);
  const Vec3 a = f.to_world(from), b = f.to_world(hold);
  contact.reset(a);
  const int approach = int(norm(b - a) / 20e-6) + 1;
  for (int k = 1; k <= approach; ++k) contact.update(field, c.shape, a + (b - a) * (real(k) / approach), {}, {});
  bool touching = false;
  for (auto _ : bs) {
    const ContactResult& r = contact.update(field, c.shape, b, {}, {});
    touching = r.touching;
    benchmark::DoNotOptimize(r.force_N);
  }
  bs.counters["touching"] = touching ? 1 : 0;
  bs.counters["spheres"] = double(c.shape.spheres.size());
}

void BM_ContactTickInAir(benchmark::State& bs) { hold_ticks(bs, crown().field, {0, 0, 8e-3}, {0, 0, 6e-3}); }
BENCHMARK(BM_ContactTickInAir)->Unit(benchmark::kMicrosecond);

void BM_ContactTickOnEnamel(benchmark::State& bs) {
  // Beside the cavity (y 2.6 mm), pressed well past the surface: the proxy on the enamel.
  hold_ticks(bs, crown().field, {0, 2.6e-3, 6e-3}, {0, 2.6e-3, -1e-3});
}
BENCHMARK(BM_ContactTickOnEnamel)->Unit(benchmark::kMicrosecond);

void BM_ContactTickOnSetPaste(benchmark::State& bs) {
  ContactField field = crown().field;
  field.set_particles(crown().slab);
  hold_ticks(bs, field, {0, 0, 3e-3}, {0, 0, -2e-3});
}
BENCHMARK(BM_ContactTickOnSetPaste)->Unit(benchmark::kMicrosecond);

// The contact loop's work when paste set: the particle grid made again.
void BM_ContactFieldRebuild(benchmark::State& bs) {
  ContactField field = crown().field;
  for (auto _ : bs) field.set_particles(crown().slab);
  bs.counters["particles"] = double(crown().slab.size());
}
BENCHMARK(BM_ContactFieldRebuild)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
