// Force limits and hard-contact settings of the devices a person is likely to hold
// (docs/haptics.md, "Device profiles", gives the source of each figure).
#include <stdexcept>

#include "dentsph/haptics/device.hpp"

namespace dentsph {

namespace {
DeviceProfile profile(const char* name, double max_force, double rate, double torque, double k, double b) {
  DeviceProfile p;
  p.name = name;
  p.max_force_N = max_force;
  p.max_force_rate_N_per_s = rate;
  p.max_torque_N_m = torque;
  p.contact.stiffness_N_per_m = k;
  p.contact.damping_N_s_per_m = b;
  return p;
}
}  // namespace

const char* device_profile_names() { return "falcon (9 N), omega (12 N), touch (3.3 N) or sigma7 (20 N, 0.4 N m)"; }

DeviceProfile device_profile(const std::string& name) {
  if (name == "falcon") return profile("falcon", 9.0, 1000, 0, 3000, 20);    // Novint Falcon
  if (name == "omega") return profile("omega", 12.0, 1500, 0, 5000, 30);     // Force Dimension omega.3/6/7
  if (name == "touch") return profile("touch", 3.3, 500, 0, 1000, 7);        // 3D Systems Touch
  if (name == "sigma7") return profile("sigma7", 20.0, 2000, 0.4, 5000, 30);  // Force Dimension sigma.7
  throw std::invalid_argument("unknown device profile '" + name + "': use " + device_profile_names());
}

}  // namespace dentsph
