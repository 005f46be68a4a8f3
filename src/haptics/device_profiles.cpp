// Force limits of the devices a person is likely to hold (manufacturers' continuous force).
#include <stdexcept>

#include "dentsph/haptics/device.hpp"

namespace dentsph {

DeviceProfile device_profile(const std::string& name) {
  if (name == "falcon") return {"falcon", 9.0, 1000};   // Novint Falcon: about 9 N
  if (name == "omega") return {"omega", 12.0, 1500};    // Force Dimension omega.3/6/7: 12 N
  if (name == "touch") return {"touch", 3.3, 500};      // 3D Systems Touch: 3.3 N
  throw std::invalid_argument("unknown device profile '" + name + "': use falcon (9 N), omega (12 N) or touch (3.3 N)");
}

}  // namespace dentsph
