// The curing light, as an instrument: a light guide's exit window (a disk) and the beam it sends
// (docs/model.md, "Curing"). The beam is collimated: every point of the window sends light along
// `direction`, so a particle is lit when it lies in the cylinder the window sweeps forward, with
// the window's irradiance less what the paste, the tooth and the instrument in front of it absorb.
#pragma once

#include "dentsph/vec3.hpp"

namespace dentsph {

// Units people use for curing: irradiance in mW/cm^2, radiant exposure (dose) in J/cm^2.
inline constexpr real W_per_m2_per_mW_per_cm2 = 10;  // 1 mW/cm^2 = 10 W/m^2
inline constexpr real J_per_m2_per_J_per_cm2 = 1e4;  // 1 J/cm^2 = 1e4 J/m^2

struct CuringLight {
  Vec3 tip;                   // m, centre of the exit window
  Vec3 direction{0, 0, -1};   // where the beam goes (any non-zero length; normalised where used)
  real diameter = 10e-3;      // m, of the exit window (8 to 10 mm on dental lights)
  real irradiance = 1e4;      // W/m^2 at the window (1e4 = 1000 mW/cm^2)
  bool on = true;
};

}  // namespace dentsph
