// The lattice where paste is laid in a tooth's cavity: the built-in dental scene's paste
// (dental_default.cpp) and a procedure's increments (dental_procedure.cpp) take their sites here.
#pragma once

#include <vector>

#include "dentsph/tooth.hpp"

namespace dentsph::scene {

struct PasteSite {
  Vec3 local;               // m, tooth frame
  bool in_cavity = false;   // inside the removed tooth
  bool over_cavity = false; // above the occlusal reference with the column under it reaching into the cavity
};

// Points of the tooth frame's lattice of pitch s (offset half a pitch in z) that are half a
// spacing clear of the prepared tooth and inside the cavity's shape: in the cavity, or above the
// occlusal reference. In lattice order (z slowest, then y, then x); the lattice reaches two
// pitches beyond the cavity's bounds in every direction.
std::vector<PasteSite> paste_sites(const PreparedTooth& tooth, real s);

}  // namespace dentsph::scene
