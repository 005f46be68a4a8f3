// Fuzz target: tooth meshes, as `dentsph run --mesh` loads them (assimp, then the checks and
// repairs of src/tooth).
#include <string>

#include "dentsph/tooth.hpp"
#include "fuzz_support.hpp"
#include "fuzz_targets.hpp"

namespace dentsph::fuzz {

int mesh(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const formats[] = {"stl", "obj", "ply", "off"};  // off: refused by its name
  const std::filesystem::path f = scratch_dir() / (std::string("mesh.") + formats[data[0] % 4]);
  write_file(f, data + 1, size - 1);
  try {
    (void)load_mesh(f, data[0] & 4 ? MeshUnits::metres : MeshUnits::millimetres);
  } catch (const MeshError&) {
  }
  return 0;
}

}  // namespace dentsph::fuzz
