// Fuzz target: procedure files on the built-in crown, as `dentsph run --procedure` reads them.
#include "dentsph/dental.hpp"
#include "fuzz_support.hpp"
#include "fuzz_targets.hpp"

namespace dentsph::fuzz {

int procedure(const std::uint8_t* data, std::size_t size) {
  static const ToothScene crown = default_tooth_scene();
  try {
    const Scene sc = dental_procedure(crown, text_of(data, size), "fuzz.json");
    (void)make_state(sc);
  } catch (const SceneError&) {
  }
  return 0;
}

}  // namespace dentsph::fuzz
