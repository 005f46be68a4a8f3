// The tool force over a run, accumulated by the Simulation once per step (simulation.hpp) and
// read by the filling's assessment (assess.hpp). The mean is taken over the time in contact
// (|F| > 0): the tool is lifted between presses, and an average over the whole run would mostly
// measure how long it was lifted.
#pragma once

#include "dentsph/vec3.hpp"

namespace dentsph {

struct ForceStats {
  real peak_N = 0;      // N, largest |F| seen
  real impulse_Ns = 0;  // N s, integral of |F| over time
  real contact_s = 0;   // s, time with |F| > 0
  real elapsed_s = 0;   // s, all time added

  // The force on the tool after a step of `dt` seconds.
  void add(const Vec3& force, real dt);
  real mean_N() const { return contact_s > 0 ? impulse_Ns / contact_s : 0; }  // N, in contact
};

}  // namespace dentsph
