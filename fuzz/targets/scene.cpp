// Fuzz target: scene files and dental scene files, as `dentsph validate` reads them.
#include "dentsph/run.hpp"
#include "dentsph/scene.hpp"
#include "fuzz_support.hpp"
#include "fuzz_targets.hpp"

namespace dentsph::fuzz {

int scene(const std::uint8_t* data, std::size_t size) {
  try {
    const Scene sc = parse_scene(text_of(data, size), "fuzz.json");
    const State st = make_state(sc);
    (void)check_time_step(sc, st, false);
  } catch (const SceneError&) {
  } catch (const UnstableTimeStep&) {
  }
  return 0;
}

}  // namespace dentsph::fuzz
