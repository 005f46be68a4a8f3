// The built-in dental scene: a molar crown with a Class I cavity (include/dentsph/tooth.hpp),
// paste in the cavity, a ball tool. It needs no file.
#pragma once

#include <vector>

#include "dentsph/scene.hpp"
#include "dentsph/tooth.hpp"

namespace dentsph {

struct DentalSceneParams {
  real dt = 5e-5;                        // s
  int material_particles = 1600;         // the cavity's share first, the rest heaped above it
  Material paste{1.0, 10, 2000, 50};     // mu Pa s, Kp m^2/s^2, rho0 kg/m^3, Ka Pa
  Material wall{1.0, 15, 2000, 0};       // boundary and tool
};

// The default scene at default_tooth_spacing: about 1480 boundary particles lining the cavity,
// `material_particles` of paste, a 42-particle ball tool pressing in and lifting every 0.1 s.
Scene default_dental_scene(const DentalSceneParams& params = {});

}  // namespace dentsph
