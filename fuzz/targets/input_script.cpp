// Fuzz target: the viewer's input scripts (dentsph-viewer --script).
#include "dentsph/scene.hpp"
#include "fuzz_support.hpp"
#include "fuzz_targets.hpp"
#include "input_script.hpp"

namespace dentsph::fuzz {

int input_script(const std::uint8_t* data, std::size_t size) {
  try {
    (void)viewer::parse_input_script(text_of(data, size), "fuzz.json");
  } catch (const SceneError&) {
  }
  return 0;
}

}  // namespace dentsph::fuzz
