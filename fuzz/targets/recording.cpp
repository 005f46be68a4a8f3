// Fuzz target: recordings, as `dentsph replay` and `--device replay` load them, replayed into a
// small scene when they hold a few steps.
#include <stdexcept>
#include <string>

#include "dentsph/haptics/recording.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/scene.hpp"
#include "fuzz_support.hpp"
#include "fuzz_targets.hpp"

namespace dentsph::fuzz {

namespace {

const Scene& small_scene() {
  static const Scene sc = parse_scene(R"({
    "name": "fuzz_replay",
    "simulation": {"dt": 5e-4, "h": 0.02},
    "adhesion": {"A": 0.012, "B": 0.03},
    "materials": {"paste": {"viscosity": 0.5, "stiffness": 60, "rest_density": 1000, "adhesion": 200}},
    "roles": {"material": "paste", "boundary": "paste", "tool": "paste"},
    "blocks": [{"role": "material", "shape": "box", "min": [0, 0, 0], "max": [0.02, 0.02, 0.02], "spacing": 0.01}],
    "tool": {"blocks": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.01, "spacing": 0.01}],
             "keyframes": [{"t": 0, "position": [0, 0, 0.05]}],
             "events": [{"t": 0.001, "dispense": {"volume": 1e-6, "at": [0, 0, 0.04]}}]}
  })", "fuzz_replay");
  return sc;
}

}  // namespace

int recording(const std::uint8_t* data, std::size_t size) {
  static const char* const names[] = {"haptic.csv", "steps.csv", "events.csv", "session.json"};
  const std::filesystem::path dir = scratch_dir() / "recording";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::size_t start = 0;
  for (int part = 0; part < 4 && start <= size; ++part) {
    std::size_t end = start;
    while (end < size && data[end] != 0) ++end;
    write_file(dir / names[part], data + start, end - start);
    start = end + 1;
  }
  try {
    const Recording r = load_recording(dir);
    if (r.steps.size() <= 8) (void)replay_steps(small_scene(), r, 1);
  } catch (const std::runtime_error&) {
  }
  return 0;
}

}  // namespace dentsph::fuzz
